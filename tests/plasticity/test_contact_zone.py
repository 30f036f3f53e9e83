"""Never a silent answer: a contact that reaches the edge of its candidate zone grows the mesh
(the path is solved again on a larger one) or stops the run with one clear line."""

from __future__ import annotations

import math

import pytest

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fem.mesh import MeshSpec
from coathertz.fem.plastic.method import ZONE_FILL_MAX, reference_radius, solve_plastic
from coathertz.materials import Body, Material, Plasticity

Y, R, NU = 1e9, 0.01, 0.3
STEEL_J2 = Material(200e9, NU, plasticity=Plasticity(Y))
TINY = MeshSpec(n_a=8, r_fine=2.0, t_fine=1.0, growth=1.5, L=15.0)
CASE = ContactCase(Body.rigid_sphere(R), Body.half_space(STEEL_J2), 10.0)
# Kogut & Etsion (2002): K = 0.454 + 0.41 nu, H = 2.8 Y, delta_c = (pi K H / (2 E*))^2 R,
# P_c = (4/3) (R / E*)^2 (pi K H / 2)^3, P / P_c = 1.03 (delta / delta_c)^1.425 (1 <= delta/delta_c <= 6)
K_KE, H_KE = 0.454 + 0.41 * NU, 2.8 * Y
DELTA_C = (math.pi * K_KE * H_KE / (2 * STEEL_J2.E_star)) ** 2 * R
P_C = 4.0 / 3.0 * (R / STEEL_J2.E_star) ** 2 * (math.pi * K_KE * H_KE / 2) ** 3
DELTA = 5.0 * DELTA_C
P_KE = 1.03 * 5.0**1.425 * P_C


def test_mesh_is_sized_from_the_approach():
    """Approach control sizes the mesh from delta_max (the case's W = 10 N would give ~ 60 um)."""
    a = reference_radius(CASE.W, R, STEEL_J2.E_star, Y, DELTA)
    assert a == pytest.approx(math.sqrt(2 * R * DELTA)), a
    res = solve_plastic(CASE, mesh=TINY, n_steps=5, delta_max=DELTA)
    assert res.meta["zone_growths"] == []
    a_end = res.curves["a"][-1]
    assert a_end < ZONE_FILL_MAX * TINY.r_fine * res.meta["a_ref"]
    # tiny mesh (8 elements across a_ref), 5 increments: within 5 % of Kogut & Etsion at 5 delta_c
    assert res.curves["W"][-1] == pytest.approx(P_KE, rel=0.05), (res.curves["W"][-1], P_KE)


def test_contact_at_the_zone_edge_grows_the_mesh():
    """A mesh sized for half the contact: the contact reaches the zone's edge, the path is solved
    again on a grown mesh and the load agrees with the well-sized run (discretisation: 2 %)."""
    a0 = 0.5 * reference_radius(CASE.W, R, STEEL_J2.E_star, Y, DELTA)
    res = solve_plastic(CASE, mesh=TINY, n_steps=5, delta_max=DELTA, a_ref=a0)
    assert len(res.meta["zone_growths"]) >= 1
    assert res.meta["a_ref"] > 1.4 * a0
    assert res.curves["a"][-1] < ZONE_FILL_MAX * TINY.r_fine * res.meta["a_ref"]
    assert res.curves["W"][-1] == pytest.approx(P_KE, rel=0.05), (res.curves["W"][-1], P_KE)


def test_contact_at_the_zone_edge_stops_with_one_line():
    a0 = 0.5 * reference_radius(CASE.W, R, STEEL_J2.E_star, Y, DELTA)
    with pytest.raises(CoatHertzError, match=r"candidate zone .*stopped after 0 mesh growth") as ei:
        solve_plastic(CASE, mesh=TINY, n_steps=5, delta_max=DELTA, a_ref=a0, max_growths=0)
    assert "\n" not in str(ei.value)


@pytest.mark.parametrize("bad", [-1, 11, 1.5])
def test_max_growths_validated(bad):
    with pytest.raises(CoatHertzError, match="max_growths"):
        solve_plastic(CASE, mesh=TINY, n_steps=2, max_growths=bad)


def _jackson_green(delta: float, E_star: float, Y_: float, nu: float, R_: float) -> float:
    """Jackson & Green (2005) load of a rigid flat on a sphere (eqs 9, 10, 17, 18, 21)."""
    C = 1.295 * math.exp(0.736 * nu)
    dc = (math.pi * C * Y_ / (2 * E_star)) ** 2 * R_
    Pc = 4.0 / 3.0 * (R_ / E_star) ** 2 * (C * math.pi * Y_ / 2) ** 3
    x, ey = delta / dc, Y_ / E_star
    B = 0.14 * math.exp(23 * ey)
    HG = 2.84 * (1 - math.exp(-0.82 * (math.pi * C * ey / 2 * math.sqrt(x) * (x / 1.9) ** (B / 2)) ** -0.7))
    elastic = math.exp(-0.25 * x ** (5 / 12)) * x**1.5
    plastic = 4 * HG / C * (1 - math.exp(-x ** (5 / 9) / 25)) * x
    return (elastic + plastic) * Pc


@pytest.mark.slow
def test_readme_approach_example_gives_the_published_load():
    """README: ``coathertz fem example:yielding_steel --plastic --approach "20 um"`` (delta/delta_c
    = 15.0): within 5 % of Kogut & Etsion (1.40 (delta/delta_c)^1.263 P_c = 1931 N) and of
    Jackson & Green (1993 N). Measured: 1926 N (default mesh, 10 increments); was 982 N when the
    candidate zone was sized from the case's W."""
    from coathertz.casefile import load_case

    case = load_case("example:yielding_steel")
    res = solve_plastic(case, n_steps=10, delta_max=20e-6)
    W = res.curves["W"][-1]
    P_ke = 1.40 * (20e-6 / DELTA_C) ** 1.263 * P_C
    P_jg = _jackson_green(20e-6, STEEL_J2.E_star, Y, NU, R)
    assert W == pytest.approx(P_ke, rel=0.05), (W, P_ke)
    assert W == pytest.approx(P_jg, rel=0.05), (W, P_jg)
    assert 1870 <= W <= 1930, W
    assert res.meta["zone_growths"] == []
