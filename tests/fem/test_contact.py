"""Contact formulations, far field and linear solvers."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.errors import ConvergenceError


def test_penalty_agrees_with_active_set_within_penalty_error(fx):
    """Penalty study (coarse Hertz mesh), difference to the active set:

    ====== ========= ========= =========
    beta   delta     a         p0
    ====== ========= ========= =========
    1e1    +1.6e-3   +2.9e-3   -2.7e-3
    1e2    +1.6e-4   +2.8e-4   -1.9e-4
    1e3    +1.6e-5   +2.7e-5   -3e-6
    1e4    +1.6e-6   +2.7e-6   (p0 fit floor 2e-5)
    ====== ========= ========= =========

    i.e. O(1/beta): the penetration is p s0 / (beta E*).
    """
    case = fx.hertz_case()
    ref = fx.solve(case, mesh="coarse")
    diffs = []
    for beta in (1e1, 1e2, 1e3):
        r = fx.solve(case, mesh="coarse", contact="penalty", penalty_beta=beta)
        d = abs(r.delta / ref.delta - 1)
        diffs.append(d)
        assert d < 0.03 / beta, (beta, d)
        assert abs(r.a / ref.a - 1) < 0.05 / beta + 3e-5, (beta, r.a / ref.a - 1)
        assert abs(r.p0 / ref.p0 - 1) < 0.05 / beta + 3e-5, (beta, r.p0 / ref.p0 - 1)
    order = -np.polyfit(np.log([1e1, 1e2, 1e3]), np.log(diffs), 1)[0]
    assert 0.9 < order < 1.1, f"penalty error in delta decays like beta^-{order:.2f}"


def test_farfield_bias_removed(fx):
    """Fixed outer boundary: delta biased by -0.62 a/L (measured -6.2, -3.1, -1.6 % at L = 10,
    20, 40 a); Boussinesq boundary values: residual |bias| <= 8e-5 at L >= 10 a."""
    case = fx.hertz_case()
    Ls = np.array([10.0, 20.0])
    fixed = np.array([fx.solve(case, mesh="coarse", farfield="fixed", L=float(L)).delta for L in Ls])
    bous = np.array([fx.solve(case, mesh="coarse", L=float(L)).delta for L in Ls])
    bias_fixed = fixed / case.delta0s - 1
    bias_bous = bous / case.delta0s - 1
    slope = np.polyfit(np.log(Ls), np.log(-bias_fixed), 1)[0]
    assert -1.1 < slope < -0.9, f"fixed far field bias ~ L^{slope:.2f}: {bias_fixed}"
    assert np.all(np.abs(bias_bous) < 1e-4), bias_bous


def test_amg_matches_direct_on_coarse_mesh(fx):
    case = fx.hertz_case()
    d = fx.solve(case, mesh="coarse", n_a=10)  # small: the AMG path refactorises per active set
    a = fx.solve(case, mesh="coarse", n_a=10, solver="amg")
    assert a.meta["solver"] == "amg-cg" and a.meta["solver_stats"]["cg_iterations"] > 0
    assert a.delta == pytest.approx(d.delta, rel=1e-6)
    assert a.p0 == pytest.approx(d.p0, rel=1e-5)


def test_active_set_iteration_cap_raises_convergence_error(fx):
    from coathertz.fem.contact import ActiveSet, ContactProblem
    from coathertz.fem.farfield import BoussinesqFarField
    from coathertz.fem.material import LinearElastic
    from coathertz.fem.mesh import MeshSpec, build_mesh
    from coathertz.fem.model import FEModel, Region
    from coathertz.fem.solvers import DirectSolver

    case = fx.hertz_case()
    lm = build_mesh(case.a0s, 0.0, MeshSpec(n_a=8, L=10))
    model = FEModel(lm, [Region(np.arange(lm.n_elements), LinearElastic(200e9, 0.3))], fx.STEEL,
                    BoussinesqFarField())
    fixed, vals = model.dirichlet(case.W)
    c = model.candidates
    r = model.r_dof[c]
    prob = ContactProblem(model.stiffness(), np.zeros(model.n_dofs), fixed, vals, c, r, model.weights_all[c],
                          r**2 / 0.02, case.W, fx.STEEL.E_star, case.a0s / 8)
    with pytest.raises(ConvergenceError, match="maxiter=1"):
        ActiveSet(maxiter=1).solve(prob, DirectSolver(), r <= r[1])  # far from the answer
    sol = ActiveSet().solve(prob, DirectSolver(), r <= r[1])
    assert sol.iterations > 1 and np.all(sol.lam >= 0) and np.all(sol.gap >= -1e-15)


def test_amg_iteration_cap_raises_convergence_error():
    import scipy.sparse as sp

    from coathertz.fem.solvers import AMGSolver

    n = 400
    A = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)).tocsr()
    with pytest.raises(ConvergenceError, match="maxiter=1"):
        AMGSolver(rtol=1e-14, maxiter=1).prepare(A)(np.ones(n))
