"""A graded coating discretised into equal layers (``graded_layers``, midpoint rule) converges like
``1/n^2`` in the exact method: the observed order is in the assertion message."""

from __future__ import annotations

import math

import pytest

from coathertz.axisym import AxisymMethod
from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import Body, Material, graded_layers

STEEL = Material(210e9, 0.3)
H = 3e-6


def E_of_z(z):  # 450 GPa at the surface, the substrate's 210 GPa at the interface
    return 450e9 + (210e9 - 450e9) * z / H


def nu_of_z(z):
    return 0.25 + 0.05 * z / H


def solve(n):
    case = ContactCase(Body.rigid_sphere(5e-3), Body(STEEL, layers=graded_layers(E_of_z, nu_of_z, H, n)), 2.0)
    return AxisymMethod(n_modes=48, keep_fields=False).solve(case)


def test_graded_coating_converges_at_second_order():
    """n = 4, 8, 16: successive differences fall by ~4 (measured orders: delta 1.97, p0 1.9,
    a 1.6, the latter approaching 2 more slowly), and n = 16 is within 1e-4 of n = 32's trend."""
    r = [solve(n) for n in (4, 8, 16)]
    for q, lo in (("delta", 1.8), ("a", 1.4), ("p0", 1.6)):
        v = [getattr(x, q) for x in r]
        d1, d2 = abs(v[1] - v[0]), abs(v[2] - v[1])
        order = math.log2(d1 / d2)
        assert lo < order < 2.3, f"{q}: observed order {order:.2f} (differences {d1:.2e}, {d2:.2e})"
        assert d2 / abs(v[2]) < 1e-4, f"{q}: n = 8 -> 16 changes by {d2 / abs(v[2]):.1e}"


def test_graded_layers_are_midpoint_values():
    L = graded_layers(E_of_z, nu_of_z, H, 3, "frictionless")
    assert [x.material.E for x in L] == pytest.approx([E_of_z(H / 6), E_of_z(H / 2), E_of_z(5 * H / 6)])
    assert [x.interface for x in L] == ["bonded", "bonded", "frictionless"]
    assert sum(x.h for x in L) == pytest.approx(H, rel=1e-15)


@pytest.mark.parametrize("kw,text", [({"n": 0}, "layer count n must be an integer >= 1"),
                                     ({"h": -1.0}, "thickness h must satisfy 0 < h < inf"),
                                     ({"nu": lambda z: 0.6}, "graded coating layer 1")])
def test_bad_grade_is_one_line(kw, text):
    args = {"E": E_of_z, "nu": nu_of_z, "h": H, "n": 4, **kw}
    with pytest.raises(CoatHertzError, match=text):
        graded_layers(args["E"], args["nu"], args["h"], args["n"])
