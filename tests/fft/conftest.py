"""Shared cases for the FFT solver tests."""

from __future__ import annotations

import pytest

from coathertz.case import ContactCase
from coathertz.materials import RIGID, Body, Material

STEEL = Material(200e9, 0.3)


def coated(E_ratio: float, H: float, nu_c: float = 0.3, substrate: Material = STEEL):
    """Rigid 10 mm sphere, 1 N, on a coating with Ec*/Es* = E_ratio at H = h/a0s (h/a0c)."""
    if substrate.is_rigid:
        co = Material(200e9, nu_c)
        c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, co, 1.0, RIGID)
        return c0.with_thickness(H * c0.a0c)
    Ec = E_ratio * substrate.E_star * (1 - nu_c**2)
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(Ec, nu_c), 1.0, substrate)
    return c0.with_thickness(H * c0.a0s)


@pytest.fixture
def homogeneous():
    return ContactCase(Body.rigid_sphere(10e-3), Body.half_space(STEEL), 1.0)
