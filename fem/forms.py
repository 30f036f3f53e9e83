"""Axisymmetric elasticity as scikit-fem forms (coordinates ``x[0] = r``, ``x[1] = z``).

Displacement ``u = (u_r, u_z)``; strains in Voigt order with engineering shear
(e.g. Timoshenko & Goodier, Section 135; Zienkiewicz & Taylor, Vol 1, eq 5.3):

.. math::

    \\varepsilon_{rr} = \\partial_r u_r, \\quad \\varepsilon_{zz} = \\partial_z u_z, \\quad
    \\varepsilon_{\\theta\\theta} = u_r / r, \\quad \\gamma_{rz} = \\partial_z u_r + \\partial_r u_z .

Every integral carries the circumferential weight ``2 * np.pi * r``, so assembled forces are
forces on the full ring [N]. Material parameters enter as quadrature fields (``w['lam']``,
``w['mu']``, ``w['D']``, ``w['sig']``) so that regions and quadrature-point laws need no special
code. The mixed (Taylor-Hood Q2-Q1) form writes ``sigma = 2 mu eps - p I`` with
``-div u - p / lam = 0`` and works for ``lam = inf`` (``nu = 0.5``, ``w['inv_lam'] = 0``).
"""

from __future__ import annotations

import numpy as np
from skfem import BilinearForm, LinearForm


def strain(u, r) -> tuple:
    """``(eps_rr, eps_zz, eps_tt, gamma_rz)`` of a vector field ``u`` (DiscreteField or basis)."""
    return (u.grad[0][0], u.grad[1][1], u[0] / r, u.grad[0][1] + u.grad[1][0])


def divergence(u, r):
    """``div u = d_r u_r + u_r / r + d_z u_z`` (volumetric strain)."""
    return u.grad[0][0] + u[0] / r + u.grad[1][1]


def linear_stress(lam, mu):
    """Isotropic Hooke's law ``eps -> sigma`` (Voigt, engineering shear)."""

    def stress(eps):
        err, ezz, ett, grz = eps
        tr = err + ezz + ett
        return (lam * tr + 2 * mu * err, lam * tr + 2 * mu * ezz, lam * tr + 2 * mu * ett, mu * grz)

    return stress


def work(sig, eps):
    """Virtual work density ``sigma . eps`` (Voigt, engineering shear)."""
    return sig[0] * eps[0] + sig[1] * eps[1] + sig[2] * eps[2] + sig[3] * eps[3]


@BilinearForm
def elasticity(u, v, w):
    """Isotropic stiffness with fields ``lam``, ``mu``: int sigma(u) : eps(v) 2 pi r."""
    r = w.x[0]
    sig = linear_stress(w["lam"], w["mu"])(strain(u, r))
    return work(sig, strain(v, r)) * 2 * np.pi * r


@BilinearForm
def tangent_stiffness(u, v, w):
    """Stiffness from a quadrature-point tangent ``D[4, 4, nel, nqp]`` (any material law)."""
    r = w.x[0]
    eu, ev = strain(u, r), strain(v, r)
    D = w["D"]
    sig = tuple(sum(D[i, j] * eu[j] for j in range(4)) for i in range(4))
    return work(sig, ev) * 2 * np.pi * r


@LinearForm
def internal_force(v, w):
    """Internal force ``int sigma : eps(v) 2 pi r`` from quadrature-point stress ``sig[4, ...]``."""
    r = w.x[0]
    s = w["sig"]
    return work((s[0], s[1], s[2], s[3]), strain(v, r)) * 2 * np.pi * r


@BilinearForm
def pressure_coupling(p, v, w):
    """``-int p div(v) 2 pi r`` (trial: pressure, test: displacement)."""
    r = w.x[0]
    return -p * divergence(v, r) * 2 * np.pi * r


@BilinearForm
def pressure_compliance(p, q, w):
    """``-int p q / lam 2 pi r`` with field ``inv_lam`` (zero when incompressible)."""
    r = w.x[0]
    return -p * q * w["inv_lam"] * 2 * np.pi * r


@LinearForm
def body_force(v, w):
    """``int f . v 2 pi r`` for quadrature fields ``fr``, ``fz`` (body force per volume)."""
    r = w.x[0]
    return (w["fr"] * v[0] + w["fz"] * v[1]) * 2 * np.pi * r


@BilinearForm
def mass(u, v, w):
    """Scalar mass ``int u v 2 pi r`` (L2 projection of stresses)."""
    return u * v * 2 * np.pi * w.x[0]


def quad_strain(basis, u: np.ndarray) -> np.ndarray:
    """Strain vector ``[4, nel, nqp]`` of the nodal displacement ``u`` at quadrature points."""
    uh = basis.interpolate(u)
    r = basis.global_coordinates()[0]
    return np.array(strain(uh, r))
