"""The load-controlled Newton loop starts from the active set extrapolated from the path's last two
contact fronts (``IncrementalContact._predicted_active``): only the start changes, so the path is
the one solved from the committed active set, in fewer iterations."""

from __future__ import annotations

import numpy as np

from coathertz.case import ContactCase
from coathertz.fem.mesh import MeshSpec
from coathertz.fem.plastic.contact import NewtonSettings
from coathertz.fem.plastic.method import solve_plastic
from coathertz.materials import Body, Material, Plasticity

R = 0.01
STEEL_J2 = Material(200e9, 0.3, plasticity=Plasticity(1e9))
SMALL = MeshSpec(n_a=8, r_fine=2.0, t_fine=1.0, growth=1.5, L=15.0)


def test_predicted_active_set_same_path_fewer_iterations():
    """200 N (about 4.5 times the first-yield load) in 8 steps and unloading in 8: every curve
    agrees with the path started from the committed active sets to 1e-9 relative (both converge to
    rtol = 1e-9; measured 3e-12 for the residual depth), and the path takes fewer Newton
    iterations (measured 50 against 58, unloading 18 against 23). Iteration counts can move by
    round-off where an edge node chatters, hence no tighter bound than "fewer"."""
    case = ContactCase(Body.rigid_sphere(R), Body.half_space(STEEL_J2), 200.0)
    plain, pred = (solve_plastic(case, mesh=SMALL, n_steps=8, unload=True,
                                 newton=NewtonSettings(predict_active=p)) for p in (False, True))
    assert max(pred.curves["ep_max"]) > 1e-3  # the path yields
    for k in ("W", "delta", "ep_max", "zone_depth", "a_lo", "a_hi"):
        a, b = np.array(plain.curves[k], float), np.array(pred.curves[k], float)
        assert a.shape == b.shape, (k, a.shape, b.shape)
        err = float(np.nanmax(np.abs(a - b)) / np.nanmax(np.abs(a)))
        assert err < 1e-9, f"{k}: predicted vs committed start differ by {err:.2e} (relative)"
    rel = abs(pred.final["residual_depth"] - plain.final["residual_depth"]) / plain.final["residual_depth"]
    assert rel < 1e-9, f"residual depth differs by {rel:.2e} (relative)"
    its_plain, its_pred = plain.curves["newton_iterations"], pred.curves["newton_iterations"]
    n_plain, n_pred = sum(its_plain), sum(its_pred)
    assert n_pred < n_plain, (f"no fewer Newton iterations with the predicted active set: {n_pred} "
                              f"against {n_plain}", its_pred, its_plain)


def test_newton_settings_reject_nonsense_with_one_line():
    """Every Newton setting outside what the loop can use is one CoatHertzError naming it and its
    range (a truthy string must not switch a feature on; a tolerance below the residual's
    round-off floor would never be met); numpy scalars in range are accepted."""
    import pytest

    from coathertz.errors import CoatHertzError

    NewtonSettings(max_newton=np.int64(5), rtol=np.float64(1e-8))
    bad = [("rtol", 0.0, "[1e-13, 0.001]"), ("rtol", float("nan"), "[1e-13, 0.001]"),
           ("rtol", "1e-9", "a number"),
           ("max_newton", 2.5, "an integer in [1, 200]"), ("max_newton", True, "an integer"),
           ("max_cutbacks", -1, "[0, 30]"), ("grow", 0.5, "[1, 4]"), ("condense", "no", "True or False"),
           ("predict_active", 1, "True or False")]
    for name, value, says in bad:
        with pytest.raises(CoatHertzError) as err:
            NewtonSettings(**{name: value})
        msg = str(err.value)
        assert msg.startswith(f"NewtonSettings: {name} must be") and says in msg and "\n" not in msg, msg
    with pytest.raises(CoatHertzError, match="rtol must be a number"):
        case = ContactCase(Body.rigid_sphere(R), Body.half_space(STEEL_J2), 50.0)
        solve_plastic(case, mesh=SMALL, rtol=-1.0)
