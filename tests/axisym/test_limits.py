"""Exact limits of the axisymmetric method: Hertz (eq 1) for homogeneous bodies, a coating equal to
its substrate, H -> 0 and H -> infinity (Richardson-extrapolated), and the thin-layer asymptotics
on a rigid base (Winkler layer, Matthewson's incompressible layer, eq 10)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coathertz.axisym import AxisymMethod
from coathertz.closedform.hertz import hertz_circular
from coathertz.materials import RIGID, Material

from .conftest import STEEL, coated, homogeneous

M = AxisymMethod()


def rel(x, y):
    return abs(x / y - 1.0)


@pytest.mark.parametrize("indenter", [None, Material(200e9, 0.3), Material(70e9, 0.2)])
def test_homogeneous_is_hertz(indenter):
    case = homogeneous(indenter)
    r = M.solve(case)
    h = hertz_circular(case.W, case.R, case.E_star_s)
    assert rel(r.delta, h.delta0) < 1e-12
    assert rel(r.a, h.a0) < 1e-12
    assert rel(r.p0, h.p0) < 1e-12
    assert r.meta["r_p0"] == 0.0
    json.dumps(r.scalars(), allow_nan=False)  # strict JSON (store)
    # the pressure profile is eq (1d)
    rr = r.fields["r"]
    inside = rr <= r.a
    p_h = h.p0 * np.sqrt(np.clip(1 - (rr[inside] / r.a) ** 2, 0, None))
    assert np.max(np.abs(r.fields["pressure"][inside] - p_h)) < 1e-11 * h.p0


@pytest.mark.parametrize("H", [0.01, 0.3, 3.0])
def test_coating_equal_to_substrate_is_hertz(H):
    case = coated(1.0, H)
    r = M.solve(case)
    assert rel(r.delta, case.delta0s) < 1e-10
    assert rel(r.a, case.a0s) < 1e-10
    assert rel(r.p0, case.p0s) < 1e-10


def test_zero_thickness_is_substrate_hertz():
    case = coated(3.0, 1.0).with_thickness(0.0)
    r = M.solve(case)
    assert rel(r.delta, case.delta0s) < 1e-12 and rel(r.p0, case.p0s) < 1e-12


def _richardson(Hs, vals, power):
    """Limit of ``v(H) = v0 + c1 H^power + c2 H^(2 power)`` from three values (geometric H)."""
    x = np.asarray(Hs, dtype=float) ** power
    A = np.vander(x, 3, increasing=True)
    return np.linalg.solve(A, np.asarray(vals))[0]


@pytest.mark.parametrize("E", [0.25, 4.0])
def test_thin_coating_limit_is_substrate_hertz(E):
    """H -> 0: delta_bar and p_bar tend to 1 at first order in H, a_bar more slowly (observed
    order ~0.8: the edge boundary layer of width h); the exact H = 0 limit is tested above."""
    Hs = [0.04, 0.02, 0.01]
    res = [M.solve(coated(E, H)) for H in Hs]
    case = coated(E, 0.01)
    for q, ref, lo, hi in (("delta", case.delta0s, 0.8, 1.1), ("p0", case.p0s, 0.8, 1.1),
                           ("a", case.a0s, 0.6, 1.0)):
        dev = np.abs([getattr(r, q) / ref - 1.0 for r in res])
        order = np.polyfit(np.log(Hs), np.log(dev), 1)[0]
        assert lo < order < hi, f"{q}: |bar - 1| = {dev} at H = {Hs}: observed order {order:.2f}"
        assert dev[-1] < 0.03


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
@pytest.mark.parametrize("E", [0.25, 4.0])
def test_thick_coating_limit_is_coating_hertz(E, interface):
    """H -> inf: the solution tends to the coating's Hertz values like 1/H (Vorovich-type series);
    Richardson extrapolation in 1/H recovers eq (1) with Ec* to 1e-8."""
    Hs = [400.0, 800.0, 1600.0]
    m = AxisymMethod(interface=interface)
    res = [m.solve(coated(E, H)) for H in Hs]
    case = coated(E, 400.0)
    inv = [1.0 / H for H in Hs]
    for q, ref in (("delta", case.delta0c), ("a", case.a0c), ("p0", case.p0c)):
        v = [getattr(r, q) / ref for r in res]
        lim = _richardson(inv, v, 1.0)
        assert abs(lim - 1.0) < 1e-8, (q, v, lim)


def _winkler_deviation(interface, nu_c, Hs):
    """``delta/delta_W - 1`` and ``p0/p_W - 1`` against ``tau = h/a`` for thin layers on a rigid
    base; Winkler layer of modulus ``M`` (bonded: constrained modulus 2G(1-nu)/(1-2nu);
    frictionless: Ec*): ``delta_W = sqrt(W h / (pi R M))``, ``a^2 = 2 R delta``, ``p_W = M delta_W/h``."""
    m = AxisymMethod(interface=interface)
    taus, dd, dp = [], [], []
    for H in Hs:
        case = coated(0.0, H, nu_c=nu_c, substrate=RIGID)
        r = m.solve(case)
        co = case.body2.coating
        G = co.material.G
        Mw = 2 * G * (1 - nu_c) / (1 - 2 * nu_c) if interface == "bonded" else co.material.E_star
        d_w = math.sqrt(case.W * co.h / (math.pi * case.R * Mw))
        taus.append(co.h / r.a)
        dd.append(r.delta / d_w - 1)
        dp.append(r.p0 / (Mw * d_w / co.h) - 1)
    return np.array(taus), np.array(dd), np.array(dp)


@pytest.mark.parametrize(("interface", "nu_c", "order", "dev_max"), [
    ("bonded", 0.3, 2, 1e-4),       # compressible layer bonded to the base: O(tau^2)
    ("bonded", 0.0, 3, 2e-6),
    ("frictionless", 0.3, 3, 2e-6),  # laterally free layer: O(tau^3), any nu_c
    ("frictionless", 0.5, 3, 2e-6),
])
def test_rigid_base_thin_layer_is_winkler(interface, nu_c, order, dev_max):
    """Thin layers on a rigid base approach the Winkler layer; the deviation falls with the
    observed order in tau = h/a, and a cubic fit extrapolates to the Winkler values (tau -> 0)
    within 1e-6."""
    Hs = [0.02, 0.01, 0.005, 0.0025]
    taus, dd, dp = _winkler_deviation(interface, nu_c, Hs)
    for name, dev in (("delta", dd), ("p0", dp)):
        obs = np.polyfit(np.log(taus[-3:]), np.log(np.abs(dev[-3:])), 1)[0]
        lim = np.polyfit(taus, dev, 3)[-1]
        msg = (f"{interface} nu_c={nu_c} {name}: deviation {dev} at tau {taus}: observed order {obs:.2f}"
               f" (expected {order}), extrapolated {lim:.1e}")
        assert abs(obs - order) < 0.35 and np.all(np.abs(dev) < dev_max * 100), msg
        assert abs(dev[-1]) < dev_max and abs(lim) < 1e-6, msg


def test_rigid_base_incompressible_thin_layer_matthewson():
    """nu_c = 0.5 on a rigid base: the solution approaches Matthewson's eq (10) (whose leading
    term is the bonded incompressible thin layer, W = pi G a^6 / (32 R h^3), delta = a^2/(4R));
    the differences fall at first order in tau = h/a (the kernel stays finite at nu_c = 0.5)."""
    from coathertz.closedform.literature import matthewson_load

    errs, d_errs, taus = [], [], []
    for H in (0.05, 0.02, 0.01):
        case = coated(0.0, H, nu_c=0.5, substrate=RIGID)
        r = M.solve(case)
        co = case.body2.coating
        tau = co.h / r.a
        W_m = matthewson_load(r.a, case.R, tau, co.material.E, 0.5)
        errs.append(rel(W_m, case.W))
        d_errs.append(rel(r.delta, r.a**2 / (4 * case.R)))
        taus.append(tau)
    order = np.polyfit(np.log(taus), np.log(errs), 1)[0]
    d_order = np.polyfit(np.log(taus), np.log(d_errs), 1)[0]
    assert errs[-1] < 0.08 and 0.7 < order < 1.3, f"W vs eq (10): {errs} at tau {taus}: order {order:.2f}"
    assert d_errs[-1] < 0.16 and 0.7 < d_order < 1.3, f"delta: {d_errs} at tau {taus}: order {d_order:.2f}"


@pytest.mark.parametrize("E", [0.25, 4.0])
def test_frictionless_thin_coating_limit_is_substrate_hertz(E):
    """Frictionless interface, H -> 0: delta_bar -> 1 at first order in H."""
    m = AxisymMethod(interface="frictionless")
    Hs = [0.04, 0.02, 0.01]
    case = coated(E, 0.01)
    dev = np.abs([m.solve(coated(E, H)).delta / case.delta0s - 1 for H in Hs])
    order = np.polyfit(np.log(Hs), np.log(dev), 1)[0]
    assert dev[-1] < 0.03 and 0.8 < order < 1.2, f"|delta_bar - 1| = {dev} at H = {Hs}: order {order:.2f}"


@pytest.mark.parametrize("indenter", [Material(200e9, 0.3), Material(70e9, 0.2)])
@pytest.mark.parametrize("H", [0.01, 0.5])
def test_elastic_indenter_on_equal_coating_is_hertz(indenter, H):
    """Elastic sphere on a coating equal to its substrate: Hertz with the eq (2) modulus."""
    case = coated(1.0, H, indenter=indenter)
    r = M.solve(case)
    assert rel(r.delta, case.delta0s) < 1e-10 and rel(r.a, case.a0s) < 1e-10 and rel(r.p0, case.p0s) < 1e-10


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_two_identical_coated_balls_equal_half_moduli(interface):
    """Two identical coated balls (radius 2R each) have twice the compliance of one coated body
    (F depends on modulus ratios only), i.e. the same contact as a rigid sphere R on one coated
    half-space with both moduli halved (eq 18 applied to both bodies, exactly)."""
    from coathertz.case import ContactCase
    from coathertz.materials import Body, Coating

    co, sub, h = Material(406.25e9, 0.3), Material(200e9, 0.28), 12.336e-6
    two = ContactCase(Body.sphere(sub, 20e-3, Coating(co, h)), Body.sphere(sub, 20e-3, Coating(co, h)), 1.0)
    half = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(co.E / 2, co.nu), h,
                                                   Material(sub.E / 2, sub.nu))
    m = AxisymMethod(interface=interface)
    r2, r1 = m.solve(two), m.solve(half)
    assert rel(r2.delta, r1.delta) < 1e-12 and rel(r2.a, r1.a) < 1e-12 and rel(r2.p0, r1.p0) < 1e-12


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_similarity_scaling(interface):
    """Scaling every length (R, h) by s and the load by s^2 keeps the strains: delta and a scale
    by s, p0 is unchanged (exactly, up to round-off); a larger load moves deeper (monotone)."""
    from coathertz.case import ContactCase
    from coathertz.materials import Body, Coating

    def case(s, W):
        return ContactCase(Body.rigid_sphere(10e-3 * s),
                           Body.half_space(STEEL, Coating(Material(600e9, 0.2), 8e-6 * s)), W)

    m = AxisymMethod(interface=interface)
    r1, r2 = m.solve(case(1.0, 1.0)), m.solve(case(3.0, 9.0))
    assert rel(r2.delta, 3 * r1.delta) < 1e-11 and rel(r2.a, 3 * r1.a) < 1e-11
    assert rel(r2.p0, r1.p0) < 1e-11
    r3 = m.solve(case(1.0, 1.5))
    assert r3.delta > r1.delta and r3.a > r1.a and r3.p0 > r1.p0
