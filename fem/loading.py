"""Incremental loading with a Newton loop around the contact solve.

The load ``W`` is applied in ``n_steps`` equal increments. In increment ``k`` the target is
``W_k = k W / n``; each Newton iteration linearises the internal force at the current
displacement ``u`` with the material laws of :mod:`coathertz.fem.material`,

.. math:: F_{int}(u + \\Delta u) \\approx F_{int}(u) + K_t(u)\\,\\Delta u ,

and solves the contact problem of :mod:`coathertz.fem.contact` for the new total
displacement with right-hand side ``f_ext - F_int(u) + K_t u``. The iteration stops when the
linearisation residual ``|F_int(u_new) - F_int(u) - K_t (u_new - u)|`` is below ``rtol`` times
``|F_int(u_new)|``; history variables are committed at the end of the increment. For linear
laws ``K_t`` is the constant stiffness (assembled once, fast path of
:meth:`coathertz.fem.model.FEModel.stiffness`) and the first iteration converges, so
:func:`solve_incremental`, which serves the elastic model, solves each increment once. The
generic quadrature-point path (:func:`internal_force`, :func:`tangent`) is what a non-linear law
would use; the tests check it against the fast path. The elastic-plastic model with the B-bar strain,
cutbacks and unloading is :mod:`coathertz.fem.plastic.contact` (this loop stays the elastic
model's, displacement form only).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import Basis, asm

from coathertz.fem import forms
from coathertz.fem.contact import ContactProblem, ContactSolution
from coathertz.fem.model import INTORDER, FEModel


def _region_basis(model: FEModel, elements: np.ndarray) -> Basis:
    return Basis(model.lm.mesh, model.elem, intorder=INTORDER, elements=elements)


def internal_force(model: FEModel, u: np.ndarray, states: list) -> tuple[np.ndarray, list]:
    """``F_int`` assembled from quadrature-point stresses of each region's law (displacement form)."""
    F = np.zeros(model.n_u)
    new_states = []
    for reg, st in zip(model.regions, states, strict=True):
        rb = _region_basis(model, reg.elements)
        sig, _, st_new = reg.law.stress(forms.quad_strain(rb, u), st)
        F += asm(forms.internal_force, rb, sig=sig)
        new_states.append(st_new)
    return F, new_states


def tangent(model: FEModel, u: np.ndarray, states: list) -> sp.csr_matrix:
    """Tangent stiffness assembled from each region's quadrature-point tangent."""
    K = None
    for reg, st in zip(model.regions, states, strict=True):
        rb = _region_basis(model, reg.elements)
        _, D, _ = reg.law.stress(forms.quad_strain(rb, u), st)
        Kr = asm(forms.tangent_stiffness, rb, D=np.ascontiguousarray(D))
        K = Kr if K is None else K + Kr
    return sp.csr_matrix(K)


@dataclass
class LoadPath:
    """Outcome of :func:`solve_incremental`."""

    solution: ContactSolution
    x: np.ndarray
    steps: int
    newton_iterations: int
    contact_iterations: int
    deltas: list
    states: list | None = None  # committed history of each region (quadrature layout)


def solve_incremental(
    model: FEModel,
    contact,
    solver,
    W: float,
    g0_fun,
    E_star: float,
    s0: float,
    n_steps: int = 1,
    active0: np.ndarray | None = None,
) -> LoadPath:
    """Apply ``W`` in ``n_steps`` increments to a model of linear laws (see module docstring).

    The stiffness is assembled once; each increment is one contact solve (for a linear law the
    Newton loop of the module docstring converges in its first iteration, so it is not run).
    """
    if not all(reg.law.is_linear for reg in model.regions):
        raise NotImplementedError("solve_incremental is the elastic model's loop (linear laws); "
                                  "plasticity is coathertz.fem.plastic.contact")
    K = model.stiffness()
    cand = model.candidates
    r = model.r_dof[cand]
    g0 = g0_fun(r)
    weights = model.weights_all[cand]
    grid = model.dof_grid()  # condensed contact solve (one factorisation)
    rhs = np.zeros(K.shape[0])
    active = (r <= r[1]) if active0 is None else active0
    contact_total = 0
    deltas = []
    sol = None
    for k in range(1, n_steps + 1):
        Wk = W * k / n_steps
        fixed, vals = model.dirichlet(Wk)
        prob = ContactProblem(K, rhs, fixed, vals, cand, r, weights, g0, Wk, E_star, s0,
                              model.near_null_space, grid)
        sol = contact.solve(prob, solver, active)
        contact_total += sol.iterations
        active = sol.active
        deltas.append(sol.delta)
    return LoadPath(sol, sol.u, n_steps, n_steps, contact_total, deltas)
