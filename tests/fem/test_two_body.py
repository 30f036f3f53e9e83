"""Elastic indenter on a different elastic body: both bodies meshed."""

from __future__ import annotations

from importlib.resources import files

import pytest

from coathertz.case import ContactCase
from coathertz.casefile import load_case
from coathertz.errors import CoatHertzError
from coathertz.fem.method import FEMMethod
from coathertz.materials import Body, Material

STEEL = Material(200e9, 0.3)
ALUMINIUM = Material(70e9, 0.33)


def test_steel_ball_on_aluminium_is_hertz():
    """Two different homogeneous bodies: exact Hertz with the pair's E* (eq 2). Measured at the
    coarse mesh: delta -4.1e-5, a -4.4e-4, p0 +9.2e-5 (default: -1.5e-5, -1.7e-4, +1.9e-5)."""
    case = ContactCase(Body.sphere(STEEL, 0.01), Body.half_space(ALUMINIUM), 10.0)
    r = FEMMethod(mesh="coarse").solve(case)
    assert r.delta == pytest.approx(case.delta0s, rel=2e-4)
    assert r.a == pytest.approx(case.a0s, rel=1e-3)
    assert r.p0 == pytest.approx(case.p0s, rel=3e-4)
    swapped_case = ContactCase(Body.half_space(ALUMINIUM), Body.sphere(STEEL, 0.01), 10.0)
    swapped = FEMMethod(mesh="coarse").solve(swapped_case)  # the aluminium body is the indenter
    assert (swapped.delta, swapped.a) == pytest.approx((r.delta, r.a), rel=1e-9)


def test_section6_b4c_example_matches_fft():
    """Section 6, B4C coating (40 um) on steel, steel ball 10 mm, 1 N. DC-FFT at 128^2 (used here
    only as the reference): FE - FFT measured delta -3.1e-5, a -6.2e-4, p0 +6.8e-6 at the coarse
    mesh (default mesh: +9.4e-6, -1.9e-5, +9.3e-6; the FFT's own a errs ~ 1e-3)."""
    from coathertz.fft.method import FFTMethod

    case = load_case(files("coathertz") / "data" / "b4c_on_steel.toml")
    fe = FEMMethod(mesh="coarse").solve(case)
    ff = FFTMethod().solve(case)
    assert fe.delta == pytest.approx(ff.delta, rel=2e-4)
    assert fe.a == pytest.approx(ff.a, rel=2e-3)
    assert fe.p0 == pytest.approx(ff.p0, rel=3e-4)
    assert fe.meta["solver_stats"]["factorisations"] == 1


def test_indenter_needs_condensed_path():
    case = ContactCase(Body.sphere(STEEL, 0.01), Body.half_space(ALUMINIUM), 10.0)
    m = FEMMethod(mesh="coarse")
    m._reuse_factorisation = False
    with pytest.raises(CoatHertzError, match="condensed"):
        m.solve(case)
