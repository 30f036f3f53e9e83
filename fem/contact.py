"""Frictionless contact of the surface nodes with the indenter (a rigid paraboloid, or an elastic
sphere meshed as a second body, :class:`TwoBody`), under load control.

The indenter surface after an approach ``delta`` is ``z = -delta + g0(r)``,
``g0 = r^2 / (2 R)`` (Hertz's paraboloid, Johnson 1985, eq 4.9). At each candidate node ``i``
(the ``u_z`` dof of a surface node) the gap and the nodal contact force are

.. math:: g_i = g_0(r_i) - \\delta - u_{z,i} \\ge 0, \\quad \\lambda_i \\ge 0, \\quad
          \\lambda_i g_i = 0, \\qquad \\textstyle\\sum_i \\lambda_i = W ,

``lambda_i`` pushing the body down (``K u = f - B^T lambda``). ``W`` is prescribed and
``delta`` comes out.

Condensed solve (default): the stiffness is factorised once per contact
problem, with the candidates ordered last, and the trailing block of the factors is the
stiffness condensed on the candidates, ``S`` (:class:`coathertz.fem.solvers.CondensedFactor`);
its inverse ``G = S^{-1}`` is the candidates' compliance. With ``u0 = K^{-1} f`` (essential values
included) the candidates' displacement is ``u_C = u0_C - G lambda`` and, for an active set ``A``,

    [G_AA + D_A   -1] [lambda_A]   [u0_A - g0_A]
    [   1^T        0] [ delta  ] = [     W     ],

a dense system of the size of the active set (``D = 0`` for :class:`ActiveSet`, ``D = diag(1/eps)``
for :class:`Penalty`). Each active-set iteration costs only that; one more sparse solve gives the
full displacement at the end. Without the geometry of the unknowns (``grid``) or with an
iterative solver the legacy path is used: per active set, the active dofs are eliminated and
the system is refactorised, solved by superposition ``u = u_1 + delta u_2`` (two solves),
``delta`` from ``sum(lambda) = W``. Both give the same numbers to round-off (measured <= 1e-11,
``tests/fem/test_contact.py``).

Two strategies share this loop and differ in how the active set enters:

* :class:`ActiveSet` -- primal-dual active set (Hintermueller, Ito & Kunisch 2002), i.e. a
  semi-smooth Newton method on ``lambda - max(0, lambda - c g) = 0``: active dofs are
  constrained exactly (``g_i = 0``, eliminated), ``lambda`` are the reactions (Lagrange
  multipliers); ``A <- {lambda > 0} U {g < 0}``; finite termination in a few steps.
* :class:`Penalty` -- springs of stiffness ``eps_i = beta E* w_i / s0`` on penetrating nodes
  (``w_i`` the nodal area, ``s0`` the element size): ``lambda_i = -eps_i g_i``; the penetration is
  ``~ p s0 / (beta E*)`` so the error in delta, a and p0 is ``O(1/beta)`` (penalty study in
  ``tests/fem/test_contact.py``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.linalg import LinAlgError
from scipy.linalg import cho_factor, cho_solve

from coathertz.blas import blas_threads
from coathertz.errors import ConvergenceError


@dataclass
class ContactProblem:
    """A linear system with essential dofs and unilateral contact candidates.

    ``K`` the system matrix, ``f`` the right-hand side, ``fixed``/``fixed_values`` essential
    dofs, ``cand`` the candidate ``u_z`` dofs with radii ``r``, area weights ``weights`` and
    obstacle shape ``g0``; ``W`` the load; ``E_star`` and ``s0`` scale the penalty;
    ``near_null`` builds an AMG near-null space for a set of free dofs; ``grid`` holds the
    ``(r, z)`` node-grid indices of every unknown (:meth:`coathertz.fem.model.FEModel.dof_grid`),
    needed by the condensed solve (``None``: legacy path).
    """

    K: sp.csr_matrix
    f: np.ndarray
    fixed: np.ndarray
    fixed_values: np.ndarray
    cand: np.ndarray
    r: np.ndarray
    weights: np.ndarray
    g0: np.ndarray
    W: float
    E_star: float
    s0: float
    near_null: object = None
    grid: tuple[np.ndarray, np.ndarray] | None = None
    extra: tuple[np.ndarray, np.ndarray] | None = None  # (compliance, displacement) added on cand


@dataclass
class ContactSolution:
    u: np.ndarray
    delta: float
    lam: np.ndarray  # nodal contact forces on the candidates [N]
    gap: np.ndarray  # gaps on the candidates [m]
    active: np.ndarray  # bool mask on the candidates
    iterations: int
    history: list = field(default_factory=list)
    #: ``resolve(W) -> ContactSolution``: the same problem at the load ``W`` on the same condensed
    #: factorisation (:meth:`Condensed.at_load`), started from this active set; ``None`` on the
    #: refactorising path. Valid where the right-hand side and the essential values are
    #: proportional to the load (the elastic model: far field and axis, no body force).
    resolve: object = None


def _solve_superposed(prob: ContactProblem, solver, K, rhs1, rhs2, fixed, val1, val2):
    """Solve ``K u_k = rhs_k`` with ``u_k[fixed] = val_k`` for k = 1, 2 (one preparation)."""
    n = K.shape[0]
    free = np.setdiff1d(np.arange(n), fixed)
    Kff = K[free][:, free]
    Kfd = K[free][:, fixed]
    B = prob.near_null(free) if prob.near_null is not None else None
    solve = solver.prepare(Kff, B)
    out = []
    for rhs, val in ((rhs1, val1), (rhs2, val2)):
        u = np.zeros(n)
        u[fixed] = val
        u[free] = solve(rhs[free] - Kfd @ val)
        out.append(u)
    return out


#: A repeated active set (a cycle) is accepted if its complementarity violation, relative to the
#: largest multiplier and to the approach, is below this: the edge node's multiplier and gap are
#: then round-off (seen with the incompressible mixed system), not a physical ambiguity.
CYCLE_TOL = 1e-6


def _violation(lam: np.ndarray, gap: np.ndarray, active: np.ndarray, delta: float) -> float:
    """Relative violation of the complementarity conditions of a contact solution."""
    lam_scale = max(float(np.max(np.abs(lam))), 1e-300)
    v_lam = max(0.0, -float(lam[active].min())) / lam_scale if active.any() else 0.0
    v_gap = max(0.0, -float(gap[~active].min())) / max(abs(delta), 1e-300) if (~active).any() else 0.0
    return max(v_lam, v_gap)


@dataclass
class Condensed:
    """A contact problem condensed on its candidates with one factorisation (module docstring)."""

    prob: ContactProblem
    free: np.ndarray
    rhs0: np.ndarray  # free part of the right-hand side with the essential values moved over
    solve: object
    G: np.ndarray  # compliance of the candidates, S^{-1}
    u0_c: np.ndarray

    @classmethod
    def build(cls, prob: ContactProblem, solver) -> Condensed | None:
        """``None`` if the solver or the problem does not allow it (then: legacy path)."""
        if prob.grid is None or not hasattr(solver, "condensed"):
            return None
        n = prob.K.shape[0]
        is_free = np.ones(n, dtype=bool)
        is_free[prob.fixed] = False
        if not is_free[prob.cand].all():
            return None  # a candidate is an essential dof
        free = np.flatnonzero(is_free)
        pos = np.searchsorted(free, prob.cand)
        u_fixed = np.zeros(n)
        u_fixed[prob.fixed] = prob.fixed_values
        rhs0 = (prob.f - prob.K @ u_fixed)[free]  # the essential values moved to the right-hand side
        try:
            cf = solver.condensed(prob.K, free, (prob.grid[0][free], prob.grid[1][free]), pos)
        except (ValueError, RuntimeError):
            solver.stats["condensed_fallbacks"] = solver.stats.get("condensed_fallbacks", 0) + 1
            return None
        G = np.linalg.inv(cf.S)
        u0 = cf.solve(rhs0)
        u0_c = u0[pos]
        if prob.extra is not None:  # a second body's candidates in series (TwoBody)
            G = G + prob.extra[0]
            u0_c = u0_c + prob.extra[1]
        return cls(prob, free, rhs0, cf.solve, 0.5 * (G + G.T), u0_c)

    def at_load(self, W: float) -> Condensed:
        """The problem at the load ``W``: ``u0`` (the candidates' displacement without contact,
        a second body's included), the right-hand side and the essential values scaled by
        ``W / prob.W``; the factorisation and the compliance ``G`` are the same."""
        from dataclasses import replace

        f = W / self.prob.W
        prob = replace(self.prob, W=W, f=f * self.prob.f, fixed_values=f * self.prob.fixed_values)
        return Condensed(prob, self.free, f * self.rhs0, self.solve, self.G, f * self.u0_c)

    def step(self, active: np.ndarray, compliance: np.ndarray | None = None):
        """``(None, u_C, delta, lambda)`` for the active set (``compliance``: penalty ``1/eps``)."""
        A = np.nonzero(active)[0]
        if compliance is not None:
            A = A[np.isfinite(compliance[A])]  # no spring (zero nodal area, the axis node): no force
        nA = len(A)
        GA = self.G[np.ix_(A, A)]
        if compliance is not None:
            GA[np.arange(nA), np.arange(nA)] += compliance[A]
        b = self.u0_c[A] - self.prob.g0[A]
        try:  # G_AA is symmetric positive definite (a compliance): Cholesky, delta from sum = W
            cf = cho_factor(GA, check_finite=False)
            y = cho_solve(cf, np.column_stack([b, np.ones(nA)]), check_finite=False)
            delta = (self.prob.W - y[:, 0].sum()) / y[:, 1].sum()
            lam_A = y[:, 0] + delta * y[:, 1]
        except LinAlgError:  # not positive definite to round-off: the bordered system
            M = np.zeros((nA + 1, nA + 1))
            M[:nA, :nA] = GA
            M[:nA, nA] = -1.0
            M[nA, :nA] = 1.0
            x = np.linalg.solve(M, np.concatenate([b, [self.prob.W]]))
            lam_A, delta = x[:nA], x[nA]
        lam = np.zeros(len(active))
        lam[A] = lam_A
        u_c = self.u0_c - self.G[:, A] @ lam_A  # both bodies' displacements (TwoBody)
        return None, u_c, float(delta), lam

    def full(self, lam: np.ndarray, delta: float) -> np.ndarray:
        """The full displacement for the contact forces ``lam`` (one sparse solve)."""
        b = self.rhs0.copy()
        b[np.searchsorted(self.free, self.prob.cand)] -= lam
        u = np.zeros(self.prob.K.shape[0])
        u[self.prob.fixed] = self.prob.fixed_values
        u[self.free] = self.solve(b)
        return u


@dataclass(frozen=True)
class TwoBody:
    """A contact formulation with a second elastic body (the indenter) in series.

    The indenter is a model of its own whose surface candidates sit at the same radii as the
    body's. Pressed by the nodal forces ``lambda`` (the same as on the body, opposite in
    direction) its candidates move by ``u1 = u1_0 - G1 lambda`` (``u1_0``: its far-field boundary
    values alone; ``G1``: its condensed compliance, one factorisation). The gap becomes
    ``g0 - delta - u_C - u1``, i.e. the body's ``u0_C`` and ``G`` plus ``u1_0`` and ``G1``:
    ``ContactProblem.extra``. Only the condensed solve supports it.
    """

    inner: object
    G1: np.ndarray
    u1_0: np.ndarray
    name: str = "two-body"

    @classmethod
    def build(cls, inner, model, W: float, r_cand: np.ndarray) -> TwoBody:
        from coathertz.fem.solvers import DirectSolver

        cand = model.candidates
        if len(cand) != len(r_cand) or not np.allclose(model.r_dof[cand], r_cand, rtol=0,
                                                       atol=1e-9 * r_cand.max()):
            raise ValueError("the indenter's surface nodes do not match the body's")
        K = model.stiffness()
        fixed, vals = model.dirichlet(W)
        z = np.zeros(len(cand))
        prob = ContactProblem(K, np.zeros(K.shape[0]), fixed, vals, cand, r_cand, z, z, W, 1.0, 1.0,
                              grid=model.dof_grid())
        with blas_threads(1):  # the compliance's inverse: small dense algebra (solvers module docstring)
            cond = Condensed.build(prob, DirectSolver())
        if cond is None:
            raise ValueError("the indenter's stiffness could not be condensed")
        return cls(inner, cond.G, cond.u0_c)

    @property
    def reuse(self) -> bool:
        return True

    def solve(self, prob: ContactProblem, solver, active0: np.ndarray) -> ContactSolution:
        from dataclasses import replace

        return self.inner.solve(replace(prob, extra=(self.G1, self.u1_0)), solver, active0)


def _loop(prob: ContactProblem, solver, step, update, active: np.ndarray, maxiter: int,
          finish=None) -> ContactSolution:
    """Iterate ``step``/``update`` until the active set repeats itself.

    ``step(prob, solver, active)`` returns ``(u, u_C, delta, lambda)``; ``u`` (the full
    displacement) may be ``None``, then ``finish(lambda, delta)`` computes it for the answer.
    A fixed point ends the loop. A cycle (a set seen before, not the last one) ends it too: the
    member of the cycle with the smallest violation is returned if that violation is below
    :data:`CYCLE_TOL`, else :class:`~coathertz.errors.ConvergenceError` is raised.
    """
    history: list[int] = []
    seen: dict[bytes, int] = {}
    sols: list[tuple[ContactSolution, float]] = []
    for it in range(1, maxiter + 1):
        if not active.any():
            active = prob.g0 <= prob.g0.min()  # at least the first node touches
        u, u_c, delta, lam = step(prob, solver, active)
        gap = prob.g0 - delta - u_c
        new = update(active, lam, gap)
        history.append(int(active.sum()))
        sol = ContactSolution(u, delta, lam, gap, active, it, history)
        if np.array_equal(new, active):
            return _finished(sol, finish)
        seen[active.tobytes()] = len(sols)
        sols.append((sol, _violation(lam, gap, active, delta)))
        key = new.tobytes()
        if key in seen:  # cycle: sols[seen[key]:] repeat forever
            best, v = min(sols[seen[key]:], key=lambda sv: sv[1])
            if v < CYCLE_TOL:
                return _finished(best, finish)
            raise ConvergenceError(
                f"contact active set cycles (sizes {history[seen[key]:]}) with violation {v:.2e} "
                f">= {CYCLE_TOL:g}"
            )
        active = new
    raise ConvergenceError(
        f"contact active set did not settle in maxiter={maxiter} iterations (sizes {history[-5:]})"
    )


def _no_extra(prob: ContactProblem) -> None:
    if prob.extra is not None:
        raise ValueError("a second body (TwoBody) needs the condensed solve: the direct solver")


def _finished(sol: ContactSolution, finish) -> ContactSolution:
    if sol.u is None:
        sol.u = finish(sol.lam, sol.delta)
    return sol


def _legacy(step):
    """Adapt a full-displacement step ``(u, delta, lambda)`` to the loop's ``(u, u_C, delta, lambda)``."""

    def wrapped(prob, solver, active):
        u, delta, lam = step(prob, solver, active)
        return u, u[prob.cand], delta, lam

    return wrapped


