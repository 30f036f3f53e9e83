r"""Static condensation of the elastic far field: one factorisation of the part that stays elastic.

In an indentation path only the elements near the contact yield; the rest of the mesh (most of
its unknowns) keeps the elastic tangent, so its stiffness ``K^E`` is the same at every Newton
iteration. Split the elements into a box ``N`` at the contact (``0 <= r < r_N``,
``0 <= -z < t_N``) and the rest ``E``; the free unknowns into ``e`` (touched by ``E`` only),
``n`` (touched by ``N``) and their interface ``g = n \cap dofs(E)``. With ``u_F`` the essential
values (far field, axis, the contact's active set, all inside ``n`` or on the outer boundary),
``b = f - K u_F`` and

.. math:: S^E = K^E_{gg} - K_{ge} K_{ee}^{-1} K_{eg},\qquad
          t = K_{ge} K_{ee}^{-1} b_e ,

the Newton system reduces exactly (block Gauss elimination, e.g. Saad 2003, Section 14.2) to

.. math:: \bigl(K_{nn} - K_{ge} K_{ee}^{-1} K_{eg}\bigr)\, u_n = b_n - t \ \text{(on g)},\qquad
          u_e = K_{ee}^{-1} (b_e - K_{eg} u_g) .

``A = K^E`` on ``e \cup g`` is factorised once, ordered by nested dissection with ``g`` last and
without pivoting (:class:`coathertz.fem.solvers.CondensedFactor`), which gives ``S^E`` as the
trailing block of its LU. Both ``t`` and ``u_e`` come from full solves with ``A`` (``t`` not for a
zero ``b_e`` nor for one equal to the last solve's):
``A [x; y] = [b_e; 0]`` gives ``t = -S^E y``, and ``A [x; y] = [b_e; t + S^E u_g]`` gives
``y = u_g``, ``x = u_e``. Per Newton iteration only the sparse ``n`` block (plus the dense
``g x g`` block, ordered last) is factorised, and not even that when the tangent and the
active set are those of the last solve (elastic unloading: the next increment's first
iteration). Where the tangent is the last one's but the active set changed (elastic unloading
releases the contact node by node), the box with no dof decoupled is factorised once for that
tangent and each active set is imposed by a capacitance matrix on the active contact dofs
(``ElasticCondensation._solve_free``): on the README load path 39 of 78 Newton iterations
reuse factors (11 before), CPU 10.6 -> 8.6-8.8 s (separate runs, shared machine). The elastic
tangent itself (``K^E`` everywhere: the first iteration of every increment starts on the
committed state, whose points on the yield surface answer elastically, and all of elastic
unloading) keeps its free box factors for as long as the box stands, and their capacitance
columns with them, so that each increment's first iteration factorises nothing: on the README
load path 42 -> 33 box factorisations (54 iterations), delta/delta_c = 200 (E/Y = 1000, 197
iterations) 203 -> 188, box factorisation time 18.9 -> 16.8 s there, solves 3.3 -> 3.5 s
(cProfile, one run each, the same machine). SuperLU's
minimum degree on ``A + A^T`` instead of the nested-dissection order, measured on the README
load path's largest box (7497 unknowns): fill 1.04M against 1.07M, but 59-95 ms against 45-64 ms
per factorisation (with the ordering's time); ``panel_size`` / ``relax`` changed nothing measurable.
The box's matrix is gathered from the tangent's data into a structure built once per
box; the rows and columns of the active contact dofs are decoupled there (diagonal kept,
right-hand side 0) rather than sliced out, so that the structure does not depend on the active set.

The split is exact, not an approximation, as long as every ``E`` element has the elastic tangent
(the assembler reports the elements whose tangent changed,
``BBarAssembler.nonelastic``, and the elastic ones carry the
same cached element matrices) and the contact's active set lies inside ``n`` off ``g``; when
either fails the box is rebuilt larger (:data:`BOX_GROWTH` times what is needed). A box that
would hold more than :data:`MAX_FRACTION` of the elements is not worth it: the caller then
factorises the whole tangent.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from coathertz.blas import blas_threads, norm2
from coathertz.errors import CoatHertzError
from coathertz.fem.ordering import nested_dissection
from coathertz.fem.solvers import CondensedFactor

#: A rebuilt box reaches this factor beyond the plastic zone and contact it must hold. Measured on
#: the README's approach path with unloading (default mesh, CPU): 1.25, 1.5 and 2.0 give 18.2,
#: 18.1 and 20.9 s (5, 4 and 3 condensations).
BOX_GROWTH = 1.5
#: No condensation when the box would hold more than this fraction of the elements. Approach to
#: delta/delta_c = 200 (E/Y = 1000, default mesh, 20 steps): 54.9 s CPU with 0.6 (58 of 197
#: solves of the whole tangent), 45.1 s with 0.9 (none).
MAX_FRACTION = 0.9
#: ``t = K_ge K_ee^-1 b_e`` is not solved again for a ``b_e`` within this fraction of the force
#: scale (the path's largest load) of a stored one (nor for such a small ``b_e``): within a Newton
#: loop the far field's ``b_e`` often changes by round-off only (its elements keep the elastic
#: tangent, so ``K u - F_int`` vanishes there up to round-off), and the neglected change of ``t``
#: is a force of this size (the Newton tolerance is 1e-9 of the load). Measured against the whole
#: right-hand side's norm instead (which holds the large forces of the prescribed contact
#: displacements), round-off of 2e-14 of that norm was about 1e-9 of the load and the coated path
#: of ``tests/plasticity/test_condense.py`` stopped converging.
T_REUSE = 1e-12


@dataclass
class ElementBoxes:
    """Radial and depth extent ``[r_min, r_max]``, ``[t_min, t_max]`` of every element [m]."""

    r_min: np.ndarray
    r_max: np.ndarray
    t_min: np.ndarray
    t_max: np.ndarray

    @classmethod
    def of(cls, mesh) -> ElementBoxes:
        r, t = mesh.p[0][mesh.t], -mesh.p[1][mesh.t]  # [4, nel]
        return cls(r.min(0), r.max(0), t.min(0), t.max(0))


@dataclass
class _FreeBox:
    """The box matrix ``M`` with no dof decoupled, for one tangent (whose CSR ``data`` it keeps),
    its factors and the columns ``Z[:, i] = M^-1 e_i`` computed so far, by dof."""

    lu: spla.SuperLU
    cols: dict
    M: sp.csc_matrix
    data: np.ndarray


class ElasticCondensation:
    """The elastic far field of one box condensed on its interface (module docstring).

    Parameters
    ----------
    asm
        The :class:`~coathertz.fem.plastic.assembly.BBarAssembler` (its cached elastic element
        matrices give ``K^E``).
    fixed
        The essential dofs that do not depend on the contact (far field, axis).
    grid
        Grid node ``(i, j)`` of every dof (nested-dissection order).
    in_box
        Mask of the elements of ``N``.
    """

    def __init__(self, asm, fixed: np.ndarray, grid: tuple[np.ndarray, np.ndarray], in_box: np.ndarray,
                 box: tuple[float, float]) -> None:
        n = asm.n
        self.box = box
        self.in_box = in_box
        is_fixed = np.zeros(n, dtype=bool)
        is_fixed[fixed] = True
        touched_n = np.zeros(n, dtype=bool)
        touched_n[asm.edofs[:, in_box].ravel()] = True
        touched_e = np.zeros(n, dtype=bool)
        touched_e[asm.edofs[:, ~in_box].ravel()] = True
        self.n_mask = touched_n & ~is_fixed
        self.g = np.flatnonzero(touched_n & touched_e & ~is_fixed)
        self.e = np.flatnonzero(touched_e & ~touched_n & ~is_fixed)
        self.interior = self.n_mask.copy()  # where active contact dofs may lie
        self.interior[self.g] = False
        KE = asm.elastic_matrix(~in_box)
        keep = np.concatenate([self.e, self.g])
        last = np.arange(len(self.e), len(keep))
        stats = {"factorisations": 0, "solves": 0}
        self.factor = CondensedFactor.build(KE, keep, (grid[0][keep], grid[1][keep]), last, stats)
        self.S = self.factor.S
        KEg = KE.tocsr()[self.g][:, self.g].toarray()
        self.D = KEg - self.S  # K_ge K_ee^-1 K_eg, subtracted from the box's block on g
        # nested dissection of the box's dofs, g last; the active contact dofs are decoupled per solve
        in_g = np.zeros(n, dtype=bool)
        in_g[self.g] = True
        nb = np.flatnonzero(self.n_mask & ~in_g)
        nd = nb[nested_dissection(grid[0][nb], grid[1][nb])]
        self.order = np.concatenate([nd, self.g])
        self.ne, self.ng = len(self.e), len(self.g)
        self.n_box = int(self.n_mask.sum())
        self.Di, self.Dj = np.nonzero(np.ones_like(self.D, dtype=bool))
        self._template(KE)
        self._last = None  # (order, tangent data, factors) of the last box factorisation
        self._free: _FreeBox | None = None  # the box with no dof decoupled, for the last tangent
        self._free_el: _FreeBox | None = None  # the same for the elastic tangent, kept while the box stands
        self.reused = 0  # box factorisations reused (the same tangent and active set)
        self.elastic = 0  # of those, solves with the elastic tangent's box factors (:attr:`_free_el`)
        self._tmemo: list = []  # (b_e, t) of the last solve's right-hand sides
        self.t_solves = 0  # far-field solves for t
        self.t_reused = 0  # t taken from the memo

    def _t(self, be: np.ndarray, scale: float) -> np.ndarray:
        """``t = K_ge K_ee^-1 b_e`` for each column of ``be``: 0 for a column that is round-off
        (below :data:`T_REUSE` times the force ``scale`` [N]: the out-of-balance force
        of elastic elements, e.g. approach control's first right-hand side), a stored value for one
        within that of a stored solved column (the far field's essential values within an increment
        of load control; the far field of a unit load), else one solve with ``A``."""
        m = be.shape[1]
        t = np.zeros((self.ng, m))
        todo = []
        kept = []  # stored (b_e, t) pairs hit this time (stored as solved: no drift)
        for k in range(m):
            b, tol = be[:, k], T_REUSE * scale
            if norm2(b) <= tol:
                continue
            hit = next((pair for pair in self._tmemo if norm2(pair[0] - b) <= tol), None)
            if hit is None:
                todo.append(k)
            else:
                t[:, k] = hit[1]
                kept.append(hit)
                self.t_reused += 1
        if todo:
            y0 = self.factor.solve(np.vstack([be[:, todo], np.zeros((self.ng, len(todo)))]))[self.ne:]
            t[:, todo] = -self.S @ y0
            self.t_solves += len(todo)
        self._tmemo = kept + [(be[:, k].copy(), t[:, k].copy()) for k in todo]
        return t

    def valid(self, nonelastic: np.ndarray, active_dofs: np.ndarray) -> bool:
        """The split is exact: the elements with a changed tangent lie in the box and the active
        contact dofs inside it (off its interface)."""
        return bool(self.in_box[nonelastic].all() and self.interior[active_dofs].all())

    def solve(self, K: sp.csr_matrix, rhs: list[np.ndarray], fixed: np.ndarray,
              vals: list[np.ndarray], force_scale: float = 0.0, combine=None):
        """``K u = rhs_k`` with ``u[fixed] = vals_k`` for each pair (``fixed``: the essential dofs
        and the active contact dofs; ``force_scale`` [N] the path's largest load, the scale of
        :data:`T_REUSE`; 0 solves for every nonzero ``b_e``): the list of the ``u_k``, or with
        ``combine`` the one vector ``sum_k c_k u_k``, ``c = combine(u)``, where ``combine`` gets the
        ``u_k`` before their far field ``u_e`` is solved (zero there; it may read them on the box's
        interior only, e.g. the active contact dofs' rows of ``K u``) and the far field is solved
        once, for the combination (linear in the right-hand sides: exact; one right-hand side
        instead of ``m`` in the far field's triangular solves)."""
        n = K.shape[0]
        m = len(rhs)
        U0 = np.zeros((n, m))
        for k, v in enumerate(vals):
            U0[fixed, k] = v
        Bm = np.column_stack(rhs) - self._times_fixed(K, fixed, U0)
        is_fixed = np.zeros(n, dtype=bool)
        is_fixed[fixed] = True
        fixed_box = is_fixed[self.order]  # the active contact dofs (g stays last: none of it is fixed)
        off = len(self.order) - self.ng
        last = self._last
        be = Bm[self.e]
        t = self._t(be, force_scale)
        bn = Bm[self.order]
        bn[fixed_box] = 0.0
        bn[off:] -= t
        same_k = last is not None and np.array_equal(last[1], K.data)
        if same_k and np.array_equal(last[0], fixed_box):
            un = last[2].solve(bn)  # the same tangent and active set (elastic unloading): the same factors
            self.reused += 1
        elif self._is_elastic(K):  # the elastic tangent (an increment's first iteration, unloading)
            un = self._solve_free(K, fixed_box, bn, elastic=True)
            self.reused += 1
            self.elastic += 1
        elif same_k:  # the same tangent, another active set: the free box's factors and a capacitance
            un = self._solve_free(K, fixed_box, bn)
            self.reused += 1
        else:
            lu = spla.splu(self._box_matrix(K, fixed_box), permc_spec="NATURAL", diag_pivot_thresh=0.01,
                           options={"SymmetricMode": True})
            self._last = (fixed_box, K.data.copy(), lu)
            self._free = None
            un = lu.solve(bn)
        ug = un[off:]
        U = U0
        free = ~fixed_box
        U[self.order[free]] = un[free]
        if combine is not None:
            c = np.asarray(combine([U[:, k] for k in range(m)]), dtype=float)
            u = sum((c[k] * U[:, k] for k in range(1, m)), c[0] * U[:, 0])
            u[self.e] = self.factor.solve(np.concatenate([be @ c, t @ c + self.S @ (ug @ c)]))[: self.ne]
            return u
        xe = self.factor.solve(np.vstack([be, t + self.S @ ug]))[: self.ne]
        U[self.e] = xe
        return [U[:, k].copy() for k in range(m)]

    def _times_fixed(self, K: sp.csr_matrix, fixed: np.ndarray, U0: np.ndarray) -> np.ndarray:
        """``K @ U0`` for ``U0`` zero off the rows ``fixed``: only the tangent's entries in those
        columns (found through its column-major positions, computed once for its fixed sparsity),
        summed row by row in the stored order, as ``K @ U0`` does (the skipped terms are zeros).
        1.0 against 4.0 ms per call on the delta/delta_c = 200 path (1.7M entries, 636 fixed dofs, 2
        columns), the same numbers bit for bit."""
        if getattr(self, "_colpos", None) is None or len(self._colpos[0]) != K.nnz:
            rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
            pos = np.argsort(K.indices, kind="stable")  # by column, rows ascending
            ptr = np.r_[0, np.cumsum(np.bincount(K.indices, minlength=K.shape[1]))]
            self._colpos = (pos, ptr, rows)
        pos, ptr, rows = self._colpos
        fixed = np.unique(fixed)
        starts, lens = ptr[fixed], ptr[fixed + 1] - ptr[fixed]
        first = np.repeat(starts - np.r_[0, np.cumsum(lens)[:-1]], lens)
        sel = np.sort(pos[first + np.arange(int(lens.sum()))])
        r, a, c = rows[sel], K.data[sel], K.indices[sel]
        out = np.empty((K.shape[0], U0.shape[1]))
        for k in range(U0.shape[1]):
            out[:, k] = np.bincount(r, weights=a * U0[c, k], minlength=K.shape[0])
        return out

    def _is_elastic(self, K: sp.csr_matrix) -> bool:
        """``K`` is the elastic stiffness ``K^E`` (no element with a changed tangent, and the same
        numbers as the one whose box is factorised in :attr:`_free_el`)."""
        nonelastic = getattr(K, "nonelastic", None)
        if nonelastic is None or nonelastic.size:
            return False
        return self._free_el is None or np.array_equal(self._free_el.data, K.data)

    def _solve_free(self, K: sp.csr_matrix, fixed_box: np.ndarray, bn: np.ndarray,
                    elastic: bool = False) -> np.ndarray:
        """The box system with the active contact dofs ``F = fixed_box`` decoupled (``x_F = 0``,
        ``bn_F = 0``), from the factors of the box with no dof decoupled, ``M`` (built once per
        tangent): ``x = y - Z mu`` with ``y = M^-1 bn``, ``Z = M^-1 E_F`` (columns kept per dof while
        the tangent stays) and ``Z_F mu = y_F`` (the capacitance matrix ``E_F^T M^-1 E_F``, SPD of
        the size of the active set). Then ``x_F = 0`` and the other rows of ``M x = bn - E_F mu`` are
        the decoupled system's: exact, as a factorisation of that system. Elastic unloading keeps
        the tangent while the contact shrinks node by node: one factorisation and about one column
        per contact node replace a factorisation per Newton iteration."""
        free = self._free_el if elastic else self._free
        if free is None:
            M = self._box_matrix(K, np.zeros_like(fixed_box))
            lu = spla.splu(M, permc_spec="NATURAL", diag_pivot_thresh=0.01, options={"SymmetricMode": True})
            free = _FreeBox(lu, {}, M, K.data.copy())
            if elastic:
                self._free_el = free
            else:
                self._free = free
        x = self._capacitance_solve(free, fixed_box, bn)
        # one step of iterative refinement on the decoupled system (rows F: x_F = 0 already): the
        # capacitance form is not backward stable by itself, and the Newton loop, which solves for
        # the total displacement, would stall at its error (measured: out-of-balance 1.2e-8 of the
        # load on the coated path of tests/plasticity/test_condense.py; rtol is 1e-9)
        r = bn - free.M @ x
        r[fixed_box] = 0.0
        return x + self._capacitance_solve(free, fixed_box, r)

    @staticmethod
    def _capacitance_solve(free: _FreeBox, fixed_box: np.ndarray, bn: np.ndarray) -> np.ndarray:
        """One solve of ``_solve_free``'s decoupled system by the capacitance form, with the free
        box's factors and its columns of ``Z``."""
        lu, cols = free.lu, free.cols
        F = np.flatnonzero(fixed_box)
        new = [i for i in F if i not in cols]
        if new:
            E = np.zeros((len(fixed_box), len(new)))
            E[new, np.arange(len(new))] = 1.0
            Z = lu.solve(E)
            for k, i in enumerate(new):
                cols[i] = Z[:, k]
        y = lu.solve(bn)
        if F.size == 0:
            return y
        Z = np.column_stack([cols[i] for i in F])
        with blas_threads(1):  # a product of the box's size by the active set's: threads only spin
            mu = np.linalg.solve(Z[F], y[F])
            x = y - Z @ mu
        x[F] = 0.0
        return x

    def _template(self, KE: sp.csr_matrix) -> None:
        """The box matrix's CSC structure in :attr:`order` (the tangent's entries on the box and the
        dense ``g x g`` block) and where each tangent entry and each entry of ``D`` goes in it."""
        N, off = len(self.order), len(self.order) - self.ng
        pos = sp.csr_matrix((np.arange(1, KE.nnz + 1, dtype=float), KE.indices, KE.indptr), shape=KE.shape)
        Kp = pos[self.order][:, self.order].tocoo()
        self._kpos = Kp.data.astype(np.int64) - 1  # the entry's place in the tangent's CSR data
        self._nnz = KE.nnz
        rows = np.concatenate([Kp.row, self.Di + off]).astype(np.int64)
        cols = np.concatenate([Kp.col, self.Dj + off]).astype(np.int64)
        keys, slot = np.unique(cols * N + rows, return_inverse=True)
        self._kslot, self._dslot = slot[: len(Kp.data)], slot[len(Kp.data):]
        self._indices = (keys % N).astype(np.int32)
        self._indptr = np.r_[0, np.cumsum(np.bincount(keys // N, minlength=N))].astype(np.int32)
        slot_col = np.repeat(np.arange(N), np.diff(self._indptr))
        diag = np.flatnonzero(self._indices == slot_col)
        self._diag = np.empty(N, dtype=np.int64)
        self._diag[self._indices[diag]] = diag
        # one gather per call: each slot's place in the tangent's data (slots of D alone read entry 0,
        # then weighted by 0), and each slot's transposed slot (the structure is symmetric), so that
        # an active dof's row is found from its column
        self._src = np.zeros(len(self._indices), dtype=np.int64)
        self._src[self._kslot] = self._kpos
        has_k = np.zeros(len(self._indices))
        has_k[self._kslot] = 1.0
        self._dhas = has_k[self._dslot]
        self._Dflat = self.D.ravel()
        tkeys = self._indices.astype(np.int64) * N + slot_col  # the slot (j, i) of slot (i, j)
        self._tslot = np.searchsorted(keys, tkeys)
        if not np.array_equal(keys[np.minimum(self._tslot, len(keys) - 1)], tkeys):
            raise CoatHertzError("elastic condensation: the box structure is not symmetric (internal error)")

    def _box_matrix(self, K: sp.csr_matrix, fixed_box: np.ndarray) -> sp.csc_matrix:
        """The box's matrix ``K_nn - K_ge K_ee^-1 K_eg`` in :attr:`order` (``g`` last), the rows
        and columns of the active contact dofs ``fixed_box`` decoupled (their diagonal entry kept,
        right-hand side 0): one gather from the tangent's data into the stored structure."""
        if K.nnz != self._nnz:  # the gather needs the tangent's fixed sparsity (the assembler's)
            raise CoatHertzError("elastic condensation: the tangent's sparsity changed (internal error)")
        data = K.data.take(self._src)
        data[self._dslot] = data[self._dslot] * self._dhas - self._Dflat
        F = np.flatnonzero(fixed_box)
        if F.size:
            d = data[self._diag[F]]
            cols = np.concatenate([np.arange(self._indptr[i], self._indptr[i + 1]) for i in F])
            data[cols] = 0.0
            data[self._tslot[cols]] = 0.0
            data[self._diag[F]] = d
        N = len(self.order)
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(N, N))


def box_for(boxes: ElementBoxes, nonelastic: np.ndarray, r_active: float, s0: float,
            old: tuple[float, float] | None) -> tuple[float, float]:
    """Box ``(r_N, t_N)`` [m] holding the elements with a changed tangent and the contact out to
    ``r_active``, :data:`BOX_GROWTH` times larger (at least ``4 s0``, ``s0`` the finest element
    size; depth at least the radius: the plastic zone under a sphere reaches about one contact
    radius deep), and never smaller than ``old``."""
    r_need = max(r_active, float(boxes.r_max[nonelastic].max(initial=0.0)), 4 * s0)
    t_need = max(float(boxes.t_max[nonelastic].max(initial=0.0)), r_need)
    r_n, t_n = BOX_GROWTH * r_need, BOX_GROWTH * t_need
    if old is not None:
        r_n, t_n = max(r_n, old[0]), max(t_n, old[1])
    return r_n, t_n
