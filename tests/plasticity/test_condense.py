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
    """Approach control to 8 um (delta/delta_c ~ 6) in 6 increments and unloading, on yielding
    steel and on the same steel under an elastic 400 GPa coating 40 um thick (two regions, two
    laws): the plastic zone outgrows the first box, so the condensation is rebuilt at least once.
    Both paths take about the same number of Newton iterations; every curve agrees to 1e-9
    relative (the increments converge to rtol = 1e-9 and the two linear solves differ by round-off
    only: measured 3e-14 for W on the uncoated path), the fitted contact radius to 1e-6."""
    body = (Body.half_space(STEEL_J2, Coating(Material(400e9, 0.25), 40e-6)) if coated
            else Body.half_space(STEEL_J2))
    case = ContactCase(Body.rigid_sphere(R), body, 1.0)
    runs = [solve_plastic(case, mesh=SMALL, n_steps=6, delta_max=8e-6, unload=True,
                          newton=NewtonSettings(condense=c)) for c in (False, True)]
    full, cond = runs
    assert full.meta["linear_solves"]["condensed"] == 0
    ls = cond.meta["linear_solves"]
    assert ls["condensed"] > 0.8 * (ls["condensed"] + ls["full"]), ls
    assert ls["condensations"] >= 2, ls  # the box grew with the plastic zone
    # elastic unloading keeps the tangent while the contact shrinks: those iterations reuse the
    # box's factors (the free box and a capacitance on the active set), so the comparison below
    # covers that solve too
    assert ls["reused"] >= 4, ls
    # every increment's first iteration starts on the committed state, whose tangent is elastic:
    # those solves use the elastic tangent's box factors kept while the box stands (the loading
    # increments' first iterations and all of unloading), so the comparison covers them too
    n_inc = len(cond.curves["W"])
    assert ls["elastic"] >= n_inc - 1, (ls, n_inc)
    # iteration counts are not a round-off invariant: where the active set changes within an
    # increment one path may chatter once more (measured: 15 against 8 iterations in one
    # increment of the coated path); the totals stay close
    n_full, n_cond = sum(full.curves["newton_iterations"]), sum(cond.curves["newton_iterations"])
    assert abs(n_full - n_cond) <= 0.25 * n_full, (full.curves["newton_iterations"],
                                                    cond.curves["newton_iterations"])
    assert max(cond.curves["ep_max"]) > 1e-3
    for k in ("W", "delta", "ep_max", "zone_depth"):
        a, b = np.array(full.curves[k], float), np.array(cond.curves[k], float)
        err = float(np.max(np.abs(a - b)) / np.max(np.abs(a)))
        assert err < 1e-9, f"{k}: condensed vs whole-tangent path differ by {err:.2e} (relative)"
    # the contact radius is a least-squares fit on the nodal forces: its minima can be nearly
    # equally deep, so it must not amplify round-off (a single-start fit flipped between two minima
    # here, 1.0 % = 1.2 a_err apart; with the best three starts refined: 9e-10 measured)
    a, b = np.array(full.curves["a"], float), np.array(cond.curves["a"], float)
    ok = np.isfinite(a) & (a > 0)
    err = float(np.max(np.abs(a - b)[ok] / a[ok]))
    assert err < 1e-6, f"a: condensed vs whole-tangent path differ by {err:.2e} (relative)"
    assert math.isclose(full.final["residual_depth"], cond.final["residual_depth"], rel_tol=1e-9, abs_tol=0)


def test_product_over_the_fixed_columns_and_the_norm():
    """``ElasticCondensation._times_fixed`` (``K @ U0`` from the entries in the columns where ``U0``
    is nonzero) and ``coathertz.blas.norm2`` (the Euclidean norm without BLAS) on a random symmetric
    sparse matrix of 30k rows (beyond OpenBLAS's 10k threading size): within the round-off bound
    ``4 eps (|K| |U0|)`` row by row (on x86-64 the same numbers bit for bit: the sums run in the
    stored order) and the norm to 1e-14."""
    import types

    import scipy.sparse as sp

    from coathertz.blas import norm2
    from coathertz.fem.plastic.condense import ElasticCondensation

    rng = np.random.default_rng(5)
    n = 30_000
    A = sp.random(n, n, density=2e-4, random_state=rng, format="csr")
    K = (A + A.T + sp.eye(n)).tocsr()
    K.sort_indices()
    fixed = np.sort(rng.choice(n, 700, replace=False))
    U0 = np.zeros((n, 2))
    U0[fixed] = rng.standard_normal((len(fixed), 2))
    got = ElasticCondensation._times_fixed(types.SimpleNamespace(), K, fixed, U0)
    ref = K @ U0
    bound = 4 * np.finfo(float).eps * (abs(K) @ np.abs(U0)) + 1e-300
    assert np.all(np.abs(got - ref) <= bound), float(np.max(np.abs(got - ref) / bound))
    x = rng.standard_normal(n)
    assert abs(norm2(x) / np.linalg.norm(x) - 1) < 1e-14
