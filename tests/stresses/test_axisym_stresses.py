"""Stresses of the exact axisymmetric method (coathertz.axisym.stresses): Huber's closed form,
interface tractions, equilibrium, quadrature convergence and the FFT field on the same points."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numpy.polynomial import legendre as npleg

from coathertz.axisym.method import AxisymMethod
from coathertz.axisym.stresses import AxisymStresses, StackResponse, body_parts
from coathertz.case import ContactCase
from coathertz.casefile import load_example
from coathertz.errors import CoatHertzError
from coathertz.materials import RIGID, Body, Coating, Layer, Material
from coathertz.stress_methods import default_depths

from .huber import huber

STEEL = Material(200e9, 0.3)
HARD = Material(400e9, 0.25)
SOFT = Material(70e9, 0.3)
# round-off of the per-k linear solves and of the ~1e4-term Hankel sums: ~1e-14 p0 observed
ROUND = 1e-11


def _solve(body: Body, W: float = 100.0):
    case = ContactCase(Body.rigid_sphere(10e-3), body, W)
    return case, AxisymMethod().solve(case)


def _huber_field(r, z, a, nu, p0):
    with np.errstate(all="ignore"):  # Huber's surface branch evaluates both np.where arms
        sr, st, sz, trz = huber(r, z, a, nu)
    return np.array([sr, st, sz, trz]) * p0


@pytest.fixture(scope="module")
def homogeneous():
    case, res = _solve(Body.half_space(STEEL))
    return case, res, AxisymStresses(case, res)


def test_homogeneous_equals_huber(homogeneous):
    """Huber's closed form (Johnson eq 3.44-3.46), surface included (off the edge r = a, where
    Huber's formulas are 0/0): measured 1.8e-13 p0 at z = 0.01a, ~1e-14 p0 elsewhere. The limit is
    round-off (the quadrature is converged: see test_quadrature_converges)."""
    _, res, S = homogeneous
    a, p0 = res.a, res.p0
    r = np.linspace(0, 3, 61) * a
    r = r[np.abs(r - a) > 1e-6 * a]
    z = np.array([0, 0.01, 0.05, 0.2, 0.48, 1, 3]) * a
    F = S.field(r, z)
    for j, zj in enumerate(z):
        err = np.abs(F.sigma[j] - _huber_field(r, zj, a, STEEL.nu, p0)).max() / p0
        assert err < 1e-9, f"z = {zj / a:.3g} a: max |axisym - Huber| = {err:.2e} p0"


def test_homogeneous_known_maxima(homogeneous):
    """von Mises 0.620 p0 at z = 0.48a on the axis (nu = 0.3), surface radial tension
    (1 - 2 nu)/3 p0 at the edge r = a (the exact surface limit, not a quadrature)."""
    _, res, S = homogeneous
    a, p0 = res.a, res.p0
    z = np.linspace(0.40, 0.56, 161) * a
    F = S.field([0.0], z)
    rr, _tt, zz, _ = F.sigma[:, :, 0].T
    vm = np.abs(rr - zz)  # on the axis rr = tt, rz = 0
    i = int(np.argmax(vm))
    assert vm[i] / p0 == pytest.approx(0.6202, abs=2e-4) and z[i] / a == pytest.approx(0.481, abs=2e-3)
    edge = S.field([a], [0.0]).sigma[0, 0, 0] / p0
    assert edge == pytest.approx((1 - 2 * STEEL.nu) / 3, abs=1e-12)


@pytest.mark.parametrize("body", [
    Body(STEEL, Coating(STEEL, 30e-6)),
    Body(STEEL, layers=(Layer(STEEL, 10e-6), Layer(STEEL, 20e-6))),
], ids=["coating", "stack"])
def test_same_material_coating_equals_huber(body):
    """A coating (or a bonded stack) of the substrate's material: Huber's field again."""
    case, res = _solve(body)
    a, p0 = res.a, res.p0
    r = np.linspace(0, 3, 31) * a
    r = r[np.abs(r - a) > 1e-6 * a]
    z = np.array([0, 0.05, 30e-6 / a, 0.5, 1.5]) * a
    F = AxisymStresses(case, res).field(r, z)
    for j, zj in enumerate(z):
        err = np.abs(F.sigma[j] - _huber_field(r, zj, a, STEEL.nu, p0)).max() / p0
        assert err < 1e-9, f"z = {zj / a:.3g} a: max |coated(same) - Huber| = {err:.2e} p0"


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_interface_tractions(interface):
    """sigma_zz and sigma_rz continuous across the interface; sigma_rz = 0 on a frictionless
    one (both faces); the lateral stresses jump (the check is not trivially passed)."""
    h = 30e-6
    case, res = _solve(Body(STEEL, Coating(HARD, h, interface)))
    S = AxisymStresses(case, res)
    p0 = res.p0
    r = np.linspace(0, 3, 61) * res.a
    up = S.field(r, [h], side="above").sigma[0]
    dn = S.field(r, [h], side="below").sigma[0]
    for j, name in ((2, "zz"), (3, "rz")):
        jump = np.abs(up[j] - dn[j]).max() / p0
        assert jump < ROUND, f"sigma_{name} jumps by {jump:.2e} p0 across the {interface} interface"
    assert np.abs(up[0] - dn[0]).max() / p0 > 0.05  # sigma_rr jumps (measured 0.11 / 1.06 p0)
    if interface == "frictionless":
        shear = max(np.abs(up[3]).max(), np.abs(dn[3]).max()) / p0
        assert shear < ROUND, f"interface shear {shear:.2e} p0 on a frictionless interface"
    else:
        assert np.abs(up[3]).max() / p0 > 0.05  # measured 0.22 p0


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_rigid_base(interface):
    """On a rigid base: sigma_rz = 0 there if frictionless; below the layer the body ends."""
    h = 50e-6
    case, res = _solve(Body(RIGID, Coating(STEEL, h, interface)))
    S = AxisymStresses(case, res)
    base = S.field(np.linspace(0, 2, 21) * res.a, [h]).sigma[0]
    if interface == "frictionless":
        assert np.abs(base[3]).max() / res.p0 < ROUND
    else:
        assert np.abs(base[3]).max() / res.p0 > 0.05
    with pytest.raises(CoatHertzError, match="outside the body"):
        S.field([0.0], [1.01 * h])


def test_surface_boundary_conditions():
    case, res = _solve(Body(STEEL, Coating(SOFT, 20e-6)))
    S = AxisymStresses(case, res)
    r = np.linspace(0, 2, 41) * res.a
    F = S.field(r, [0.0])
    assert np.abs(F.sigma[0, 2] + S.pressure(r)).max() == 0.0
    assert np.abs(F.sigma[0, 3]).max() == 0.0


def _radial_rule(Rm, a, z):
    """Gauss rule on [0, Rm]: panels of width ~z/2 around the contact edge, then growing."""
    fine = np.linspace(max(a - 4 * z, 0), a + 4 * z, 17)
    edges = np.unique(np.concatenate([np.linspace(0, fine[0], 9), fine, np.geomspace(fine[-1], Rm, 24)]))
    zg, wg = npleg.leggauss(12)
    lo, hi = edges[:-1, None], edges[1:, None]
    return (0.5 * (hi - lo) * zg + 0.5 * (hi + lo)).ravel(), (0.5 * (hi - lo) * wg).ravel()


@pytest.mark.parametrize("body", [Body(STEEL, Coating(HARD, 30e-6)),
                                  Body(STEEL, Coating(SOFT, 20e-6, "frictionless"))],
                         ids=["hard-bonded", "soft-frictionless"])
def test_equilibrium(body):
    """int sigma_zz 2 pi r dr = -W at several depths (to r = 40a; the rest estimated with
    Boussinesq's far field -3 W z^3/(2 pi rho^5), which leaves an error of order
    (h/z) (z/40a)^3 < 2e-5)."""
    case, res = _solve(body)
    a, W = res.a, case.W
    S = AxisymStresses(case, res)
    Rm = 40 * a
    errs = []
    for z in np.array([0.05, 0.2, 0.5, 1.0]) * a:
        r, w = _radial_rule(Rm, a, z)
        sz = S.field(r, [z]).sigma[0, 2]
        tail = W * z**3 / (Rm**2 + z**2) ** 1.5
        errs.append(abs(-(sz * 2 * np.pi * r) @ w + tail - W) / W)
    # measured: 2e-8, 5e-7, 2.5e-6, 7.6e-6 (hard, bonded) and 4e-9 .. 4.8e-6 (soft, frictionless)
    # at z = 0.05, 0.2, 0.5, a: growing with z like the tail estimate's error
    assert max(errs) < 2e-5, f"|int sigma_zz dA + W| / W per depth: {np.array(errs)}"


def test_quadrature_converges():
    """Gauss nodes per xi panel at a fixed node density (panel width proportional to the order):
    the error falls geometrically, measured on b4c_on_steel 4.9e-7, 6.1e-11, 1.9e-14 p0 at 4, 6,
    8 nodes against 32 (about two decades per added node); the default (16) is at round-off."""
    case = load_example("b4c_on_steel")
    res = AxisymMethod().solve(case)
    a, p0, h = res.a, res.p0, case.body2.coating.h
    r = np.linspace(0, 2.5, 26) * a
    z = np.array([0, 0.05 * a, 0.5 * h, h, 0.5 * a, a])
    ref = AxisymStresses(case, res, order=32).field(r, z).sigma
    err = [np.abs(AxisymStresses(case, res, order=o).field(r, z).sigma - ref).max() / p0
           for o in (4, 6, 8, 16)]
    rate = [math.log10(err[i] / err[i + 1]) / 2 for i in range(2)]
    assert min(rate) > 1.0 and err[3] < ROUND, (
        f"errors at 4, 6, 8, 16 nodes: {np.array(err)}; decades per node {np.round(rate, 2)}")
    # the cut-off: e^{-20} already below 1e-9 p0
    e20 = np.abs(AxisymStresses(case, res, cut=20).field(r, z).sigma - ref).max() / p0
    assert e20 < 1e-9, f"cut = 20: {e20:.2e} p0"


def test_stack_response_matches_kernel():
    """The surface displacement of the stress solution equals the stack kernel's F(kh)
    (coathertz.stack, the definition shared with the FFT): the two are built independently."""
    from coathertz.axisym.stresses import _derivs, _state
    from coathertz.stack import StackLayer, stack_layer_factor

    layers = (Layer(HARD, 10e-6, "bonded"), Layer(SOFT, 5e-6, "frictionless"), Layer(STEEL, 20e-6))
    for sub in (Material(120e9, 0.35), RIGID):
        body = Body(sub, layers=layers)
        parts, substrate = body_parts(body, "bonded")
        R = StackResponse(parts, substrate)
        k = np.geomspace(1e2, 1e7, 60)
        c = R.coefficients(k)
        uz = np.einsum("jn,jn->n", _state(_derivs(0 * k, k * parts[0].h), HARD, HARD.G)[0], c[:, :4].T)
        F = 0.25 * HARD.E_star * uz / HARD.G  # u_z = 2 F / (E1* k); the row is 2 G_ref k u_z
        ref = stack_layer_factor([StackLayer(L.material, L.h, L.interface) for L in layers], sub, k)
        assert np.abs(F - ref).max() < 1e-10, f"max |F - stack F| = {np.abs(F - ref).max():.2e}"


def test_default_depths_and_bad_input(homogeneous):
    body = Body(STEEL, Coating(HARD, 30e-6))
    z = default_depths(body, 1e-4)
    assert z[0] == 0 and 30e-6 in z and z.max() == pytest.approx(3e-4)
    assert np.all(np.diff(z) > 0)
    _, res, S = homogeneous
    with pytest.raises(CoatHertzError, match="too close to the surface"):
        S.field([0.0], [1e-9 * res.a])
    with pytest.raises(CoatHertzError, match="side must be one of"):
        S.field([0.0], [res.a], side="middle")
    with pytest.raises(CoatHertzError, match="depth z = -1e-06 m outside the body"):
        S.field([0.0], [-1e-6])


# --- against the FFT field (src/coathertz/fft/stresses.py) ---------------------------------------


def _example(name: str) -> ContactCase:
    """``NAME`` or ``NAME:frictionless`` (the example's coating resting without friction)."""
    base, _, itf = name.partition(":")
    case = load_example(base)
    if itf:
        coat = dataclasses.replace(case.body2.coating, interface=itf)
        case = case.replace(body2=dataclasses.replace(case.body2, coating=coat))
    return case


@pytest.mark.parametrize("name", ["b4c_on_steel", "fig3_soft_coating", "rigid_substrate:frictionless"])
def test_fft_converges_to_exact(name):
    """FFT stresses (DC-FFT solution, pad 8) on the row y = 0 against the exact field at
    r <= 2a. Measured (max over r and components, / p0):

    ================  ====  ================  ===========  ==============
    case              n     z = 0.1a          interface h  z = 0.5a, a
    ================  ====  ================  ===========  ==============
    b4c_on_steel      64    2.3e-3            7.0e-5       1.2e-4, 6.8e-5
    b4c_on_steel      128   7.1e-4            5.0e-5       5.5e-5, 5.0e-5
    b4c_on_steel      256   1.4e-4            4.7e-5       5.0e-5, 4.7e-5
    fig3 (soft)       64    2.4e-3            1.8e-3       1.5e-4, 2.8e-4
    fig3 (soft)       128   9.0e-5            8.8e-5       1.4e-4, 2.8e-4
    fig3 (soft)       256   2.5e-5            1.7e-5       1.4e-4, 2.8e-4
    ================  ====  ================  ===========  ==============

    Near the surface the error falls with the cells (order ~2); deep down it stops at the
    FFT's finite-domain floor (1e-4 level, independent of the cells). With the FFT's default
    pad 4 that floor is 8.6e-4 p0 on b4c_on_steel (h ~ a: the image correction's w -> 0 limit).
    Rigid base, frictionless (h = 0.41a; z = 0.1a, h/2, h): 7.9e-4, 2.8e-4, 1.1e-4 at n = 64 and
    9.9e-5, 5.9e-5, 3.4e-5 at 128.
    """
    from coathertz.fft.method import FFTMethod
    from coathertz.fft.stresses import contact_stresses

    case = _example(name)
    res = AxisymMethod().solve(case)
    a, p0, h = res.a, res.p0, case.body2.coating.h
    S = AxisymStresses(case, res)
    z = np.array([0.1 * a, h, 0.5 * a, a])
    if case.body2.material.is_rigid:
        z = np.array([0.1 * a, 0.5 * h, h])
    errs = {}
    for n in (64, 128):
        rf = FFTMethod(n=n).solve(case)
        F = contact_stresses(case, rf, depths=z, pad=8)
        j = int(np.argmin(np.abs(F.y)))
        sel = (F.x >= 0) & (F.x <= 2 * a)
        exact = S.field(F.x[sel], z).voigt()[:, :, 0, :]
        errs[n] = np.abs(F.sigma[:, :, j, :][:, :, sel] - exact).max(axis=(1, 2)) / p0
    assert errs[128].max() < 0.005, f"n = 128: max |FFT - exact| / p0 per depth {errs[128]}"
    order = math.log2(errs[64][0] / errs[128][0])
    assert order > 1.0, (f"z = 0.1a: error {errs[64][0]:.2e} -> {errs[128][0]:.2e} p0 "
                         f"(n = 64 -> 128), observed order {order:.2f}")


def test_revolved_lattice_equals_huber(homogeneous):
    """The files' lattice (the exact field at every distinct radius, rotated to x, y): Huber's
    field in Cartesian components at every cell centre."""
    from coathertz.stress_methods import StressOptions, axisym_stresses

    case, res, _ = homogeneous
    a, p0 = res.a, res.p0
    out = axisym_stresses(case, StressOptions(grid=16, depths=(0.3 * a, a), lattice=True))
    x, y, z, sig = out.lattice
    X, Y = np.meshgrid(x, y)
    R, th = np.hypot(X, Y), np.arctan2(Y, X)
    c, s = np.cos(th), np.sin(th)
    for i, zi in enumerate(z):
        sr, st, sz, trz = _huber_field(R, zi, a, STEEL.nu, p0)
        ref = np.array([c * c * sr + s * s * st, s * s * sr + c * c * st, sz, s * trz, c * trz,
                        c * s * (sr - st)])
        err = np.abs(sig[i] - ref).max() / p0
        assert err < 1e-9, f"z = {zi / a:.2g} a: max |lattice - Huber| = {err:.2e} p0"


def _fig3_corner(E: float, H: float) -> ContactCase:
    """Fig. 3 corner: rigid sphere (10 mm, 100 N) on steel with a coating ``E = Ec/Es``,
    ``h = H a0`` (``a0`` the substrate's Hertz radius)."""
    from coathertz.closedform.hertz import hertz_circular

    a0 = hertz_circular(100.0, 10e-3, STEEL.E_star).a0
    return ContactCase(Body.rigid_sphere(10e-3), Body(STEEL, Coating(Material(E * 200e9, 0.3), H * a0)),
                       100.0)


@pytest.mark.parametrize(("E", "H", "pad"), [(0.25, 0.01, 4), (0.25, 3.0, 16), (4.0, 0.01, 4),
                                             (4.0, 3.0, 16)])
def test_fft_fig3_corners(E, H, pad):
    """FFT (64^2, its default period) against the exact field at z = 0.1a, 0.3a, 0.45a,
    r <= 1.5a on the corners of fig. 3. Measured (128^2, pad 8): 8e-5 .. 4e-4 p0, except for
    the thick coatings (h = 4.75a), where the lateral stresses carry a uniform error that only
    the period cures: 0.115 / 0.014 / 0.0013 p0 with pad 4 / 8 / 16 at E = 4 (the FFT's image
    correction takes the w -> 0 limit, the substrate's far field, while the period is ~2h:
    fft/stresses.py docstring). The default period (``image_pad``) now widens to 16 for them by
    itself; the thin ones keep 4 (their FFT grid is refined to 260^2 for the layer)."""
    from coathertz.fft.method import FFTMethod
    from coathertz.fft.stresses import contact_stresses

    case = _fig3_corner(E, H)
    res = AxisymMethod().solve(case)
    a, p0 = res.a, res.p0
    z = np.array([0.1, 0.3, 0.45]) * a
    rf = FFTMethod(n=64).solve(case)
    F = contact_stresses(case, rf, depths=z)
    assert F.meta["pad"] == pad, F.meta
    j = int(np.argmin(np.abs(F.y)))
    sel = (F.x >= 0) & (F.x <= 1.5 * a)
    exact = AxisymStresses(case, res).field(F.x[sel], z).voigt()[:, :, 0, :]
    err = np.abs(F.sigma[:, :, j, :][:, :, sel] - exact).max(axis=(1, 2)) / p0
    assert err.max() < 0.005, f"E = {E}, H = {H}: max |FFT - exact| / p0 per depth {err}"


def test_thin_layer_stresses_use_the_edge_functions():
    """A layer thinner than 0.0088 a is solved with edge functions (axisym/edge.py); the stresses
    rebuild that solution, edge functions included, and match the Legendre-only solution at 400
    modes to round-off. Measured at E = 4, h = 0.001 a0s: <= 1.1e-9 p0 from z = 0.02a to 0.5a,
    r <= 1.5a (the Legendre part alone, as before: 5e-6 to 2.2e-5 p0)."""
    steel = Material(200e9, 0.3)
    base = ContactCase(Body.rigid_sphere(0.01), Body.half_space(steel), 100.0)
    c = ContactCase(Body.rigid_sphere(0.01), Body(steel, Coating(Material(800e9, 0.3), 0.001 * base.a0s)),
                    100.0)
    r = AxisymMethod().solve(c)
    ref = AxisymMethod(n_modes=400, edge=False).solve(c)
    assert r.meta["n_edge"] > 0, r.meta
    rr = np.linspace(0.0, 1.5 * r.a, 31)
    zz = np.array([0.02, 0.1, 0.5]) * r.a
    d = np.abs(AxisymStresses(c, r).field(rr, zz).sigma - AxisymStresses(c, ref).field(rr, zz).sigma)
    err = d.max(axis=(1, 2)) / r.p0
    assert err.max() < 1e-8, f"max |edge - 400 modes| / p0 per depth {err}"
