"""Frictionless contact of the surface nodes with a rigid paraboloid, under load control.

The indenter surface after an approach ``delta`` is ``z = -delta + g0(r)``,
``g0 = r^2 / (2 R)`` (Hertz's paraboloid, Johnson 1985, eq 4.9). At each candidate node ``i``
(the ``u_z`` dof of a surface node) the gap and the nodal contact force are

.. math:: g_i = g_0(r_i) - \\delta - u_{z,i} \\ge 0, \\quad \\lambda_i \\ge 0, \\quad
          \\lambda_i g_i = 0, \\qquad \\textstyle\\sum_i \\lambda_i = W ,

``lambda_i`` pushing the body down (``K u = f - B^T lambda``). ``W`` is prescribed and
``delta`` comes out: for a fixed active set the problem is linear in ``(u, delta)``, so it is
solved by superposition ``u = u_1 + delta u_2`` with one factorisation and two solves, and
``delta`` follows from ``sum(lambda) = W``.

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

from coathertz.errors import ConvergenceError


@dataclass
class ContactProblem:
    """A linear system with essential dofs and unilateral contact candidates.

    ``K`` the system matrix, ``f`` the right-hand side, ``fixed``/``fixed_values`` essential
    dofs, ``cand`` the candidate ``u_z`` dofs with radii ``r``, area weights ``weights`` and
    obstacle shape ``g0``; ``W`` the load; ``E_star`` and ``s0`` scale the penalty;
    ``near_null`` builds an AMG near-null space for a set of free dofs.
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


@dataclass
class ContactSolution:
    u: np.ndarray
    delta: float
    lam: np.ndarray  # nodal contact forces on the candidates [N]
    gap: np.ndarray  # gaps on the candidates [m]
    active: np.ndarray  # bool mask on the candidates
    iterations: int
    history: list = field(default_factory=list)


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


def _loop(prob: ContactProblem, solver, step, update, active: np.ndarray, maxiter: int) -> ContactSolution:
    """Iterate ``step``/``update`` until the active set repeats itself.

    A fixed point ends the loop. A cycle (a set seen before, not the last one) ends it too: the
    member of the cycle with the smallest violation is returned if that violation is below
    :data:`CYCLE_TOL`, else :class:`ConvergenceError` is raised.
    """
    history: list[int] = []
    seen: dict[bytes, int] = {}
    sols: list[tuple[ContactSolution, float]] = []
    for it in range(1, maxiter + 1):
        if not active.any():
            active = prob.g0 <= prob.g0.min()  # at least the first node touches
        u, delta, lam = step(prob, solver, active)
        gap = prob.g0 - delta - u[prob.cand]
        new = update(active, lam, gap)
        history.append(int(active.sum()))
        sol = ContactSolution(u, delta, lam, gap, active, it, history)
        if np.array_equal(new, active):
            return sol
        seen[active.tobytes()] = len(sols)
        sols.append((sol, _violation(lam, gap, active, delta)))
        key = new.tobytes()
        if key in seen:  # cycle: sols[seen[key]:] repeat forever
            best, v = min(sols[seen[key]:], key=lambda sv: sv[1])
            if v < CYCLE_TOL:
                return best
            raise ConvergenceError(
                f"contact active set cycles (sizes {history[seen[key]:]}) with violation {v:.2e} "
                f">= {CYCLE_TOL:g}"
            )
        active = new
    raise ConvergenceError(
        f"contact active set did not settle in maxiter={maxiter} iterations (sizes {history[-5:]})"
    )


@dataclass(frozen=True)
class ActiveSet:
    """Primal-dual active set with Lagrange multipliers (exact constraint)."""

    maxiter: int = 50
    name: str = "active-set"

    def solve(self, prob: ContactProblem, solver, active0: np.ndarray) -> ContactSolution:
        return _loop(prob, solver, self._step, self._update, active0.copy(), self.maxiter)

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

    def solve(self, prob: ContactProblem, solver, active0: np.ndarray) -> ContactSolution:
        return _loop(prob, solver, self._step, self._update, active0.copy(), self.maxiter)

    def _step(self, prob, solver, active):
        eps = np.where(active, self.beta * prob.E_star * prob.weights / prob.s0, 0.0)
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
