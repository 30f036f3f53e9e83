"""Shared cases for the axisym tests."""

from __future__ import annotations

import os

# the Galerkin systems are small: BLAS threads only add overhead (set before numpy loads BLAS)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from coathertz.case import ContactCase
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)
R_SPHERE = 10e-3
W_LOAD = 1.0


def coated(E_ratio: float, H: float, nu_c: float = 0.3, substrate: Material = STEEL,
           indenter: Material | None = None) -> ContactCase:
    """10 mm sphere (rigid unless ``indenter``), 1 N, coating with ``Ec*/Es* = E_ratio`` at
    ``H = h/a0s`` (elastic substrate) or ``h/a0c`` with ``Ec = 200 GPa`` (rigid substrate)."""
    if substrate.is_rigid:
        co = Material(200e9, nu_c)
        c0 = ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, co, 1.0, RIGID, indenter)
        return c0.with_thickness(H * c0.a0c)
    Ec = E_ratio * substrate.E_star * (1 - nu_c**2)
    c0 = ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, Material(Ec, nu_c), 1.0, substrate,
                                                 indenter)
    return c0.with_thickness(H * c0.a0s)


def homogeneous(indenter: Material | None = None) -> ContactCase:
    b1 = Body.rigid_sphere(R_SPHERE) if indenter is None else Body.sphere(indenter, R_SPHERE)
    return ContactCase(b1, Body.half_space(STEEL), W_LOAD)


def uniform_coated(Ec: float, nu_c: float, h: float) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R_SPHERE), Body.half_space(STEEL, Coating(Material(Ec, nu_c), h)),
                       W_LOAD)
