"""Classical Hertz, eqs (1)-(6): exact identities and independent formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ellipe, ellipk

from coathertz.closedform.hertz import (
    elliptic_factors,
    hertz_axis_stresses,
    hertz_circular,
    hertz_elliptical,
    radius_ratio,
    relative_radii,
    solve_zeta,
)
from coathertz.errors import CoatHertzError


def test_circular_identities():
    """delta0 = a0^2/R and W = (2/3) pi a0^2 p0 hold exactly for eq (1)."""
    W, R, E = 37.0, 7e-3, 123e9
    h = hertz_circular(W, R, E)
    assert h.delta0 == pytest.approx(h.a0**2 / R, rel=1e-14)
    assert 2 / 3 * math.pi * h.a0**2 * h.p0 == pytest.approx(W, rel=1e-14)
    assert h.p0 == pytest.approx(2 * h.a0 * E / (math.pi * R), rel=1e-14)


def test_equal_radii_give_circle():
    h = hertz_elliptical(10.0, 5e-3, 5e-3, 100e9)
    c = hertz_circular(10.0, 5e-3, 100e9)
    assert h.zeta == 1.0
    assert (h.F0, h.F1, h.F2) == pytest.approx((1.0, 1.0, 1.0), rel=1e-14)
    assert (h.a0, h.delta0, h.p0) == pytest.approx((c.a0, c.delta0, c.p0), rel=1e-14)
    assert h.r_a0 == h.r_b0 == pytest.approx(c.a0, rel=1e-14)


@pytest.mark.parametrize("zeta", [0.999, 0.9, 0.5, 1 / 3, 0.1, 0.01])
def test_carlson_forms_match_legendre_forms(zeta):
    """Eqs (4) and (6a) in Legendre form (scipy ellipk/ellipe, m = e^2) against our
    cancellation-free Carlson form; agreement limited by the Legendre form's cancellation."""
    m = 1 - zeta**2
    K, E = ellipk(m), ellipe(m)
    ratio = (E / zeta**2 - K) / (K - E)
    F0 = (4 / (math.pi * m) * math.sqrt((E / zeta**2 - K) * (K - E))) ** (1 / 3)
    tol = 1e-12 / max(m, 1e-3)
    assert radius_ratio(zeta) == pytest.approx(ratio, rel=tol)
    assert elliptic_factors(zeta)[0] == pytest.approx(F0, rel=tol)


def test_solve_zeta_inverts_eq4_to_1e4():
    q = np.geomspace(1.0, 1e4, 41)
    zeta = solve_zeta(q)
    assert np.all(np.diff(zeta) < 0)
    np.testing.assert_allclose(radius_ratio(zeta), q, rtol=1e-11)
    assert solve_zeta(1e8) > 0


def test_elliptical_identities():
    """Load balance W = (2/3) pi r_a r_b p0 and delta = p0 r_b K(e)/E* (Johnson 1985, sec 4.2),
    an independent expression of eq (5c)."""
    W, Rx, Ry, E = 400.0, 17.4e-3, 3e-3, 115e9
    h = hertz_elliptical(W, Rx, Ry, E)
    assert 2 / 3 * math.pi * h.r_a0 * h.r_b0 * h.p0 == pytest.approx(W, rel=1e-12)
    K = ellipk(1 - h.zeta**2)
    assert h.delta0 == pytest.approx(h.p0 * h.r_b0 * K / E, rel=1e-12)
    assert h.a0 == pytest.approx(math.sqrt(h.r_a0 * h.r_b0), rel=1e-14)
    # the paper's Section 5 example: 1/zeta "around 3.18"
    assert 1 / h.zeta == pytest.approx(3.18, abs=0.005)


