"""Invariants of the discrete problem (hypothesis): scaling laws and the symmetry of the pair."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coathertz.case import ContactCase
from coathertz.fft.method import FFTMethod
from coathertz.materials import Body, Coating, Material

M = FFTMethod(n=32)


def _case(E_ratio, H, nu_c, lam=1.0, mu=1.0):
    sub = Material(200e9 * mu, 0.3)
    co = Material(E_ratio * 200e9 * mu, nu_c)
    c0 = ContactCase.sphere_on_coated_half_space(10e-3 * lam, 1.0 * lam**2 * mu, co, 1.0, sub)
    return c0.with_thickness(H * c0.a0s)


ratios = st.floats(0.25, 4.0)
thick = st.floats(0.01, 3.0)
nus = st.floats(0.15, 0.5)


@settings(max_examples=8, deadline=None)
@given(E=ratios, H=thick, nu_c=nus, lam=st.floats(0.1, 10.0))
def test_length_scaling(E, H, nu_c, lam):
    """Lengths x lam and W x lam^2: delta and a scale by lam, p0 is unchanged.

    The discrete problems are similar but not bitwise equal, so the CG paths differ at the level
    of its tolerance (1e-6 on sum |dp| / W): the tolerances below are CG-level, not physics.
    """
    r1, r2 = M.solve(_case(E, H, nu_c)), M.solve(_case(E, H, nu_c, lam=lam))
    assert r2.delta == pytest.approx(lam * r1.delta, rel=1e-6)
    assert r2.a == pytest.approx(lam * r1.a, rel=2e-5)
    assert r2.p0 == pytest.approx(r1.p0, rel=2e-5)


@settings(max_examples=8, deadline=None)
@given(E=ratios, H=thick, nu_c=nus, mu=st.floats(0.01, 100.0))
def test_modulus_scaling(E, H, nu_c, mu):
    """All moduli x mu and W x mu: p0 scales by mu, delta and a are unchanged."""
    r1, r2 = M.solve(_case(E, H, nu_c)), M.solve(_case(E, H, nu_c, mu=mu))
    assert r2.delta == pytest.approx(r1.delta, rel=1e-6)
    assert r2.a == pytest.approx(r1.a, rel=2e-5)
    assert r2.p0 == pytest.approx(mu * r1.p0, rel=2e-5)


@settings(max_examples=6, deadline=None)
@given(E=ratios, H=thick)
def test_order_of_bodies_does_not_matter(E, H):
    ball = Body.sphere(Material(110e9, 0.34), 5e-3)
    flat = Body.half_space(Material(200e9, 0.3), Coating(Material(E * 200e9, 0.3), H * 30e-6))
    r1 = M.solve(ContactCase(ball, flat, 2.0))
    r2 = M.solve(ContactCase(flat, ball, 2.0))
    assert (r1.delta, r1.a, r1.p0) == pytest.approx((r2.delta, r2.a, r2.p0), rel=1e-12)


@given(st.integers(2, 5000))
@settings(max_examples=200, deadline=None)
def test_fast_n_is_the_next_even_5_smooth_size(n):
    """The refinement's ``n``: even, at least ``n``, no prime factor above 5, and no smaller
    even number in between has that property."""
    from coathertz.fft.grid import fast_n

    def smooth(m: int) -> bool:
        for f in (2, 3, 5):
            while m % f == 0:
                m //= f
        return m == 1

    m = fast_n(n)
    assert m >= n and m % 2 == 0 and smooth(m)
    assert not any(smooth(k) for k in range(n + n % 2, m, 2))
