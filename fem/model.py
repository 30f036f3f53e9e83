"""The discrete problem: bases, stiffness, boundary conditions and contact candidates.

Unknowns are the Q2 displacement ``u = (u_r, u_z)`` on the whole mesh and, in regions treated
with the mixed u-p form, a continuous Q1 pressure on that region only (Taylor-Hood Q2-Q1;
the pressure may jump across the coating/substrate interface because each region has its own
pressure nodes). Essential conditions: ``u_r = 0`` on the axis, the far field on the outer
boundary (:mod:`coathertz.fem.farfield`), ``u = 0`` on a rigid base. The contact candidates
are the ``u_z`` dofs of surface nodes with ``r <= r_fine``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementQuad1, ElementQuad2, ElementVector, FacetBasis, LinearForm, asm
from skfem.assembly import Dofs
from skfem.quadrature import get_quadrature

from coathertz.fem import forms
from coathertz.fem.affine import RectQ2, dof_locations, ring_weights
from coathertz.fem.material import LinearElastic, MaterialLaw
from coathertz.fem.mesh import LayeredMesh
from coathertz.fem.ordering import grid_indices
from coathertz.materials import Material

INTORDER = 4


@dataclass
class Region:
    """A set of elements with one material law; ``mixed`` selects the u-p form."""

    elements: np.ndarray
    law: MaterialLaw
    mixed: bool = False


@dataclass
class FEModel:
    """Assembled axisymmetric model of one layered mesh (see module docstring)."""

    lm: LayeredMesh
    regions: list[Region]
    farfield_material: Material | None
    farfield: object
    legacy_assembly: bool = False  # skfem's generic assembly (the benchmark's "before" path)

    def __post_init__(self) -> None:
        mesh = self.lm.mesh
        self.elem = ElementVector(ElementQuad2())
        self.dofs = Dofs(mesh, self.elem)  # the dof layout; the quadrature basis only on demand
        self.n_u = self.dofs.N
        self._p_blocks = []  # (pressure dofs, coupling, compliance, scale per dof) per mixed region
        self._p_locs: list[np.ndarray] = []  # (r, z) of the pressure dofs of each mixed region
        self._K: sp.csr_matrix | None = None
        self.doflocs = dof_locations(mesh, self.elem, self.dofs)
        self.r_dof, self.z_dof = self.doflocs[0], self.doflocs[1]
        comp = np.zeros(self.n_u, dtype=int)
        comp[self.dofs.nodal_dofs[1]] = 1
        comp[self.dofs.facet_dofs[1]] = 1
        comp[self.dofs.interior_dofs[1]] = 1
        self.comp = comp
        tol = 1e-9 * self.lm.a_ref
        self.top = np.nonzero((np.abs(self.z_dof) < tol) & (comp == 1))[0]
        self.top = self.top[np.argsort(self.r_dof[self.top])]
        # nodal area weights int phi_i 2 pi r ds of the surface u_z dofs
        w_top = ring_weights(self.r_dof[self.top])
        if w_top is None:  # not one line of facets: skfem's facet quadrature
            top_facets = mesh.facets_satisfying(lambda x: np.abs(x[1]) < tol)
            fb = FacetBasis(mesh, self.elem, facets=top_facets, intorder=INTORDER)
            self.weights_all = asm(LinearForm(lambda v, w: v[1] * 2 * np.pi * w.x[0]), fb)
        else:
            self.weights_all = np.zeros(self.n_u)
            self.weights_all[self.top] = w_top
        self.tie = self._tie_pairs()

    @cached_property
    def basis(self) -> Basis:
        """The skfem Q2 vector basis at the quadrature points (post-processing, material-law paths;
        the linear stiffness does without it, :mod:`coathertz.fem.affine`)."""
        return Basis(self.lm.mesh, self.elem, intorder=INTORDER, dofs=self.dofs)

    @cached_property
    def rect(self) -> RectQ2 | None:
        """The rectangle tables of the mesh (:class:`coathertz.fem.affine.RectQ2`), ``None`` if an
        element is not an axis-aligned rectangle."""
        try:
            return RectQ2.build(self.lm.mesh, INTORDER)
        except ValueError:
            return None

    def quad_strain(self, u: np.ndarray) -> np.ndarray:
        """Strain ``[4, nel, nq]`` of the displacement part of ``u`` at the quadrature points (the
        rectangle tables where they apply, else skfem's basis, :func:`~coathertz.fem.forms.quad_strain`)."""
        u = u[: self.n_u]
        if self.rect is None:
            return forms.quad_strain(self.basis, u)
        return self.rect.strain(u, self.dofs.element_dofs)

    def quad_points(self) -> np.ndarray:
        """``(r, z)`` of the quadrature points ``[2, nel, nq]``."""
        if self.rect is None:
            return np.asarray(self.basis.global_coordinates())
        return np.array([self.rect.r, self.rect.z])

    @property
    def nq(self) -> int:
        """Quadrature points per element."""
        return len(get_quadrature(self.elem.refdom, INTORDER)[1])

    def _tie_pairs(self) -> np.ndarray:
        """Frictionless interfaces over an elastic body (:meth:`LayeredMesh.split_depths`): pairs
        ``[2, n]`` of ``u_z`` dofs at the same point of each such ``z = -d``, one of each side (not
        on the outer boundary, which prescribes both). They are tied by Lagrange multipliers in
        :meth:`stiffness`; ``u_r`` slips freely."""
        lm = self.lm
        tol = 1e-9 * lm.a_ref
        pairs = [np.zeros((2, 0), dtype=np.int64)]
        for d in lm.split_depths():
            on = np.nonzero((np.abs(self.z_dof + d) < tol) & (self.comp == 1)
                            & (np.abs(self.r_dof - lm.L) > tol * lm.L / lm.a_ref))[0]
            on = on[np.lexsort((on, self.r_dof[on]))]
            pd = on.reshape(-1, 2).T
            if not np.allclose(self.r_dof[pd[0]], self.r_dof[pd[1]], rtol=0, atol=tol):
                raise RuntimeError("frictionless interface: unmatched interface nodes (internal error)")
            pairs.append(pd)
        return np.hstack(pairs)

    # -- dofs ----------------------------------------------------------------------------
    @property
    def candidates(self) -> np.ndarray:
        """Surface ``u_z`` dofs inside the fine zone (sorted by r)."""
        return self.top[self.r_dof[self.top] <= self.lm.r_fine * (1 + 1e-9)]

    @property
    def n_dofs(self) -> int:
        return self.n_u + sum(len(b[0]) for b in self._p_blocks) + self.tie.shape[1]

    def dirichlet(self, W: float) -> tuple[np.ndarray, np.ndarray]:
        """Essential dofs and their values for load ``W``."""
        tol = 1e-9 * self.lm.a_ref
        r, z, comp = self.r_dof, self.z_dof, self.comp
        axis = np.nonzero((r < tol) & (comp == 0))[0]
        outer = (np.abs(r - self.lm.L) < tol * self.lm.L / self.lm.a_ref) | (
            np.abs(z + self.lm.D) < tol * self.lm.L / self.lm.a_ref
        )
        if self.lm.rigid_base and self.lm.bottom_interface == "frictionless":
            # the coating slides on the rigid base: only u_z = 0 on the bottom (r = L stays clamped)
            tol_far = tol * self.lm.L / self.lm.a_ref
            bottom = np.abs(z + self.lm.D) < tol_far
            outer = outer & ~(bottom & (comp == 0) & (np.abs(r - self.lm.L) > tol_far))
        outer_dofs = np.nonzero(outer)[0]
        if self.lm.rigid_base or self.farfield_material is None:
            vals_outer = np.zeros(len(outer_dofs))
        else:
            uv = self.farfield.values(r[outer_dofs], z[outer_dofs], W, self.farfield_material)
            vals_outer = uv[comp[outer_dofs], np.arange(len(outer_dofs))]
        dofs = np.concatenate([axis, outer_dofs])
        vals = np.concatenate([np.zeros(len(axis)), vals_outer])
        dofs, idx = np.unique(dofs, return_index=True)
        return dofs, vals[idx]

    # -- assembly ------------------------------------------------------------------------
    def stiffness(self) -> sp.csr_matrix:
        """System matrix of the linear-elastic model (displacement + mixed-region pressures)."""
        if self._K is not None:
            return self._K
        mesh = self.lm.mesh
        nel = mesh.t.shape[1]
        nq = self.nq
        lam = np.zeros((nel, nq))
        mu = np.zeros((nel, nq))
        blocks = []
        p_locs = []
        for reg in self.regions:
            if not isinstance(reg.law, LinearElastic):
                raise TypeError("stiffness() is the linear-elastic fast path; use loading.tangent")
            lam_r, mu_r = reg.law.lame
            mu[reg.elements] = mu_r
            lam[reg.elements] = 0.0 if reg.mixed else lam_r
            if reg.mixed:
                ub = Basis(mesh, self.elem, intorder=INTORDER, elements=reg.elements)
                pb = Basis(mesh, ElementQuad1(), intorder=INTORDER, elements=reg.elements)
                inv_lam = 0.0 if math.isinf(lam_r) else 1.0 / lam_r
                Bm = asm(forms.pressure_coupling, pb, ub)
                C = asm(forms.pressure_compliance, pb, inv_lam=inv_lam)
                pd = np.unique(pb.element_dofs)
                blocks.append((pd, Bm.tocsc()[:, pd], C.tocsr()[pd][:, pd]))
                p_locs.append(pb.doflocs[:, pd])
        if self.legacy_assembly:
            K = asm(forms.elasticity, self.basis, lam=lam, mu=mu)
        else:  # == asm(forms.elasticity, ...) to round-off, about ten times faster
            K = self._elasticity(lam, mu)
        blocks = [self._scaled(K, *b) for b in blocks]  # unknowns p / s (balanced pivots)
        self._p_blocks = blocks
        self._p_locs = p_locs
        if blocks:
            cols = sp.hstack([b[1] for b in blocks])
            C = sp.block_diag([b[2] for b in blocks])
            K = sp.bmat([[K, cols], [cols.T, C]])
        if self.tie.shape[1]:
            # multipliers t_k (the interface's normal force, scaled) with u_z(coating) = u_z(substrate)
            n, m = K.shape[0], self.tie.shape[1]
            scale = float(np.median(K.diagonal()[self.tie[0]]))
            k = np.arange(m)
            T = sp.csr_matrix((np.r_[np.full(m, scale), np.full(m, -scale)], (np.r_[k, k], self.tie.ravel())),
                              shape=(m, n))
            K = sp.bmat([[K, T.T], [T, None]])
        self._K = sp.csr_matrix(K)
        return self._K

    @staticmethod
    def _scaled(K: sp.spmatrix, pd: np.ndarray, Bp: sp.csc_matrix, Cp: sp.csr_matrix) -> tuple:
        """A mixed region's blocks for the scaled pressure unknowns ``p_hat = p / s``.

        ``s_j = sqrt(k_j / d_j)`` with ``d_j = sum_i B_ij^2 / K_ii`` (the diagonal of
        ``B^T diag(K)^-1 B``, the pressure's Schur complement to first order) and ``k_j`` the mean
        of ``K_ii`` over the displacements it couples to (weights ``|B_ij|``): then a pressure
        pivot, ``~ s_j^2 d_j = k_j``, is of the size of its neighbours' displacement pivots on every
        element size of the graded mesh. The former ``s = mu`` left them apart by the element size
        (``B ~ mu r s0``, ``K ~ mu r``), i.e. 1e6-1e7: measured 1-norm condition of the system with
        the essential dofs removed, nu_c = 0.5 layer on a rigid base (benchmark case, 15k dofs):
        1.2e23 with ``s = mu``, 1.3e10 with this scaling; the refactorising and the condensed solve
        then agree to 3e-14 instead of 6e-8 (``tests/fem/test_condensed.py``).
        Returns ``(pd, B diag(s), diag(s) C diag(s), s)``.
        """
        dK = K.diagonal()
        aB = abs(Bp)
        d = aB.multiply(aB).T @ (1.0 / dK)
        k = (aB.T @ dK) / np.asarray(aB.sum(axis=0)).ravel()
        s = np.sqrt(k / d)
        S = sp.diags(s)
        return pd, (Bp @ S).tocsc(), (S @ Cp @ S).tocsr(), s

    def _elasticity(self, lam: np.ndarray, mu: np.ndarray) -> sp.csr_matrix:
        """The stiffness from the rectangle tables of the tensor mesh (:mod:`coathertz.fem.affine`;
        skfem's generic assembly if an element is not an axis-aligned rectangle)."""
        q = self.rect
        if q is None:
            return asm(forms.elasticity, self.basis, lam=lam, mu=mu)
        return q.elasticity(lam, mu, self.dofs.element_dofs, self.n_u)

    def dof_locations(self) -> np.ndarray:
        """``(r, z)`` of every unknown of :meth:`stiffness` (``[2, n_dofs]``; call it after assembly)."""
        return np.hstack([self.doflocs, *self._p_locs, self.doflocs[:, self.tie[0]]])

    def dof_grid(self) -> tuple[np.ndarray, np.ndarray]:
        """Indices ``(i, j)`` of every unknown's node in the tensor grid of Q2 nodes (the
        geometry the condensed solve orders by, :mod:`coathertz.fem.ordering`)."""
        loc = self.dof_locations()
        return grid_indices(loc[0]), grid_indices(loc[1])

    def near_null_space(self, free: np.ndarray) -> np.ndarray:
        """Near-null space for smoothed aggregation on the ``free`` dofs: ``u_z = 1``, ``u_r = 1``."""
        B = np.zeros((self.n_u, 2))
        B[self.comp == 1, 0] = 1.0
        B[self.comp == 0, 1] = 1.0
        return B[free[free < self.n_u]] if np.all(free < self.n_u) else None
