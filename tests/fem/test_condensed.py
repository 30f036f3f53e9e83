"""Condensed contact solve: one factorisation per contact problem, the same
numbers as the refactorising active-set path."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fem.method import FEMMethod
from coathertz.fem.ordering import nested_dissection


def _pair(case, **kw):
    new = FEMMethod(**kw).solve(case)
    old_m = FEMMethod(**kw)
    old_m._reuse_factorisation = False
    old = old_m.solve(case)
    return new, old


@pytest.mark.parametrize(
    ("which", "kw"),
    [("coated", {}), ("coated", {"contact": "penalty"}), ("rigid_base_05", {}),
     ("incompressible_coating", {})],
)
def test_condensed_equals_refactorising_path(fx, which, kw):
    """delta, a, p0 equal to 1e-10 (measured <= 1e-11 in the displacement form; benchmark at the
    default mesh: 6e-13 Keer A, 6e-12 thin E = 4, H = 0.01).

    Incompressible (mixed u-p) regions: with the pressure unknowns scaled per dof
    (:meth:`coathertz.fem.model.FEModel._scaled`) measured 8e-15 (nu = 0.5 layer on a rigid base)
    and 8e-14 (nu = 0.5 coating); with the former scaling by mu (condition ~1e20) the two paths
    differed by 3e-10 and 1.4e-8, and the refactorising path itself moved by 1e-7 when only its
    fill-reducing ordering changed.
    """
    case = {
        "coated": fx.coated_case(800e9, 0.3),
        "rigid_base_05": fx.rigid_base_case(0.5),
        "incompressible_coating": fx.coated_case(50e9, 1.0, nu_c=0.5),
    }[which]
    new, old = _pair(case, mesh="coarse", **kw)
    tol = 1e-10
    for k in ("delta", "a", "p0"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=tol), k
    assert np.allclose(new.fields["p"], old.fields["p"], rtol=0, atol=10 * tol * old.p0)
    assert new.meta["contact_iterations"] == old.meta["contact_iterations"]
    st = new.meta["solver_stats"]
    assert st["factorisations"] == 1 and "condensed_fallbacks" not in st, st
    assert old.meta["solver_stats"]["factorisations"] == old.meta["contact_iterations"] >= 1


def test_mixed_system_is_well_conditioned(fx):
    """The scaled u-p system of a nu = 0.5 layer on a rigid base (coarse mesh): 1-norm condition
    estimate measured 2.1e9 (1e20 with the pressures scaled by mu alone); a fill-reducing ordering
    (COLAMD vs minimum degree) moves delta, a, p0 by round-off only (measured 1.2e-14, 8e-9 before)."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    from coathertz.fem.method import FEMMethod

    _, model, _ = FEMMethod(mesh="coarse").solve_full(fx.rigid_base_case(0.5))
    K = model.stiffness()
    fixed, _ = model.dirichlet(1.0)
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    A = sp.csc_matrix(K[free][:, free])
    res = {}
    for spec in ("COLAMD", "MMD_AT_PLUS_A"):
        lu = spla.splu(A, permc_spec=spec)
        res[spec] = lu.solve(np.ones(A.shape[0]))
    inv = spla.LinearOperator(A.shape, matvec=lu.solve, rmatvec=lambda b: lu.solve(b, trans="T"))
    cond = spla.onenormest(A) * spla.onenormest(inv)
    spread = np.max(np.abs(res["COLAMD"] - res["MMD_AT_PLUS_A"])) / np.max(np.abs(res["COLAMD"]))
    assert cond < 1e11, f"condition estimate {cond:.2e}"
    assert spread < 1e-9, f"solutions with two orderings differ by {spread:.1e}"


def test_nested_dissection_is_a_permutation_with_last_at_the_end():
    i, j = np.meshgrid(np.arange(41), np.arange(17), indexing="ij")
    i, j = np.repeat(i.ravel(), 2), np.repeat(j.ravel(), 2)  # two unknowns per node
    last = (j == 16) & (i < 20)
    p = nested_dissection(i, j, last)
    assert np.array_equal(np.sort(p), np.arange(len(i)))
    assert np.array_equal(p[-last.sum():], np.nonzero(last)[0])
    # the first separator (an even line through the middle) is eliminated after both halves
    first_half = p[: np.argmax(i[p] == 20)]
    assert set(np.unique(i[first_half])) <= set(range(20)) | set(range(21, 41))


