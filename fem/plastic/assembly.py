r"""Quadrature-point assembly for non-linear laws, with the B-bar (Q2 / P1-projected volume) strain.

For elastic-plastic flow the plastic strain is isochoric, so with full integration a pure
displacement element must satisfy (nearly) incompressible kinematics at every quadrature
point and can lock (Nagtegaal, Parks & Rice 1974). The B-bar method (Hughes 1980, *Int. J.
Numer. Meth. Eng.* 15:1413; Simo & Hughes 1998, Section 4.4) replaces the volumetric strain by
its element-wise :math:`L^2` projection onto a smaller space, here the linear polynomials
:math:`\{1, r, z\}` (weight :math:`2\pi r`):

.. math:: \bar\varepsilon = \varepsilon - \tfrac13 (\operatorname{tr}\varepsilon)\, m
          + \tfrac13\, \Pi_1(\operatorname{tr}\varepsilon)\, m ,\qquad
          \operatorname{tr}\varepsilon = \partial_r u_r + u_r/r + \partial_z u_z .

With the Q2 displacement this is the Q2/P1-discontinuous mixed element with the pressure
condensed out element by element, an inf-sup stable pair; any law of
:mod:`coathertz.fem.material` (or :mod:`coathertz.fem.plastic.j2`) is evaluated with :math:`\bar\varepsilon`
and the same :math:`\bar B` enters the internal force and the tangent
(:math:`F = \int \bar B^T \sigma\, 2\pi r`, :math:`K = \int \bar B^T D\, \bar B\, 2\pi r`), so the
tangent is consistent. ``bbar=False`` gives the plain displacement form (for comparison in the
locking test, ``tests/plasticity/test_hill_sphere.py``).

Arrays: ``B[4, 18, nel, nq]`` (strain of each local shape function), element dofs
``[18, nel]`` from scikit-fem's vector Q2 basis. The tangent's sparsity is fixed, so each
element entry's place in the CSR data is found once and every assembly is one ``bincount``;
elements whose tangent is elastic at every quadrature point keep their elastic stiffness
(computed once per region; the comparison with the elastic tangent is exact, since the return
mapping leaves elastic points' tangent untouched): the tangent is the elastic stiffness, assembled
once, plus the change of the other elements' matrices; each region's strain operator is sliced
once. Measured on the quick ``indentation`` path (513 elements, 31 factorisations): 1.4-1.7 s
CPU against 2.6-2.9 s before, the README's approach path with unloading (default mesh, 95
factorisations) 42 s against 52 s; the same numbers to 1e-14.

In the Newton loop (``evaluate(..., stresses=False)``) the law is evaluated only at the elements
that may depart from elasticity (a plastic history or a trial state beyond the yield surface,
found from the strain of every point by one sparse product), and the internal force is the
elastic stiffness times ``u`` plus their correction ``int B^T (sigma - D_el eps)``: 17 ms against
31 ms per call with 302 of 3528 elements yielded (README load path, 1 BLAS thread), the internal
force the same to 4e-13 of the load.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis

from coathertz.fem import forms


class BBarAssembler:
    """Strain, internal force and tangent at quadrature points of a vector Q2 ``basis``.

    Parameters
    ----------
    basis
        scikit-fem vector basis (the FE model's ``basis``).
    regions
        ``(elements, law)`` pairs covering the elements that carry material.
    bbar
        Use the projected volumetric strain (default) or the plain displacement form.
    """

    def __init__(self, basis: Basis, regions: list, bbar: bool = True) -> None:
        self.basis = basis
        self.regions = regions
        self.bbar = bbar
        self.n = basis.N
        r = basis.global_coordinates()
        rq, zq = np.asarray(r[0]), np.asarray(r[1])
        self.rq, self.zq = rq, zq
        self.w = np.asarray(basis.dx) * 2.0 * np.pi * rq  # [nel, nq]
        nloc = basis.Nbfun
        B = np.empty((4, nloc, *rq.shape))
        for a in range(nloc):
            phi = basis.basis[a][0]
            B[:, a] = np.array(forms.strain(phi, rq))
        if bbar:
            bv = B[0] + B[1] + B[2]  # [18, nel, nq]
            rc = (rq * self.w).sum(-1) / self.w.sum(-1)
            zc = (zq * self.w).sum(-1) / self.w.sum(-1)
            hc = np.sqrt(self.w.sum(-1) / (2 * np.pi * rc))  # ~ element size
            P = np.stack([np.ones_like(rq), (rq - rc[:, None]) / hc[:, None],
                          (zq - zc[:, None]) / hc[:, None]])
            M = np.einsum("keq,leq,eq->ekl", P, P, self.w)
            rhs = np.einsum("keq,aeq,eq->eka", P, bv, self.w)
            c = np.linalg.solve(M, rhs)  # [nel, 3, 18]
            bv_bar = np.einsum("keq,eka->aeq", P, c)
            B[:3] += ((bv_bar - bv) / 3.0)[None]
        self.B = B
        self.edofs = np.asarray(basis.element_dofs)  # [18, nel]
        nl = nloc
        self._rows = np.broadcast_to(self.edofs[:, None, :], (nl, nl, self.edofs.shape[1])).transpose(2, 0, 1)
        self._cols = np.broadcast_to(self.edofs[None, :, :], (nl, nl, self.edofs.shape[1])).transpose(2, 0, 1)
        # the tangent's sparsity is fixed: each element entry's place in the CSR data, once
        rows = np.concatenate([self._rows[els].ravel() for els, _ in regions])
        cols = np.concatenate([self._cols[els].ravel() for els, _ in regions])
        keys, self._slot = np.unique(rows.astype(np.int64) * self.n + cols, return_inverse=True)
        self._indices = (keys % self.n).astype(np.int32)
        self._indptr = np.r_[0, np.cumsum(np.bincount(keys // self.n, minlength=self.n))].astype(np.int32)
        self._elastic_Ke: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # region -> (D_el, Ke_el)
        self._el_data: np.ndarray | None = None  # CSR data of the elastic stiffness, once
        ends = np.cumsum([len(els) * nl * nl for els, _ in regions])
        self._slot_r = [self._slot[e - len(els) * nl * nl: e].reshape(len(els), nl, nl)
                        for e, (els, _) in zip(ends, regions, strict=True)]
        # each region's strain operator, weights and dofs, sliced once (not copied at every call)
        self._Bq = [np.ascontiguousarray(B[:, :, els]) for els, _ in regions]
        # and element-major, ``Be[nel, nq * 4, 18]`` (row ``4 q + i``: strain component ``i`` at point
        # ``q``): a subset of elements is one contiguous gather, their stiffness batched products
        self._Be = [np.ascontiguousarray(Bq.transpose(2, 3, 0, 1)).reshape(Bq.shape[2], -1, nloc)
                    for Bq in self._Bq]
        self._wq = [self.w[els] for els, _ in regions]
        self._eq = [self.edofs[:, els] for els, _ in regions]

    # -- quadrature-point fields ----------------------------------------------------------------
    def strain(self, u: np.ndarray, elements: np.ndarray) -> np.ndarray:
        """``eps_bar[4, nel_region, nq]`` of the nodal displacement ``u`` on ``elements``."""
        ue = u[self.edofs[:, elements]]
        return np.einsum("iaeq,ae->ieq", self.B[:, :, elements], ue)

    def evaluate(self, u: np.ndarray, states: list, tangent: bool = True, stresses: bool = True):
        """Stresses, tangents and trial states of every region at displacement ``u``.

        Returns ``(F_int, K or None, sigmas, new_states)``. With the tangent, ``K.nonelastic``
        holds the (global) indices of the elements whose tangent is not the elastic one.
        ``stresses=False`` (with the tangent; the Newton loop) returns ``None`` for ``sigmas`` and
        runs the law only where it may depart from elasticity (``_evaluate_inelastic``).
        """
        if tangent and not stresses:
            return self._evaluate_inelastic(u, states)
        F = np.zeros(self.n)
        slots, dvals, sigmas, new_states, nonelastic = [], [], [], [], []
        for k, ((els, law), st) in enumerate(zip(self.regions, states, strict=True)):
            Bq, w, ed = self._Bq[k], self._wq[k], self._eq[k]
            eps = np.einsum("iaeq,ae->ieq", Bq, u[ed])
            sig, D, st_new = law.stress(eps, st)
            fe = np.einsum("iaeq,ieq->ae", Bq, sig * w)
            F += np.bincount(ed.ravel(), weights=fe.ravel(), minlength=self.n)
            if tangent:
                D = np.broadcast_to(D, (4, 4, *eps.shape[1:]))
                D_el, Ke = self._elastic(k, els, law)
                # elements whose tangent is the elastic one at every point keep their elastic
                # stiffness (the same numbers); the others are integrated again
                changed = np.nonzero(np.any(D != D_el[:, :, None, None], axis=(0, 1, 3)))[0]
                nonelastic.append(els[changed])
                if changed.size:  # the change from the elastic matrices, added to their assembly below
                    Kc = self._element_stiffness(self._Be[k][changed], D[:, :, changed], w[changed])
                    dvals.append((Kc - Ke[changed]).ravel())
                    slots.append(self._slot_r[k][changed].ravel())
            sigmas.append(sig)
            new_states.append(st_new)
        K = self._tangent(slots, dvals, nonelastic) if tangent else None
        return F, K, sigmas, new_states

    def _tangent(self, slots: list, dvals: list, nonelastic: list) -> sp.csr_matrix:
        """The elastic stiffness (assembled once) plus the changes ``dvals`` of the elements whose
        tangent departs from it, at their matrix ``slots``; ``K.nonelastic`` lists those elements."""
        if slots:
            cat = (lambda a: a[0]) if len(slots) == 1 else np.concatenate  # one region: no copy
            data = np.bincount(cat(slots), weights=cat(dvals), minlength=len(self._indices))
            data += self._elastic_data()
        else:
            data = self._elastic_data().copy()
        K = sp.csr_matrix((data, self._indices, self._indptr), shape=(self.n, self.n))
        K.nonelastic = np.concatenate(nonelastic) if nonelastic else np.zeros(0, dtype=np.int64)
        return K

    def _evaluate_inelastic(self, u: np.ndarray, states: list):
        """:meth:`evaluate` without the stresses, the law evaluated only at the elements that may
        depart from elasticity.

        ``F_int = K^E u + sum_e int B^T (sigma - D_el eps) 2 pi r``: the elastic stiffness of every
        element (assembled once) times ``u``, corrected at the elements ``P`` where the law's
        stress is not ``D_el eps``. A law with ``inelastic_points(eps, state)`` (the J2 law: plastic
        history or a trial state beyond the yield surface, the return mapping's own test) names
        them from the strain of every point (one sparse product); a linear law has none; any
        other law is evaluated everywhere. The law's return mapping, the new state and the tangent
        then concern ``P`` only; the other points keep their state and the elastic tangent, as in
        :meth:`evaluate`, whose stresses and tangent at ``P`` are the same numbers (``F_int``
        agrees to round-off). Measured on the README load path (default mesh, 3528 elements, at
        most 302 yielded): 8-13 ms per call against 18-38 ms.
        """
        F = self._elastic_csr() @ u
        slots, dvals, new_states, nonelastic = [], [], [], []
        for k, ((els, law), st) in enumerate(zip(self.regions, states, strict=True)):
            D_el, Ke = self._elastic(k, els, law)
            if law.is_linear:
                new_states.append(st)
                continue
            w = self._wq[k]
            full = hasattr(law, "inelastic_points") and all(
                np.shape(v)[-2:] == w.shape for v in st.values())
            if full:
                eps = (self._bsp(k) @ u).reshape(4, *w.shape)
                P = np.flatnonzero(law.inelastic_points(eps, st).any(axis=-1))
            else:  # any other law, or a state not stored per point: evaluated everywhere
                P = np.arange(len(els))
            if P.size == 0:
                new_states.append(st)
                continue
            BeP, wP, edP = self._Be[k][P], w[P], self._eq[k][:, P]
            eps_P = eps[:, P] if full else np.einsum("iaeq,ae->ieq", self._Bq[k][:, :, P], u[edP])
            st_P = {key: v[..., P, :] for key, v in st.items()} if full else st
            sig, D, st_newP = law.stress(eps_P, st_P)
            corr = (sig - np.einsum("ij,jeq->ieq", D_el, eps_P)) * wP
            # fe[e, a] = sum_{q, i} Be[e, 4 q + i, a] corr[i, e, q]
            fe = np.matmul(corr.transpose(1, 2, 0).reshape(len(P), 1, -1), BeP)[:, 0, :]
            F += np.bincount(edP.T.ravel(), weights=fe.ravel(), minlength=self.n)
            if full:
                st_new = {key: v.copy() for key, v in st.items()}
                for key, v in st_newP.items():
                    st_new[key][..., P, :] = v
            else:
                st_new = st_newP
            new_states.append(st_new)
            D = np.broadcast_to(D, (4, 4, *eps_P.shape[1:]))
            changed = np.nonzero(np.any(D != D_el[:, :, None, None], axis=(0, 1, 3)))[0]
            nonelastic.append(els[P[changed]])
            if changed.size:
                Kc = self._element_stiffness(BeP[changed], D[:, :, changed], wP[changed])
                dvals.append(np.subtract(Kc, Ke[P[changed]], out=Kc).ravel())
                slots.append(self._slot_r[k][P[changed]].ravel())
        return F, self._tangent(slots, dvals, nonelastic), None, new_states

    def _bsp(self, k: int) -> sp.csr_matrix:
        """Region ``k``'s strain operator as a sparse matrix, ``eps.ravel() = B u`` (built once)."""
        if not hasattr(self, "_bsp_cache"):
            self._bsp_cache: dict[int, sp.csr_matrix] = {}
        if k not in self._bsp_cache:
            Bq, ed = self._Bq[k], self._eq[k]
            ne, nq = Bq.shape[2:]
            rows = np.broadcast_to(np.arange(4 * ne * nq).reshape(4, 1, ne, nq), Bq.shape)
            cols = np.broadcast_to(ed[None, :, :, None], Bq.shape)
            self._bsp_cache[k] = sp.csr_matrix((Bq.ravel(), (rows.ravel(), cols.ravel())),
                                               shape=(4 * ne * nq, self.n))
        return self._bsp_cache[k]

    def _elastic_csr(self) -> sp.csr_matrix:
        """The elastic stiffness of every region (``K^E``; assembled once)."""
        if not hasattr(self, "_el_csr"):
            self._el_csr = sp.csr_matrix((self._elastic_data(), self._indices, self._indptr),
                                         shape=(self.n, self.n))
        return self._el_csr

    def _elastic_data(self) -> np.ndarray:
        """CSR data of the elastic stiffness of every region (assembled once)."""
        if self._el_data is None:
            self._el_data = self.elastic_matrix(np.ones(self.w.shape[0], dtype=bool)).data
        return self._el_data

    def elastic_matrix(self, mask: np.ndarray) -> sp.csr_matrix:
        """The elastic stiffness of the elements in ``mask`` (boolean over all elements; the
        others contribute nothing), from the same cached element matrices as :meth:`evaluate`
        (the same numbers, so that a split ``K = K^E + K^N`` is exact to round-off in the sum)."""
        vals = []
        for k, (els, law) in enumerate(self.regions):
            Ke = self._elastic(k, els, law)[1]
            vals.append((Ke * mask[els][:, None, None]).ravel())
        data = np.bincount(self._slot, weights=np.concatenate(vals), minlength=len(self._indices))
        return sp.csr_matrix((data, self._indices, self._indptr), shape=(self.n, self.n))

    @staticmethod
    def _element_stiffness(Be: np.ndarray, D: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``Ke[nel, 18, 18] = sum_q w_q B_q^T D_q B_q`` of elements with the element-major strain
        operator ``Be[nel, nq * 4, 18]``, the tangent ``D[4, 4, nel, nq]`` and the weights
        ``w[nel, nq]``: two batched matrix products (``D_q B_q`` per point, then ``B^T`` times the
        stacked ``w D B``). Measured on the delta/delta_c = 200 path's late iterations (1573
        elements, 1 BLAS thread): 6 ms against 29 ms for the einsum over ``[4, 18, nel, nq]``."""
        ne, nl = Be.shape[0], Be.shape[2]
        wD = D.transpose(2, 3, 0, 1) * w[:, :, None, None]  # [nel, nq, 4, 4]
        DB = np.matmul(wD, Be.reshape(ne, -1, 4, nl))  # [nel, nq, 4, 18]
        return np.matmul(Be.transpose(0, 2, 1), DB.reshape(ne, -1, nl))

    def _elastic(self, k: int, els: np.ndarray, law) -> tuple[np.ndarray, np.ndarray]:
        """The elastic tangent of region ``k``'s law (at zero strain, no history) and its element
        stiffnesses, computed once."""
        if k not in self._elastic_Ke:
            D_el = np.array(law.stress(np.zeros((4, 1, 1)), law.initial_state((1, 1))
                                       if hasattr(law, "initial_state") else {})[1])[:, :, 0, 0]
            shape = (4, 4, len(els), self.w.shape[1])
            D = np.broadcast_to(D_el[:, :, None, None], shape)
            Ke = self._element_stiffness(self._Be[k], D, self._wq[k])
            self._elastic_Ke[k] = (D_el, Ke)
        return self._elastic_Ke[k]
