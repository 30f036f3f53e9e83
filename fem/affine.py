"""Stiffness of Q2 elements on axis-aligned rectangles (the tensor-product mesh), without skfem's basis.

scikit-fem's :class:`skfem.CellBasis` maps every basis function through the generic
isoparametric mapping (a Jacobian inverse per function and quadrature point). On the meshes of
:mod:`coathertz.fem.mesh` every element is a rectangle ``h_r x h_z``, so with skfem's reference
square ``[0, 1]^2`` and its Q2 functions ``N_k(xi, eta)``

.. math:: \\partial_r \\phi_k = \\partial_\\xi N_k / h_r, \\quad
          \\partial_z \\phi_k = \\partial_\\eta N_k / h_z, \\quad
          r = r_0 + h_r \\xi, \\quad dx = |h_r h_z| W_q ,

(``xi`` the reference coordinate along ``r``; ``MeshQuad.init_tensor`` maps the first one to ``z``),

and every element matrix is a combination of a few fixed reference outer products
(``N_r N_r^T``, ``N N^T``, ...) at each quadrature point, with per-element coefficients
(:meth:`RectQ2.elasticity`): one matrix product for the whole mesh. Same quadrature rule as
``Basis(mesh, ElementVector(ElementQuad2()), intorder=INTORDER)``, the same matrix to round-off
(``tests/fem/test_forms.py``), about ten times cheaper than skfem's generic assembly.

:func:`dof_locations` gives the global dof locations without any quadrature (the model's dof
layout: axis, surface, candidates) so that the full skfem basis is built only when a
post-processing step asks for it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

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
class RectQ2:
    """Reference Q2 tables and the geometry of every (axis-aligned rectangular) element.

    Attributes
    ----------
    h_r, h_z
        Signed element sizes ``[nel]`` (the Jacobian ``diag(h_r, h_z)`` of skfem's map).
    r, z
        Coordinates of the quadrature points ``[nel, nq]`` (skfem's bilinear map).
    W
        Reference quadrature weights ``[nq]``.
    N, N_r, N_z
        Values of the nine scalar Q2 functions and their reference derivatives along the reference
        coordinate that maps to ``r`` and to ``z`` ``[9, nq]``.
    """

    h_r: np.ndarray
    h_z: np.ndarray
    r: np.ndarray
    W: np.ndarray
    N: np.ndarray
    N_r: np.ndarray
    N_z: np.ndarray
    z: np.ndarray | None = None

    @classmethod
    def build(cls, mesh: MeshQuad, intorder: int) -> RectQ2:
        """Tables on ``mesh``; :class:`ValueError` unless every element is an axis-aligned rectangle
        with the same orientation of the reference square (then the generic skfem assembly is the way)."""
        p = mesh.p[:, mesh.t]  # [2, 4, nel]
        e1, e3 = p[:, 1] - p[:, 0], p[:, 3] - p[:, 0]  # images of the reference xi and eta edges
        scale = np.abs(e1).max() + np.abs(e3).max()
        tol = 1e-12 * scale
        X, W = get_quadrature(ElementQuad2.refdom, intorder)
        elem = ElementQuad2()
        N = np.empty((9, X.shape[1]))
        dN = np.empty((2, 9, X.shape[1]))
        for k in range(9):
            N[k], dN[:, k] = elem.lbasis(X, k)
        if np.abs(p[:, 2] - p[:, 1] - e3).max() > tol:
            raise ValueError("RectQ2 needs rectangular elements")
        if np.abs(e1[1]).max() <= tol and np.abs(e3[0]).max() <= tol:  # xi along r
            h_r, h_z, d_r, d_z = e1[0], e3[1], dN[0], dN[1]
        elif np.abs(e1[0]).max() <= tol and np.abs(e3[1]).max() <= tol:  # xi along z (MeshQuad.init_tensor)
            h_r, h_z, d_r, d_z = e3[0], e1[1], dN[1], dN[0]
        else:
            raise ValueError("RectQ2 needs axis-aligned elements of one orientation")
        r, z = _bilinear(mesh, X[0], X[1])
        return cls(h_r, h_z, r, W, N, d_r, d_z, z)

    @cached_property
    def _reference(self) -> np.ndarray:
        """``R[(q, term), 18 * 18]``: the outer products of :meth:`elasticity` placed in the
        element matrix (row ``2 k + c`` is scalar function ``k`` in component ``c``)."""
        nq = len(self.W)
        out = np.zeros((nq, 9, 18, 18))
        for q in range(nq):
            n, x, y = self.N[:, q], self.N_r[:, q], self.N_z[:, q]
            rr = [np.outer(x, x), np.outer(n, n), np.outer(x, n) + np.outer(n, x), np.outer(y, y)]
            rz = [np.outer(x, y), np.outer(n, y), np.outer(y, x)]
            zz = [np.outer(y, y), np.outer(x, x)]
            for t, P in enumerate(rr):
                out[q, t, 0::2, 0::2] = P
            for t, P in enumerate(rz, start=4):
                out[q, t, 0::2, 1::2] = P
                out[q, t, 1::2, 0::2] = P.T
            for t, P in enumerate(zz, start=7):
                out[q, t, 1::2, 1::2] = P
        return out.reshape(nq * 9, 18 * 18)

    def strain(self, u: np.ndarray, element_dofs: np.ndarray) -> np.ndarray:
        """Strain ``(eps_rr, eps_zz, eps_tt, gamma_rz)`` ``[4, nel, nq]`` of the nodal displacement
        ``u`` at the quadrature points (``coathertz.fem.forms.quad_strain`` on skfem's basis, equal
        to round-off): ``d_r u = sum_k u_k N_r,k / h_r``, ``d_z u = sum_k u_k N_z,k / h_z``,
        ``u_r / r`` with ``u_r = sum_k u_r,k N_k``."""
        ue = u[element_dofs]  # [18, nel]
        ur, uz = ue[0::2].T, ue[1::2].T  # [nel, 9]
        hr, hz = self.h_r[:, None], self.h_z[:, None]
        return np.array([ur @ self.N_r / hr, uz @ self.N_z / hz, (ur @ self.N) / self.r,
                         ur @ self.N_z / hz + uz @ self.N_r / hr])

    def elasticity(self, lam: np.ndarray, mu: np.ndarray, element_dofs: np.ndarray, N: int) -> sp.csr_matrix:
        """The matrix of ``coathertz.fem.forms.elasticity`` (same quadrature, equal to round-off).

        With ``w = 2 pi r |h_r h_z| W_q``, ``alpha = lam w``, ``beta = mu w`` and the reference
        functions ``N``, ``N_r``, ``N_z`` at quadrature point ``q``, the blocks of the element
        matrix between scalar functions ``k`` and ``l`` (the axisymmetric ``B^T D B`` with
        ``eps = (d_r u_r, d_z u_z, u_r / r, d_z u_r + d_r u_z)``, Zienkiewicz & Taylor, Vol 1,
        Section 5.2) are, summed over ``q``::

            K_rr = (alpha + 2 beta) [N_r N_r^T / h_r^2 + N N^T / r^2]
                   + alpha (N_r N^T + N N_r^T) / (h_r r) + beta N_z N_z^T / h_z^2
            K_rz = alpha [N_r N_z^T / (h_r h_z) + N N_z^T / (r h_z)] + beta N_z N_r^T / (h_r h_z)
            K_zz = (alpha + 2 beta) N_z N_z^T / h_z^2 + beta N_r N_r^T / h_r^2

        i.e. nine coefficients per element and quadrature point times fixed reference matrices:
        one ``[nel, 9 nq] x [9 nq, 324]`` product (on one BLAS thread). ``lam``, ``mu`` are
        quadrature fields ``[nel, nq]``; ``element_dofs[2 k + c, e]`` as in skfem's ``ElementVector``.
        """
        from coathertz.blas import blas_threads

        r, hr, hz = self.r, self.h_r[:, None], self.h_z[:, None]
        w = 2 * np.pi * r * np.abs(hr * hz) * self.W
        a, b = lam * w, mu * w
        ab = a + 2 * b
        coef = np.stack([ab / hr**2, ab / r**2, a / (hr * r), b / hz**2,  # K_rr
                         a / (hr * hz), a / (r * hz), b / (hr * hz),  # K_rz
                         ab / hz**2, b / hr**2], axis=2)  # K_zz; [nel, nq, 9]
        with blas_threads(1):
            Ke = coef.reshape(len(w), -1) @ self._reference  # [nel, 324]
        dofs = element_dofs.T  # [nel, 18]
        rows = np.repeat(dofs, 18, axis=1).ravel()
        cols = np.tile(dofs, (1, 18)).ravel()
        return sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(N, N))


def ring_weights(x: np.ndarray) -> np.ndarray | None:
    """``int phi_i 2 pi r dr`` of the Q2 functions on a line of facets ``[x_0, x_2], [x_2, x_4], ...``
    (``x`` sorted, odd entries the midpoints); ``None`` if ``x`` is not such a line.

    Exact for the quadratic Lagrange functions ``phi`` times ``r`` on ``[x0, x0 + L]``:
    ``2 pi L (x0 / 6, 2 x0 / 3 + L / 3, x0 / 6 + L / 6)`` for the left, middle and right node.
    """
    if len(x) < 3 or len(x) % 2 == 0:
        return None
    x0, xm, x1 = x[:-1:2], x[1::2], x[2::2]
    L = x1 - x0
    if np.abs(xm - 0.5 * (x0 + x1)).max() > 1e-9 * max(float(x[-1]), 1e-300):
        return None
    w = np.zeros(len(x))
    w[:-1:2] += 2 * np.pi * L * x0 / 6
    w[1::2] += 2 * np.pi * L * (2 * x0 / 3 + L / 3)
    w[2::2] += 2 * np.pi * L * (x0 / 6 + L / 6)
    return w
