"""Property-based checks of the extended Hertz predictor (hypothesis)."""

from __future__ import annotations

import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from coathertz import RIGID, Body, Coating, ContactCase, Material
from coathertz.closedform.alpha import BREAKPOINTS, Alphas
from coathertz.closedform.extended import predict

moduli = st.floats(5e9, 1e12)
poisson = st.floats(0.0, 0.49)
alphas = st.builds(Alphas, st.floats(0.2, 8.0), st.floats(0.2, 8.0), st.floats(0.2, 8.0))
loads = st.floats(0.01, 1e4)
radii = st.floats(1e-4, 0.1)
indenters = st.one_of(st.just(RIGID), st.builds(Material, moduli, poisson))


def _case(ind, R, sub, coat, h, W):
    return ContactCase(Body.sphere(ind, R) if not ind.is_rigid else Body.rigid_sphere(R),
                       Body.half_space(sub, Coating(coat, h)), W)


@settings(max_examples=60, deadline=None)
@given(moduli, poisson, indenters, radii, loads, st.floats(1e-3, 1e2), alphas)
def test_identical_coating_gives_hertz_exactly(E, nu, ind, R, W, H, al):
    m = Material(E, nu)
    case = _case(ind, R, m, m, 1.0, W)
    case = case.with_thickness(H * case.a0s)
    r = predict(case, al)
    assert (r.a, r.delta, r.p0) == pytest.approx((case.a0s, case.delta0s, case.p0s), rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(moduli, poisson, moduli, poisson, indenters, radii, loads, alphas)
def test_thin_and_thick_limits(Ec, nuc, Es, nus, ind, R, W, al):
    case = _case(ind, R, Material(Es, nus), Material(Ec, nuc), 1.0, W)
    thin = predict(case.with_thickness(1e-9 * case.a0s), al)
    assert (thin.a, thin.delta, thin.p0) == pytest.approx((case.a0s, case.delta0s, case.p0s), rel=1e-6)
    thick = predict(case.with_thickness(1e3 * case.a0s), al)
    assert (thick.a, thick.delta, thick.p0) == pytest.approx((case.a0c, case.delta0c, case.p0c), rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(moduli, poisson, st.floats(0.25, 4.0), poisson, radii, loads, st.floats(0.01, 3.0),
       st.floats(1e-3, 1e3), st.floats(1e-3, 1e3))
@example(7812500000.0, 0.25, 1.0, 0.0, 0.0859375, 2.0, 0.751, 1.0, 3.0)  # near the H = 0.75 jump
def test_depends_on_moduli_only_through_ratios(Es, nus, E_ratio, nuc, R, W, H, s_mod, s_load):
    """Scaling every modulus by s_mod and the load by s_load leaves the bars unchanged at fixed H.

    Except exactly at a breakpoint of the paper's piecewise Appendix A alpha curves: they jump
    there (alpha_p(3) at H = 0.75: 1.9348 -> 1.9367, :func:`coathertz.closedform.alpha.breakpoint_jumps`),
    and the round-off of H = h/a0s after scaling can land on either side (hypothesis found
    H = 0.75, s_load = 3: p0 bar off by 4.9e-5). Those H are excluded.
    """
    assume(all(abs(H / b - 1.0) > 1e-9 for bps in BREAKPOINTS.values() for b in bps))
    sub = Material(Es, nus)
    coat = Material(E_ratio * sub.E_star * (1 - nuc**2), nuc)

    def bars(scale, load):
        c = _case(RIGID, R, Material(sub.E * scale, nus), Material(coat.E * scale, nuc), 1.0, W * load)
        c = c.with_thickness(H * c.a0s)
        r = predict(c, warn=False)
        return r.a / c.a0s, r.delta / c.delta0s, r.p0 / c.p0s

    assert bars(s_mod, s_load) == pytest.approx(bars(1.0, 1.0), rel=1e-10)


@settings(max_examples=40, deadline=None)
@given(moduli, poisson, moduli, poisson, moduli, poisson, radii, radii, loads, st.floats(1e-7, 1e-4))
def test_swapping_bodies_changes_nothing(E1, nu1, Ec, nuc, Es, nus, R1, R2, W, h):
    b1 = Body.sphere(Material(E1, nu1), R1)
    b2 = Body.sphere(Material(Es, nus), R2, Coating(Material(Ec, nuc), h))
    al = Alphas(2.0, 1.0, 1.5)
    r12, r21 = predict(ContactCase(b1, b2, W), al), predict(ContactCase(b2, b1, W), al)
    assert (r12.a, r12.delta, r12.p0) == pytest.approx((r21.a, r21.delta, r21.p0), rel=1e-13)
