"""Incremental elastic-plastic indentation: load / unload / reload on a tiny mesh (fast), and the
homogeneous checks against the elastic onset and the mesh / increment convergence (slow)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.errors import ConvergenceError
from coathertz.fem.mesh import MeshSpec
from coathertz.fem.plastic.contact import NewtonSettings
from coathertz.fem.plastic.method import solve_plastic, write_vtu_series
from coathertz.materials import Body, Material, Plasticity

Y, R = 1e9, 0.01
STEEL_J2 = Material(200e9, 0.3, plasticity=Plasticity(Y))
TINY = MeshSpec(n_a=8, r_fine=2.0, t_fine=1.0, growth=1.5, L=15.0)
P0_Y = 1.6128  # Hertz onset, nu = 0.3 (tests/plasticity/test_onset.py)


def W_onset(mat: Material = STEEL_J2) -> float:
    """Load at which the Hertz p0 = 1.6128 Y (Johnson eq 4.23 inverted)."""
    p0 = P0_Y * Y
    return p0**3 * math.pi**3 * R**2 / (6.0 * mat.E_star**2)


def case(W: float, mat: Material = STEEL_J2) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R), Body.half_space(mat), W)


@pytest.fixture(scope="module")
def cycle():
    return solve_plastic(case(3.0 * W_onset()), mesh=TINY, n_steps=3, reload=True, keep_snapshots=True)


def test_unloading_is_elastic_and_reloading_retraces(cycle):
    c = cycle.curves
    ph = np.array(c["phase"])
    ep = np.array(c["ep_max"])
    W, d = np.array(c["W"]), np.array(c["delta"])
    assert ep[ph == "loading"][0] == 0.0 and ep[ph == "loading"][-1] > 1e-3  # elastic first, then plastic
    assert np.all(ep[ph != "loading"] == ep[ph == "loading"][-1]), "no new plastic strain after loading"
    un = {round(w, 9): x for w, x, p in zip(W, d, ph, strict=True) if p == "unloading" and w > 0}
    re = {round(w, 9): x for w, x, p in zip(W, d, ph, strict=True) if p == "reloading"}
    common = sorted(set(un) & set(re))
    assert len(common) >= 2
    for w in common:  # reloading retraces the unloading curve (elastic shakedown)
        assert abs(re[w] / un[w] - 1) < 1e-9, (w, re[w], un[w])
    assert abs(d[-1] / d[ph == "loading"][-1] - 1) < 1e-9  # back to the same approach at W_max
    assert cycle.final["residual_depth"] > 0.05 * d[ph == "loading"][-1]  # a permanent dent


def test_outputs_json_vtu_and_iterations(cycle, tmp_path):
    data = json.loads(json.dumps(cycle.to_json()))
    assert set(data["curves"]) >= {"W", "delta", "a", "p_max", "p_mean", "newton_iterations", "ep_max",
                                   "zone_r", "zone_depth"}
    res = cycle.final["residual"]
    for side in ("axis_sigma_rr", "axis_sigma_tt", "axis_von_mises"):
        assert np.all(np.isfinite(res["stresses"][side]))
    assert np.max(np.abs(res["stresses"]["axis_sigma_rr"])) > 0.05 * Y  # residual stresses are not small
    assert max(cycle.curves["newton_iterations"]) <= 8
    paths = write_vtu_series(cycle, tmp_path)
    assert len(paths) == len(cycle.curves["W"]) and paths[-1].stat().st_size > 0
    pvd = (tmp_path / "plastic.pvd").read_text()
    assert all(f'file="{p.name}"' in pvd for p in paths)
    import meshio

    k = int(np.argmax(cycle.curves["W"]))  # peak load: perfectly plastic, so q <= Y at every point
    m = meshio.read(paths[k])
    q, ep = m.cell_data["sigma_eq"][0], m.cell_data["ep"][0]
    assert q.max() <= Y * (1 + 1e-6), q.max() / Y
    assert q[ep > 0].max() >= 0.9 * Y, q[ep > 0].max() / Y  # yielded elements sit near the surface
    assert 0 < ep.max() <= cycle.curves["ep_max"][k] * (1 + 1e-12)
    assert set(m.cell_data) >= {"sigma_rr", "sigma_zz", "sigma_tt", "sigma_rz", "sigma_eq", "ep", "region"}


def test_plastic_increment_converges_quadratically():
    res = solve_plastic(case(2.0 * W_onset()), mesh=TINY, n_steps=2)
    assert res.curves["ep_max"][-1] > 0
    # residual history of the last (plastic) increment: r_(k+1) <= C r_k^2 once the active set settled
    hist = np.array(res.meta["residual_histories"][-1])
    k = np.nonzero((hist[:-1] < 1e-3) & (hist[1:] > 1e-12))[0]
    assert len(k) >= 1, hist
    assert np.all(hist[k + 1] <= 1e3 * hist[k] ** 2), f"residual history {hist}"


def test_failed_cutbacks_raise_convergence_error():
    with pytest.raises(ConvergenceError, match="cutbacks"):
        solve_plastic(case(3.0 * W_onset()), mesh=TINY, n_steps=1,
                      newton=NewtonSettings(max_newton=2, max_cutbacks=2))


def test_large_contact_warns_about_small_strain():
    soft = Material(2e9, 0.3, plasticity=Plasticity(50e6))
    W = math.pi * (0.12 * R) ** 2 * 2.8 * 50e6 * 1.5  # mean pressure <~ 3 Y: a/R > 0.12
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        res = solve_plastic(case(W, soft), mesh=TINY, n_steps=2)
    assert "validity" in res.meta and any("a/R" in str(w.message) for w in rec)


def test_approach_control_matches_load_control():
    """Elastic body (no yield data): the path is reversible, so approach control to the delta that
    load control reached must give back the load (1e-6), and plastic paths agree to the
    increment error (1 %)."""
    elastic = Material(200e9, 0.3)
    W = 50.0
    by_load = solve_plastic(case(W, elastic), mesh=TINY, n_steps=2)
    d = by_load.curves["delta"][-1]
    by_app = solve_plastic(case(W, elastic), mesh=TINY, n_steps=2, delta_max=d)
    assert abs(by_app.curves["W"][-1] / W - 1) < 1e-6
    assert by_app.meta["control"] == "approach"
    pl_load = solve_plastic(case(2.5 * W_onset()), mesh=TINY, n_steps=4, unload=True)
    i = pl_load.curves["phase"].index("unloading") - 1
    pl_app = solve_plastic(case(2.5 * W_onset()), mesh=TINY, n_steps=4, delta_max=pl_load.curves["delta"][i],
                           unload=True)
    j = pl_app.curves["phase"].index("unloading") - 1
    assert abs(pl_app.curves["W"][j] / pl_load.curves["W"][i] - 1) < 0.01
    assert pl_app.curves["W"][-1] == 0.0  # contact lost before delta = 0 (permanent dent)


def test_elements_across_the_contact_radius_per_increment(cycle):
    """``elements_across_a``: the surface elements from the axis to ``a`` (fractions counted), the
    covered share of every surface element summed; 0 without contact."""
    c = cycle.curves
    mesh = cycle.model.lm.mesh
    pr, pz = mesh.p[0][mesh.t], mesh.p[1][mesh.t]  # [4, nel]
    top = np.sum(np.abs(pz) < 1e-12, axis=0) == 2  # elements with an edge on the surface
    r0, r1 = pr[:, top].min(0), pr[:, top].max(0)
    for a, n in zip(c["a"], c["elements_across_a"], strict=True):
        covered = float(np.clip((a - r0) / (r1 - r0), 0.0, 1.0).sum())
        assert abs(n - covered) < 1e-9 * max(covered, 1.0), (a, n, covered)
    assert max(c["elements_across_a"]) > 4 and min(c["elements_across_a"]) == 0.0
