"""Linear solvers as plain objects: ``solver.prepare(A, B) -> solve(b)``.

* :class:`DirectSolver` -- SuperLU factorisation (scipy), the reference; the only choice for the
  indefinite mixed u-p system.
* :class:`AMGSolver` -- conjugate gradients preconditioned by pyamg smoothed aggregation
  (Vanek, Mandel & Brezina 1996). The near-null space passed to the aggregation is the
  axisymmetric rigid-body mode ``u_z = const`` (radial translation and rotations are not
  zero-energy modes of a solid of revolution) plus the local radial translation, which is a
  near-null mode away from the axis (hoop strain ``u_r / r`` small for large ``r``).
  The strength-of-connection threshold ``theta = 0.25`` matters on these graded meshes with
  element aspect ratios up to ~1e3: on the default Hertz mesh (28k dofs) CG needs ~130
  iterations with it and ~1000 with pyamg's default ``theta = 0``; ``u_z = const`` alone as
  near-null space needs ~500. Measured on a 2-core x86-64 machine the direct solver is still ~50x faster
  at these sizes (SuperLU factorisation 0.2 s), so ``direct`` is the default.

Each solver counts its work in ``stats`` (factorisations, solves, CG iterations).

BLAS threads (:func:`coathertz.blas.blas_threads`): the condensed contact solve runs its dense algebra (the
candidates' compliance, ~200 x 200, and the triangular solves) on one thread; only the sparse
factorisation keeps the library's threads. Measured on the shared 2-core machine: inverting the
173 x 173 Schur complement of Keer case A takes 1 ms on one thread and 80-150 ms on two when the
other core is busy (OpenBLAS threads wait for each other), a triangular solve 15 vs 19 ms.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from coathertz.blas import blas_threads
from coathertz.errors import ConvergenceError
from coathertz.fem.ordering import nested_dissection


def _delay_zero_pivots(A: sp.csr_matrix, order: np.ndarray, is_last: np.ndarray) -> np.ndarray:
    """Move every unknown with a zero diagonal (an incompressible region's pressure) just after the
    first of its neighbours in ``order``, so that its pivot has received fill and is not zero."""
    diag = A.diagonal()
    zero = np.nonzero((diag == 0) & ~is_last)[0]
    if len(zero) == 0:
        return order
    n = A.shape[0]
    where = np.full(n, np.inf)
    where[order] = np.arange(len(order))
    key = where.copy()
    for i in zero:
        nb = A.indices[A.indptr[i] : A.indptr[i + 1]]
        nb = nb[(nb != i) & ~is_last[nb]]
        first = where[nb].min() if len(nb) else np.inf
        if np.isfinite(first) and first > where[i]:
            key[i] = first + 0.5
    return order[np.argsort(key[order], kind="stable")]


def nd_lu(A: sp.spmatrix, grid: tuple[np.ndarray, np.ndarray],
          diag_pivot_thresh: float = 0.01) -> Callable[[np.ndarray], np.ndarray]:
    """``b -> A^{-1} b`` by one SuperLU factorisation in the geometric nested-dissection order of
    the unknowns' grid nodes (:mod:`coathertz.fem.ordering`), no column reordering, diagonal pivots
    preferred (``A`` structurally symmetric, e.g. a tangent stiffness). Measured on the plastic
    benchmark's tangent (28.7k unknowns, 1 BLAS thread): about half the factorisation time of
    SuperLU's minimum degree on ``A + A^T``."""
    perm = nested_dissection(grid[0], grid[1])
    return _lu_in_order(sp.csr_matrix(A)[perm][:, perm], perm, diag_pivot_thresh)[1]


def _lu_in_order(Ap: sp.spmatrix, perm: np.ndarray, diag_pivot_thresh: float):
    """SuperLU of ``Ap = A[perm][:, perm]`` in that order (no column reordering, diagonal pivots
    preferred) and ``b -> A^{-1} b`` in ``A``'s numbering."""
    lu = spla.splu(sp.csc_matrix(Ap), permc_spec="NATURAL", diag_pivot_thresh=diag_pivot_thresh,
                   options={"SymmetricMode": True})
    inv = np.empty(len(perm), dtype=np.int64)
    inv[perm] = np.arange(len(perm))
    return lu, lambda b: lu.solve(b[perm])[inv]


@dataclass
class CondensedFactor:
    """One LU of ``A`` whose trailing block is the Schur complement on the unknowns ``last``.

    ``A`` is ordered by geometric nested dissection with ``last`` at the end
    (:mod:`coathertz.fem.ordering`) and factorised without column reordering (SuperLU,
    ``permc_spec='NATURAL'``) and with diagonal pivots (``diag_pivot_thresh=0``), so that
    ``P A P^T = L U`` with ``P`` our permutation; then the trailing blocks give
    ``S = A_CC - A_CI A_II^{-1} A_IC = L_CC U_CC`` (the stiffness condensed on the contact
    candidates ``C``). The mixed u-p system works too: in this order every pressure unknown is
    eliminated after the displacements of its own node, so its pivot is not zero. If SuperLU
    pivots off the diagonal anyway (``perm_r`` not the identity), :class:`ValueError` is raised
    and the caller falls back to refactorising.

    Attributes
    ----------
    S
        Dense Schur complement on ``last`` (in the order given).
    solve
        ``b -> A^{-1} b`` in the original numbering.
    """

    S: np.ndarray
    solve: Callable[[np.ndarray], np.ndarray]

    @classmethod
    def build(cls, K: sp.spmatrix, keep: np.ndarray, grid: tuple[np.ndarray, np.ndarray], last: np.ndarray,
              stats: dict) -> CondensedFactor:
        """Factorise ``A = K[keep][:, keep]``; ``grid`` and ``last`` refer to ``A``'s numbering."""
        n = len(keep)
        is_last = np.zeros(n, dtype=bool)
        is_last[last] = True
        nd = nested_dissection(grid[0], grid[1], is_last)[: n - len(last)]
        if np.any(K.diagonal()[keep] == 0):  # mixed u-p: the pressure pivots (rare path)
            nd = _delay_zero_pivots(sp.csr_matrix(K)[keep][:, keep], nd, is_last)
        perm = np.concatenate([nd, last])
        with blas_threads(None):  # the supernodal updates may use the library's threads
            lu, lu_solve = _lu_in_order(sp.csr_matrix(K)[keep[perm]][:, keep[perm]], perm, 0.0)
        stats["factorisations"] += 1
        if not (np.array_equal(lu.perm_r, np.arange(n)) and np.array_equal(lu.perm_c, np.arange(n))):
            raise ValueError("SuperLU reordered the condensed factorisation")
        m = n - len(last)
        S = lu.L[m:, m:] @ lu.U[m:, m:]

        def solve(b: np.ndarray) -> np.ndarray:
            stats["solves"] += 1
            return lu_solve(b)

        return cls(np.asarray(S.todense()), solve)


@dataclass
class DirectSolver:
    """Sparse LU (SuperLU).

    ``symmetric_mode`` (for SPD matrices): minimum-degree ordering of ``A + A^T`` with diagonal
    pivots, about 3x faster and half the fill of COLAMD on these FE matrices. The indefinite
    mixed u-p system (zero pressure diagonal for nu = 0.5) needs ``symmetric_mode=False``
    (COLAMD, partial pivoting): in symmetric mode its factorisation degenerates (minutes).
    """

    symmetric_mode: bool = True
    name: str = "direct"
    stats: dict = field(default_factory=lambda: {"factorisations": 0, "solves": 0})

    def condensed(
        self, K: sp.spmatrix, keep: np.ndarray, grid: tuple[np.ndarray, np.ndarray], last: np.ndarray
    ) -> CondensedFactor:
        """Factorise ``K[keep][:, keep]`` once with the Schur complement on its unknowns ``last``
        (:class:`CondensedFactor`)."""
        return CondensedFactor.build(K, keep, grid, last, self.stats)

    def prepare(self, A: sp.spmatrix, B: np.ndarray | None = None) -> Callable[[np.ndarray], np.ndarray]:
        if self.symmetric_mode:
            lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
        else:
            lu = spla.splu(sp.csc_matrix(A))
        self.stats["factorisations"] += 1

        def solve(b: np.ndarray) -> np.ndarray:
            self.stats["solves"] += 1
            return lu.solve(b)

        return solve


@dataclass
class AMGSolver:
    """CG preconditioned by pyamg smoothed aggregation.

    Parameters
    ----------
    rtol
        Relative residual tolerance of CG.
    maxiter
        CG iteration cap; exceeding it raises :class:`~coathertz.errors.ConvergenceError`.
    """

    rtol: float = 1e-10
    maxiter: int = 2000
    theta: float = 0.25
    name: str = "amg-cg"
    stats: dict = field(default_factory=lambda: {"setups": 0, "solves": 0, "cg_iterations": 0})

    def prepare(self, A: sp.spmatrix, B: np.ndarray | None = None) -> Callable[[np.ndarray], np.ndarray]:
        import pyamg

        A = sp.csr_matrix(A)
        ml = pyamg.smoothed_aggregation_solver(
            A, B=B, symmetry="hermitian", max_coarse=500, strength=("symmetric", {"theta": self.theta})
        )
        M = ml.aspreconditioner(cycle="V")
        self.stats["setups"] += 1

        def solve(b: np.ndarray) -> np.ndarray:
            it = [0]

            def count(_xk: np.ndarray) -> None:
                it[0] += 1

            x, info = spla.cg(A, b, rtol=self.rtol, atol=0.0, maxiter=self.maxiter, M=M, callback=count)
            self.stats["solves"] += 1
            self.stats["cg_iterations"] += it[0]
            if info != 0:
                raise ConvergenceError(
                    f"AMG-preconditioned CG did not reach rtol={self.rtol:g}"
                    f" in maxiter={self.maxiter} iterations"
                )
            return x

        return solve
