"""Quadrature tables of the Q2 element on parallelogram quadrilaterals (the tensor-product mesh).

scikit-fem's :class:`skfem.CellBasis` maps every basis function through the generic
isoparametric mapping (a Jacobian inverse per function and quadrature point); on the meshes of
:mod:`coathertz.fem.mesh` every element is a rectangle, so the mapping is affine,

.. math:: x(\\xi, \\eta) = p_0 + (p_1 - p_0)\\,\\xi + (p_3 - p_0)\\,\\eta ,\\qquad
          \\nabla \\phi = J^{-T} \\hat\\nabla \\hat\\phi ,

(``p_k`` the element's vertices, ``(xi, eta)`` in skfem's reference square ``[0, 1]^2``) and the
reference values and gradients of the nine Q2 functions are tabulated once. Same quadrature rule
as ``Basis(mesh, ElementVector(ElementQuad2()), intorder=INTORDER)``, same numbers to round-off
(``tests/fem/test_forms.py``), about ten times cheaper to build.

:func:`dof_locations` gives the global dof locations without any quadrature (the model's dof
layout: axis, surface, candidates) so that the full skfem basis is built only when a
post-processing step asks for it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import ElementQuad2, MeshQuad
from skfem.assembly import Dofs
from skfem.quadrature import get_quadrature


def _bilinear(mesh: MeshQuad, xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Global coordinates ``[2, nel, npts]`` of reference points (skfem's bilinear map)."""
    p = mesh.p[:, mesh.t]  # [2, 4, nel]
    N = np.array([(1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta])  # [4, npts]
    return np.einsum("dve,vq->deq", p, N)


def dof_locations(mesh: MeshQuad, elem, dofs: Dofs) -> np.ndarray:
    """``(r, z)`` of every global dof ``[2, N]`` (as ``skfem.Basis.doflocs``, without quadrature)."""
    loc = _bilinear(mesh, elem.doflocs[:, 0], elem.doflocs[:, 1])  # [2, nel, nbfun]
    out = np.zeros((2, dofs.N))
    for j in range(dofs.element_dofs.shape[0]):
        out[:, dofs.element_dofs[j]] = loc[:, :, j]
    return out


@dataclass(frozen=True)
class AffineQ2:
    """Q2 basis data at the quadrature points of every (parallelogram) element.

    Attributes
    ----------
    r
        Radius of the quadrature points ``[nel, nq]``.
    dx
        Quadrature weight times the Jacobian determinant ``[nel, nq]``.
    phi
        Reference values of the nine scalar Q2 functions ``[9, nq]`` (the same on every element).
    d_r, d_z
        Physical derivatives of the nine functions ``[nel, 9, nq]``.
    """

    r: np.ndarray
    dx: np.ndarray
    phi: np.ndarray
    d_r: np.ndarray
    d_z: np.ndarray

    @classmethod
    def build(cls, mesh: MeshQuad, intorder: int) -> AffineQ2:
        """Tables on ``mesh``; :class:`ValueError` if an element is not a parallelogram (then the
        generic skfem assembly is the way)."""
        p = mesh.p[:, mesh.t]  # [2, 4, nel]
        e1, e3 = p[:, 1] - p[:, 0], p[:, 3] - p[:, 0]
        scale = np.abs(e1).max() + np.abs(e3).max()
        if np.abs(p[:, 2] - p[:, 1] - e3).max() > 1e-12 * scale:
            raise ValueError("AffineQ2 needs parallelogram elements")
        X, W = get_quadrature(ElementQuad2.refdom, intorder)
        elem = ElementQuad2()
        phi = np.empty((9, X.shape[1]))
        dref = np.empty((2, 9, X.shape[1]))
        for k in range(9):
            phi[k], dref[:, k] = elem.lbasis(X, k)
        det = e1[0] * e3[1] - e1[1] * e3[0]  # [nel]; J = [[e1_r, e3_r], [e1_z, e3_z]]
        inv_t = np.array([[e3[1], -e1[1]], [-e3[0], e1[0]]]) / det  # J^{-T} [2, 2, nel]
        d = np.einsum("abe,bkq->aekq", inv_t, dref)  # grad = J^{-T} grad_ref
        r = _bilinear(mesh, X[0], X[1])[0]
        return cls(r, np.abs(det)[:, None] * W[None, :], phi, d[0], d[1])

    def elasticity(self, lam: np.ndarray, mu: np.ndarray, element_dofs: np.ndarray, N: int) -> sp.csr_matrix:
        """The matrix of :data:`coathertz.fem.forms.elasticity` (same quadrature, equal to round-off).

        With ``d_r``, ``d_z`` the gradient of a scalar Q2 function, ``h = phi / r`` (hoop strain)
        and ``w = 2 pi r dx``, the 2 x 2 blocks of the element matrix between the scalar functions
        ``k`` and ``l`` (the axisymmetric ``B^T D B``, Zienkiewicz & Taylor, Vol 1, Section 5.2) are::

            K_rr = sum_q w [lam (d_r + h)_k (d_r + h)_l + 2 mu (d_r,k d_r,l + h_k h_l) + mu d_z,k d_z,l]
            K_rz = sum_q w [lam (d_r + h)_k d_z,l + mu d_z,k d_r,l]
            K_zz = sum_q w [(lam + 2 mu) d_z,k d_z,l + mu d_r,k d_r,l]

        each one batched matrix product over the stacked quadrature terms. Local function
        ``2 k + c`` is scalar ``k`` in component ``c`` (skfem's ``ElementVector`` order of
        ``element_dofs[2 k + c, e]``); ``lam``, ``mu`` are quadrature fields ``[nel, nq]``.
        """
        w = 2 * np.pi * self.r * self.dx
        lw, mw = (lam * w)[:, None, :], (mu * w)[:, None, :]
        dr, dz = self.d_r, self.d_z
        h = self.phi[None] / self.r[:, None, :]
        a = dr + h

        def gram(left: list, right: list) -> np.ndarray:
            return np.matmul(np.concatenate(left, axis=2), np.concatenate(right, axis=2).transpose(0, 2, 1))

        Ke = np.empty((len(w), 18, 18))
        Ke[:, 0::2, 0::2] = gram([lw * a, 2 * mw * dr, 2 * mw * h, mw * dz], [a, dr, h, dz])
        Krz = gram([lw * a, mw * dz], [dz, dr])
        Ke[:, 0::2, 1::2] = Krz
        Ke[:, 1::2, 0::2] = Krz.transpose(0, 2, 1)
        Ke[:, 1::2, 1::2] = gram([(lw + 2 * mw) * dz, mw * dr], [dz, dr])
        dofs = element_dofs.T  # [nel, 18]
        rows = np.repeat(dofs, 18, axis=1).ravel()
        cols = np.tile(dofs, (1, 18)).ravel()
        return sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(N, N))
