"""Invariances of the FE model: unit scaling and the order of the two bodies."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coathertz.case import ContactCase
from coathertz.fem.method import FEMMethod
from coathertz.materials import Body, Coating, Material


@settings(max_examples=4, deadline=None)
@given(
    lam=st.floats(0.05, 20.0),
    E_ratio=st.sampled_from([0.25, 1.0, 4.0]),
    H=st.floats(0.05, 2.0),
)
def test_length_scaling(lam, E_ratio, H):
    """Lengths x lam and W x lam^2 at fixed moduli: pressures unchanged, lengths x lam
    (the mesh is built relative to a_ref, so this holds to round-off)."""
    sub = Material(200e9, 0.3)
    coat = Material(200e9 * E_ratio, 0.25)
    base = ContactCase(Body.rigid_sphere(0.01), Body.half_space(sub, Coating(coat, 1e-4 * H)), 50.0)
    big = ContactCase(Body.rigid_sphere(0.01 * lam), Body.half_space(sub, Coating(coat, 1e-4 * H * lam)),
                      50.0 * lam**2)
    r1 = FEMMethod(mesh="coarse").solve(base)
    r2 = FEMMethod(mesh="coarse").solve(big)
    assert r2.delta == pytest.approx(lam * r1.delta, rel=1e-7)
    assert r2.a == pytest.approx(lam * r1.a, rel=1e-7)
    assert r2.p0 == pytest.approx(r1.p0, rel=1e-7)


def test_body_order_does_not_matter(fx):
    coated = Body.half_space(fx.STEEL, Coating(Material(400e9, 0.3), 60e-6))
    c1 = ContactCase(Body.rigid_sphere(0.01), coated, 100.0)
    c2 = ContactCase(coated, Body.rigid_sphere(0.01), 100.0)
    r1, r2 = fx.solve(c1, mesh="coarse"), fx.solve(c2, mesh="coarse")
    assert (r1.delta, r1.a, r1.p0) == (r2.delta, r2.a, r2.p0)