def _solve_scheme(scheme, prob: ContactProblem, solver, active0: np.ndarray,
                  condensed_step) -> ContactSolution:
    """Run a contact ``scheme`` (:class:`ActiveSet` or :class:`Penalty`): with ``scheme.reuse``, on
    one condensed factorisation (``condensed_step(cond)`` gives its ``active -> step``); otherwise,
    or where the condensed factorisation is not available, refactorising with ``scheme._step``."""
    if scheme.reuse:
        with blas_threads(1):  # small dense algebra (solvers module docstring)
            cond = Condensed.build(prob, solver)
            if cond is not None:
                return _condensed_loop(scheme, cond, solver, active0, condensed_step)
    _no_extra(prob)
    return _loop(prob, solver, _legacy(scheme._step), scheme._update, active0.copy(), scheme.maxiter)


def _condensed_loop(scheme, cond: Condensed, solver, active0: np.ndarray, condensed_step) -> ContactSolution:
    """The active-set loop on one condensed factorisation; the answer can be solved again at
    another load (``ContactSolution.resolve``)."""
    step = condensed_step(cond)
    sol = _loop(cond.prob, solver, lambda p, s, a: step(a), scheme._update, active0.copy(), scheme.maxiter,
                finish=cond.full)

    def resolve(W: float) -> ContactSolution:
        with blas_threads(1):
            return _condensed_loop(scheme, cond.at_load(W), solver, sol.active, condensed_step)

    sol.resolve = resolve
    return sol