def _recursive_nd(i, j, last, leaf):
    """The box-by-box recursion that :func:`nested_dissection` replaces (reference)."""
    node = i * (int(j.max()) + 1) + j
    out = []
    stack = [(np.nonzero(~last)[0], False)]
    while stack:
        ids, emit = stack.pop()
        if emit:
            out.append(ids)
            continue
        ii, jj = i[ids], j[ids]
        i0, i1, j0, j1 = ii.min(), ii.max(), jj.min(), jj.max()
        if (i1 - i0 + 1) * (j1 - j0 + 1) <= leaf:
            out.append(ids[np.argsort(node[ids], kind="stable")])
            continue
        key, lo, hi = (ii, i0, i1) if i1 - i0 >= j1 - j0 else (jj, j0, j1)
        m = (lo + hi) // 2
        m -= m % 2
        if m <= lo:
            m += 2
        sep = ids[key == m]
        stack += [(sep[np.argsort(node[sep], kind="stable")], True), (ids[key > m], False),
                  (ids[key < m], False)]
    return np.concatenate([*out, np.nonzero(last)[0]])


def test_nested_dissection_equals_the_box_recursion():
    """The level-wise ordering is the recursive one, unknown for unknown (two unknowns per node,
    a mesh-like hole of removed unknowns on the outer boundary, candidates last)."""
    from coathertz.fem.ordering import LEAF_NODES

    i, j = np.meshgrid(np.arange(61), np.arange(37), indexing="ij")
    i, j = np.repeat(i.ravel(), 2), np.repeat(j.ravel(), 2)
    keep = (i < 60) & (j > 0)  # essential dofs removed: outer column and bottom row
    i, j = i[keep], j[keep]
    last = (j == 36) & (i < 30) & (np.arange(len(i)) % 2 == 1)
    assert np.array_equal(nested_dissection(i, j, last), _recursive_nd(i, j, last, LEAF_NODES))


@pytest.mark.parametrize("factor", [0.3, 2.5])
def test_resolve_at_another_load_equals_a_new_solve_on_the_same_mesh(fx, factor):
    """``ContactSolution.resolve(W)`` (the condensed factorisation of the solve at ``W0`` reused,
    the far field and ``u0`` scaled by ``W / W0``) against a contact solve from scratch at ``W``
    on the same model: displacements, delta and the multipliers equal to 1e-9 (measured
    ~1e-13), and the resolved answer can itself be resolved back to ``W0``."""
    from coathertz.fem.contact import ActiveSet
    from coathertz.fem.loading import solve_incremental
    from coathertz.fem.solvers import DirectSolver

    case = fx.coated_case(800e9, 0.3)
    _, model, path = FEMMethod(mesh="coarse").solve_full(case)
    W0 = case.W
    r_c = model.r_dof[model.candidates]
    a0 = float(r_c[path.solution.active].max())
    fresh = solve_incremental(model, ActiveSet(), DirectSolver(), factor * W0, lambda r: r**2 / (2 * case.R),
                              1.0, a0 / 20, active0=r_c <= a0 * factor ** (1 / 3)).solution
    got = path.solution.resolve(factor * W0)
    assert got.delta == pytest.approx(fresh.delta, rel=1e-9)
    assert np.array_equal(got.active, fresh.active)
    assert np.abs(got.u - fresh.u).max() <= 1e-9 * np.abs(fresh.u).max()
    assert np.abs(got.lam - fresh.lam).max() <= 1e-9 * np.abs(fresh.lam).max()
    back = got.resolve(W0)
    assert back.delta == pytest.approx(path.solution.delta, rel=1e-9)
    assert np.abs(back.u - path.x).max() <= 1e-9 * np.abs(path.x).max()