def test_johnson_statement_zeta_one_third():
    """Section 1.2: at zeta = 1/3 the circular formulas with R = sqrt(Rx Ry) overestimate a0 and
    delta0 "by only 5 %" and underestimate p0 "by 8 %". Eq (6) gives 3.66 %, 3.79 % and 6.94 %:
    the direction and size agree with Johnson's rounded reading of his figure 4.4."""
    q = radius_ratio(1 / 3)
    e = hertz_elliptical(1.0, q, 1.0, 1.0)
    c = hertz_circular(1.0, math.sqrt(q), 1.0)
    over_a, over_d, under_p = c.a0 / e.a0 - 1, c.delta0 / e.delta0 - 1, 1 - c.p0 / e.p0
    assert over_a == pytest.approx(0.0366, abs=5e-4)
    assert over_d == pytest.approx(0.0379, abs=5e-4)
    assert under_p == pytest.approx(0.0694, abs=5e-4)
    assert 0.03 < over_a < 0.055 and 0.03 < over_d < 0.055 and 0.06 < under_p < 0.085


def test_relative_radii_eq3():
    # crossed cylinders at 90 degrees: a circular contact of radius R
    Rx, Ry = relative_radii(math.inf, 0.01, math.inf, 0.01, math.pi / 2)
    assert Rx == pytest.approx(0.01) and Ry == pytest.approx(0.01)
    # two spheres
    Rx, Ry = relative_radii(0.01, 0.01, 0.02, 0.02)
    assert Rx == Ry == pytest.approx(1 / (1 / 0.01 + 1 / 0.02))
    with pytest.raises(CoatHertzError, match="point contact"):
        relative_radii(math.inf, 0.01, math.inf, 0.01, 0.0)  # parallel cylinders: line contact


def test_axis_stresses_johnson_345():
    """Surface values and the maximum shear 0.31 p0 at z = 0.48 a (nu = 0.3), Johnson sec 3.4."""
    z = np.linspace(0, 3, 30001)
    sr, sz = hertz_axis_stresses(z, 1.0, 1.0, 0.3)
    assert sz[0] == pytest.approx(-1.0)
    assert sr[0] == pytest.approx(-(1 + 2 * 0.3) / 2)
    tau = 0.5 * np.abs(sz - sr)
    k = np.argmax(tau)
    assert tau[k] == pytest.approx(0.31, abs=0.005)
    assert z[k] == pytest.approx(0.48, abs=0.01)


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan")])
def test_bad_load_is_rejected(bad):
    with pytest.raises(CoatHertzError, match="W must satisfy"):
        hertz_circular(bad, 0.01, 1e9)


def test_scalar_fast_path_gives_the_array_path_bits():
    """One case (plain floats) takes a memoised fast path; 0-d arrays take the vectorised one:
    the same operations, hence the same numbers to the last bit (the report's numbers must not
    move), including a rigid pair (E* = inf), huge and tiny loads and very elongated contacts."""
    rng = np.random.default_rng(7)
    inputs = [(1.0, 0.01, 0.01, math.inf), (1e-9, 1e3, 1e-6, 1e15), (1e9, 1e-3, 1e-3, 1.0)]
    inputs += [tuple(float(v) for v in (10 ** rng.uniform(-3, 4), 10 ** rng.uniform(-4, 0),
                                         10 ** rng.uniform(-4, 0), 10 ** rng.uniform(8, 12)))
               for _ in range(200)]
    for W, Rx, Ry, E in inputs:
        fast = hertz_elliptical(W, Rx, Ry, E)
        slow = hertz_elliptical(*(np.asarray(v) for v in (W, Rx, Ry, E)))
        assert all(type(v) is float for v in vars(fast).values())
        assert vars(fast) == vars(slow), (W, Rx, Ry, E)
        R = math.sqrt(Rx * Ry)
        assert vars(hertz_circular(W, R, E)) == vars(hertz_circular(*(np.asarray(v) for v in (W, R, E))))
    with pytest.raises(CoatHertzError, match="E_star must satisfy"):
        hertz_elliptical(1.0, 0.01, 0.01, -1.0)  # bad scalars still worded by the array path
    with pytest.raises(CoatHertzError, match="Rx must satisfy"):
        hertz_elliptical(1.0, math.inf, 0.01, 1e9)