@dataclass(frozen=True)
class ActiveSet:
    """Primal-dual active set with Lagrange multipliers (exact constraint)."""

    maxiter: int = 50
    name: str = "active-set"
    reuse: bool = True  # one factorisation per contact problem (condensed solve); False: legacy

    def solve(self, prob: ContactProblem, solver, active0: np.ndarray) -> ContactSolution:
        return _solve_scheme(self, prob, solver, active0, lambda cond: cond.step)

    @staticmethod
    def _step(prob, solver, active):
        A = prob.cand[active]
        fixed = np.concatenate([prob.fixed, A])
        order = np.argsort(fixed)
        fixed = fixed[order]
        v1 = np.concatenate([prob.fixed_values, prob.g0[active]])[order]
        v2 = np.concatenate([np.zeros(len(prob.fixed)), -np.ones(len(A))])[order]
        u1, u2 = _solve_superposed(prob, solver, prob.K, prob.f, np.zeros_like(prob.f), fixed, v1, v2)
        l1 = (prob.f - prob.K @ u1)[prob.cand]
        l2 = (-(prob.K @ u2))[prob.cand]
        l1[~active] = 0.0
        l2[~active] = 0.0
        delta = (prob.W - l1.sum()) / l2.sum()
        return u1 + delta * u2, delta, l1 + delta * l2

    @staticmethod
    def _update(active, lam, gap):
        return np.where(active, lam > 0.0, gap < 0.0)


