"""Shared cases and cached solves for the FE tests."""

from __future__ import annotations

from functools import cache
from types import SimpleNamespace

import pytest

from coathertz.case import ContactCase
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)


def hertz_case(W: float = 100.0, R: float = 0.01) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R), Body.half_space(STEEL), W)


def coated_case(Ec: float, H: float, nu_c: float = 0.3, W: float = 100.0) -> ContactCase:
    base = hertz_case(W)
    return ContactCase.sphere_on_coated_half_space(0.01, W, Material(Ec, nu_c), H * base.a0s, STEEL)


def rigid_base_case(nu_c: float, h: float = 30e-6) -> ContactCase:
    return ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(Material(200e9, nu_c), h)), 100.0)


@cache
def solve(case: ContactCase, **kw):
    from coathertz.fem.method import FEMMethod

    return FEMMethod(**kw).solve(case)


@pytest.fixture(scope="session")
def fx():
    """Helpers: ``fx.hertz_case``, ``fx.coated_case``, ``fx.rigid_base_case``, ``fx.solve`` (cached)."""
    return SimpleNamespace(hertz_case=hertz_case, coated_case=coated_case, rigid_base_case=rigid_base_case,
                           solve=solve, STEEL=STEEL)
