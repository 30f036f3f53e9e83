"""Exact limits of the axisymmetric method: Hertz (eq 1) for homogeneous bodies, a coating equal to
its substrate, H -> 0 and H -> infinity (Richardson-extrapolated), and the thin-layer asymptotics
on a rigid base (Winkler layer, Matthewson's incompressible layer, eq 10)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import coated, homogeneous

from coathertz.axisym import AxisymMethod
from coathertz.hertz import hertz_circular
from coathertz.materials import RIGID, Material

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


@pytest.mark.parametrize("E", [0.25, 4.0])
def test_thick_coating_limit_is_coating_hertz(E):
    """H -> inf: the solution tends to the coating's Hertz values like 1/H (Vorovich-type series);
    Richardson extrapolation in 1/H recovers eq (1) with Ec* to 1e-8."""
    Hs = [400.0, 800.0, 1600.0]
    res = [M.solve(coated(E, H)) for H in Hs]
    case = coated(E, 400.0)
    inv = [1.0 / H for H in Hs]
    for q, ref in (("delta", case.delta0c), ("a", case.a0c), ("p0", case.p0c)):
        v = [getattr(r, q) / ref for r in res]
        lim = _richardson(inv, v, 1.0)
        assert abs(lim - 1.0) < 1e-8, (q, v, lim)


@pytest.mark.parametrize("nu_c", [0.0, 0.3, 0.45])
def test_rigid_base_thin_compressible_layer_is_winkler(nu_c):
    """Thin bonded compressible layer on a rigid base: u = p h (1 - 2 nu)/(2 G (1 - nu)),
    delta = sqrt(W h / (pi R M_c)), a^2 = 2 R delta, p0 = M_c delta / h; the relative
    error falls with tau = h/a."""
    errs, taus = [], []
    for H in (0.2, 0.1, 0.05):
        case = coated(0.0, H, nu_c=nu_c, substrate=RIGID)
        r = M.solve(case)
        co = case.body2.coating
        G = co.material.G
        Mc = 2 * G * (1 - nu_c) / (1 - 2 * nu_c)
        d_w = math.sqrt(case.W * co.h / (math.pi * case.R * Mc))
        errs.append(rel(r.delta, d_w))
        taus.append(co.h / r.a)
    order = np.polyfit(np.log(taus), np.log(errs), 1)[0]
    assert errs[-1] < 0.1 and order > 0.8, f"errors {errs} at tau {taus}: observed order {order:.2f}"


def test_rigid_base_incompressible_thin_layer_matthewson():
    """nu_c = 0.5 on a rigid base: the solution approaches Matthewson's eq (10) (whose leading
    term is the bonded incompressible thin layer, W = pi G a^6 / (32 R h^3), delta = a^2/(4R));
    the differences fall at first order in tau = h/a (the kernel stays finite at nu_c = 0.5)."""
    from coathertz.literature import matthewson_load

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


def test_rigid_base_thin_frictionless_layer_is_winkler():
    """Thin layer resting on a rigid base without friction: laterally free, u = p h / Ec*
    (F ~ t/2, independent of nu_c); delta -> sqrt(W h / (pi R Ec*)) as tau -> 0."""
    m = AxisymMethod(interface="frictionless")
    errs, taus = [], []
    for H in (0.2, 0.1, 0.05):
        case = coated(0.0, H, nu_c=0.5, substrate=RIGID)
        r = m.solve(case)
        co = case.body2.coating
        d_w = math.sqrt(case.W * co.h / (math.pi * case.R * co.material.E_star))
        errs.append(rel(r.delta, d_w))
        taus.append(co.h / r.a)
    order = np.polyfit(np.log(taus), np.log(errs), 1)[0]
    assert errs[-1] < 0.1 and order > 0.8, f"errors {errs} at tau {taus}: observed order {order:.2f}"