@dataclass(frozen=True)
class Penalty:
    """Penalty springs ``eps_i = beta E* w_i / s0`` on penetrating candidates."""

    beta: float = 1e3
    maxiter: int = 50
    name: str = "penalty"
    reuse: bool = True

    def solve(self, prob: ContactProblem, solver, active0: np.ndarray) -> ContactSolution:
        def condensed_step(cond):
            with np.errstate(divide="ignore"):
                compliance = 1.0 / self._eps(prob, np.ones(len(prob.cand), dtype=bool))
            return lambda active: cond.step(active, compliance)

        return _solve_scheme(self, prob, solver, active0, condensed_step)

    def _eps(self, prob, active):
        return np.where(active, self.beta * prob.E_star * prob.weights / prob.s0, 0.0)

    def _step(self, prob, solver, active):
        eps = self._eps(prob, active)
        n = prob.K.shape[0]
        P = sp.csr_matrix((eps, (prob.cand, prob.cand)), shape=(n, n))
        rhs1 = prob.f.copy()
        rhs1[prob.cand] += eps * prob.g0
        rhs2 = np.zeros(n)
        rhs2[prob.cand] -= eps
        u1, u2 = _solve_superposed(
            prob, solver, prob.K + P, rhs1, rhs2, prob.fixed, prob.fixed_values, np.zeros(len(prob.fixed))
        )
        l1 = eps * (u1[prob.cand] - prob.g0)
        l2 = eps * (u2[prob.cand] + 1.0)
        delta = (prob.W - l1.sum()) / l2.sum()
        return u1 + delta * u2, delta, l1 + delta * l2

    @staticmethod
    def _update(active, lam, gap):
        return gap < 0.0
