"""The elastic far field's static condensation (``fem/plastic/condense.py``) is exact: a load path
solved with it equals the path solved with the whole tangent factorised every iteration."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.fem.mesh import MeshSpec
from coathertz.fem.plastic.contact import NewtonSettings
from coathertz.fem.plastic.method import solve_plastic
from coathertz.materials import Body, Coating, Material, Plasticity

Y, R = 1e9, 0.01
STEEL_J2 = Material(200e9, 0.3, plasticity=Plasticity(Y))
SMALL = MeshSpec(n_a=8, r_fine=2.0, t_fine=1.0, growth=1.5, L=15.0)


@pytest.mark.parametrize("coated", [False, True])
def test_condensed_path_equals_whole_tangent_path(coated):
    """Approach control to 5 um (delta/delta_c ~ 3.8) and unloading, on yielding steel and on the
    same steel under an elastic 400 GPa coating 40 um thick (two regions, two laws): the plastic
    zone outgrows the first box, so the condensation is rebuilt at least once. Both paths take the
    same Newton iterations; every curve agrees to 1e-9 relative (the increments converge to
    rtol = 1e-9 and the two linear solves differ by round-off only: measured 3e-14 for W on the
    uncoated path)."""
    body = (Body.half_space(STEEL_J2, Coating(Material(400e9, 0.25), 40e-6)) if coated
            else Body.half_space(STEEL_J2))
    case = ContactCase(Body.rigid_sphere(R), body, 1.0)
    runs = [solve_plastic(case, mesh=SMALL, n_steps=3, delta_max=5e-6, unload=True,
                          newton=NewtonSettings(condense=c)) for c in (False, True)]
    full, cond = runs
    assert full.meta["linear_solves"]["condensed"] == 0
    ls = cond.meta["linear_solves"]
    assert ls["condensed"] > 0.8 * (ls["condensed"] + ls["full"]), ls
    assert ls["condensations"] >= 2, ls  # the box grew with the plastic zone
    assert full.curves["newton_iterations"] == cond.curves["newton_iterations"]
    assert max(cond.curves["ep_max"]) > 1e-3
    for k in ("W", "delta", "ep_max", "zone_depth"):
        a, b = np.array(full.curves[k], float), np.array(cond.curves[k], float)
        err = float(np.max(np.abs(a - b)) / np.max(np.abs(a)))
        assert err < 1e-9, f"{k}: condensed vs whole-tangent path differ by {err:.2e} (relative)"
    assert math.isclose(full.final["residual_depth"], cond.final["residual_depth"], rel_tol=1e-9, abs_tol=0)
