"""Outer boundary of the truncated domain: how the far field is imposed.

The approach ``delta`` is measured relative to points far away in the substrate. A domain of
size ``L`` with a fixed outer boundary measures it relative to points at distance ``L``
instead, an ``O(a/L)`` bias (the Boussinesq surface displacement decays like ``1/rho``).
:class:`BoussinesqFarField` removes it: the outer boundary (``r = L`` and ``z = -D``) carries the
displacement of a point load ``W`` on the substrate half-space (Boussinesq; Johnson, *Contact
Mechanics*, 1985, eq 3.24 with ``z`` into the solid):

.. math::

    u_r = \\frac{(1+\\nu) W}{2\\pi E \\rho}\\left[\\frac{r t}{\\rho^2}
          - \\frac{(1-2\\nu) r}{\\rho + t}\\right],\\qquad
    u_t = \\frac{(1+\\nu) W}{2\\pi E \\rho}\\left[2(1-\\nu) + \\frac{t^2}{\\rho^2}\\right],

``t = -z`` the depth and ``rho^2 = r^2 + t^2``. The Hertz load differs from a point load by a
second moment ``~ W a^2``, so the residual error in ``delta`` is ``O((a/L)^3)``; for a coated
body the coating perturbs the far field by a relative ``O(h/L)``, leaving a bias that decays
like ``L^-1.7`` (measured, E = 4, H = 1: +3.2e-4, -0.6e-5, -3.1e-5 at L = 40, 160, 640 against
the exact axisymmetric solution; hence the default ``L = 160``, :class:`coathertz.fem.mesh.MeshSpec`).
Measured residual biases: ``tests/fem/test_farfield.py`` (homogeneous and coated).
A coating on a rigid substrate needs no far field: the bottom is bonded (``u = 0``) and the
disturbance decays exponentially with ``r/h``; :class:`FixedFarField` clamps ``r = L`` too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coathertz.materials import Material


def boussinesq_displacement(r: np.ndarray, z: np.ndarray, W: float, E: float, nu: float) -> np.ndarray:
    """``(u_r, u_z)`` [m] of a point load ``W`` pressing on the half-space ``z <= 0`` (Johnson eq 3.24)."""
    t = -np.asarray(z, dtype=float)
    r = np.asarray(r, dtype=float)
    rho = np.hypot(r, t)
    c = (1.0 + nu) * W / (2.0 * np.pi * E * rho)
    ur = c * (r * t / rho**2 - (1.0 - 2.0 * nu) * r / (rho + t))
    ut = c * (2.0 * (1.0 - nu) + t**2 / rho**2)
    return np.array([ur, -ut])


@dataclass(frozen=True)
class BoussinesqFarField:
    """Prescribe the substrate's point-load field on the outer boundary (default)."""

    name: str = "boussinesq"

    def values(self, r: np.ndarray, z: np.ndarray, W: float, substrate: Material) -> np.ndarray:
        return boussinesq_displacement(r, z, W, substrate.E, substrate.nu)


@dataclass(frozen=True)
class FixedFarField:
    """Clamp the outer boundary (``u = 0``): ``delta`` relative to points at distance ``L``."""

    name: str = "fixed"

    def values(self, r: np.ndarray, z: np.ndarray, W: float, substrate: Material) -> np.ndarray:
        return np.zeros((2, np.size(r)))
