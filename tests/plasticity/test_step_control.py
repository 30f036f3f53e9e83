"""Step control of the plastic path: onset-aware first step, explicit approach targets, unloading
under load control that ends where the contact is lost."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.errors import CoatHertzError
from coathertz.fem.mesh import MeshSpec
from coathertz.fem.plastic.method import _onset_target, solve_plastic
from coathertz.fem.plastic.onset import hertz_axis_onset
from coathertz.materials import Body, Coating, Material, Plasticity

Y, R = 1e9, 0.01
MAT = Material(200e9, 0.3, plasticity=Plasticity(Y))
TINY = MeshSpec(n_a=8, r_fine=2.0, t_fine=1.0, growth=1.5, L=15.0)
CASE = ContactCase(Body.rigid_sphere(R), Body.half_space(MAT), 10.0)


def test_onset_target_is_hertz_first_yield():
    """delta_y and W_y make Hertz's p0 = p0_y (Johnson eqs 4.22-4.23) for the body's nu."""
    d_y = _onset_target(Body.half_space(MAT), R, "approach")
    W_y = _onset_target(Body.half_space(MAT), R, "load")
    h = hertz_circular(W_y, R, MAT.E_star)
    assert h.p0 == pytest.approx(hertz_axis_onset(0.3)[0] * Y, rel=1e-12)
    assert h.a0**2 / R == pytest.approx(d_y, rel=1e-12)
    coated = Body.half_space(MAT, Coating(Material(400e9, 0.25), 1e-6))
    assert _onset_target(coated, R, "load") is None  # needs the elastic solution
    assert _onset_target(Body.half_space(Material(200e9, 0.3)), R, "load") is None


def test_approach_targets_onset_and_unloading_to_contact_loss():
    """Explicit approach targets to 4 delta_y: the first increment ends at first yield (elastic up
    to it), the targets are reached exactly; unloading runs in equal load steps from the largest
    load to W = 0, where the contact is lost and the path ends (no steps without contact)."""
    d_y = _onset_target(Body.half_space(MAT), R, "approach")
    targets = [2.0 * d_y, 3.0 * d_y, 4.0 * d_y]
    res = solve_plastic(CASE, mesh=TINY, delta_max=targets[-1], targets=targets, n_steps=4, unload=True)
    c = res.curves
    ph = np.array(c["phase"])
    d_load = np.array(c["delta"])[ph == "loading"]
    assert d_load[0] == pytest.approx(d_y, rel=1e-12)
    assert all(any(math.isclose(d, t, rel_tol=1e-12) for d in d_load) for t in targets)
    assert c["ep_max"][0] < 0.05 * c["ep_max"][1], c["ep_max"][:2]  # onset: at most a trace of flow
    W_un = np.array(c["W"])[ph == "unloading"]
    W_top = np.array(c["W"])[ph == "loading"][-1]
    assert len(W_un) == 4 and np.allclose(W_un, W_top * np.array([0.75, 0.5, 0.25, 0.0]), rtol=1e-9)
    a_un = np.array(c["a"])[ph == "unloading"]
    assert np.all(a_un[:-1] > 0) and a_un[-1] == 0.0
    assert res.final["residual_depth"] > 0
    assert res.meta["targets"]["onset_target"] == pytest.approx(d_y, rel=1e-12)


@pytest.mark.parametrize("bad", [[2e-6, 1e-6, 4e-6], [1e-6, 3e-6], [0.0, 4e-6]])
def test_bad_approach_targets_refused(bad):
    with pytest.raises(CoatHertzError, match="targets must increase"):
        solve_plastic(CASE, mesh=TINY, delta_max=4e-6, targets=bad)
