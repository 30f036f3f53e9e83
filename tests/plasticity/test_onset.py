"""Elastic yield onset: homogeneous half-space under a rigid sphere against Johnson / Hertz."""

from __future__ import annotations

import pytest

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fem.method import FEMMethod
from coathertz.fem.plastic.onset import hertz_axis_onset, yield_onset
from coathertz.materials import Body, Coating, Material, Plasticity

Y = 1e9


def _case(W=10.0, nu=0.3):
    mat = Material(200e9, nu, plasticity=Plasticity(Y))
    return ContactCase(Body.rigid_sphere(0.01), Body.half_space(mat), W)


def test_closed_form_hertz_onset():
    p0, z = hertz_axis_onset(0.3)
    assert abs(p0 - 1.60) < 0.01 * 1.60 and abs(z - 0.48) < 0.01 * 0.48  # Johnson 1985, Section 6.2
    assert p0 == pytest.approx(1.6128, abs=1e-4) and z == pytest.approx(0.4809, abs=1e-4)


def test_homogeneous_onset_fe_matches_johnson_coarse():
    """Coarse mesh (20 elements across a): p0/Y within 0.1 %, depth within 2.5 % (measured:
    1.61269 vs 1.61280; z/a 0.4902 vs 0.4809, the location of a flat maximum converges slowly)."""
    o = yield_onset(_case(W=1000.0), FEMMethod(mesh="coarse"))
    p0_cf, z_cf = hertz_axis_onset(0.3)
    assert abs(o.p0_over_Y / p0_cf - 1) < 1e-3, o
    assert abs(-o.z / o.a_y / z_cf - 1) < 0.025, o
    assert o.r < 0.02 * o.a_y and o.where == "substrate" and o.solves <= 3


@pytest.mark.slow
def test_homogeneous_onset_fe_matches_johnson_default():
    """Default mesh (40 elements across a): p0/Y within 0.01 % and depth within 1 % of the Hertz
    closed form (measured: 1.61275 vs 1.61280; z/a 0.4781 vs 0.4809); 2 elastic solves, ~5 s."""
    o = yield_onset(_case(), FEMMethod(mesh="default"))
    p0_cf, z_cf = hertz_axis_onset(0.3)
    assert abs(o.p0_over_Y / p0_cf - 1) < 1e-4, o
    assert abs(-o.z / o.a_y / z_cf - 1) < 0.01, o


def test_coated_onset_location_and_bad_input():
    sub = Material(200e9, 0.3)
    case = ContactCase.sphere_on_coated_half_space(0.01, 40.0, Material(400e9, 0.3), 40e-6, sub)
    o = yield_onset(case, FEMMethod(mesh="coarse"), Yc=4e9, Ys=1e9)
    assert o.region == "substrate" and o.where in ("substrate", "interface")
    o_c = yield_onset(case, FEMMethod(mesh="coarse"), Yc=0.5e9, Ys=1e9)
    assert o_c.region == "coating" and o_c.W_y < o.W_y
    with pytest.raises(CoatHertzError, match="needs a yield stress"):
        yield_onset(ContactCase(Body.rigid_sphere(0.01), Body.half_space(sub), 1.0))
    with pytest.raises(CoatHertzError, match="Yc must satisfy"):
        yield_onset(case, Yc=-1.0)
    assert Coating  # imported for the reader: a coated body


def test_searches_sharing_their_solves_give_the_same_onsets():
    """Two searches of one elastic problem whose substrate yields first (Yc = 4 and 8 Ys: the
    coating's yield stress never binds) take the same steps: with ``solves`` shared the second
    solves nothing and both give exactly the numbers of an unshared search."""
    sub = Material(200e9, 0.3)
    case = ContactCase.sphere_on_coated_half_space(0.01, 40.0, Material(400e9, 0.3), 40e-6, sub)
    calls = []

    class Counting(FEMMethod):
        def solve_full(self, c, **kw):
            calls.append(c.W)
            return super().solve_full(c, **kw)

    m = Counting(mesh="coarse")
    alone = yield_onset(case, m, Yc=4e9, Ys=1e9)
    n_alone = len(calls)
    solves: dict = {}
    a = yield_onset(case, m, Yc=4e9, Ys=1e9, solves=solves)
    b = yield_onset(case, m, Yc=8e9, Ys=1e9, solves=solves)
    assert a == alone and (b.W_y, b.r, b.z, b.where) == (alone.W_y, alone.r, alone.z, alone.where)
    assert len(calls) == 2 * n_alone and len(solves) == n_alone  # the second search: no solve
