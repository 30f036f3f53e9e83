"""Cell influence coefficients: closed forms, limits, and the numerical remainder."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate
from scipy.special import j0

from coathertz.fft.frf import Layer
from coathertz.fft.influence import (
    H_SWITCH,
    LayerSplit,
    _remainder_kspace,
    _remainder_space,
    circulant,
    layer_coefficients,
    love_coefficients,
    love_corner,
    solid_angle_corner,
)
from coathertz.materials import RIGID, Body, Coating, Material

N, DX = 48, 1e-6
STEEL = Material(200e9, 0.3)
B4C = Material(380e9, 0.17)
SOFT = Material(50e9, 0.3)


def _cell_integral(f, x0, y0, dx, dy):
    return integrate.dblquad(
        f, y0 - dy / 2, y0 + dy / 2, x0 - dx / 2, x0 + dx / 2, epsabs=1e-14, epsrel=1e-11
    )[0]


@pytest.mark.parametrize("a", [0.0, 0.3e-6, 5e-6])
@pytest.mark.parametrize(("i", "j"), [(0, 0), (1, 0), (3, 2)])
def test_corner_functions_against_quadrature(a, i, j):
    dx, dy = 1e-6, 0.5e-6
    x0, y0 = i * dx, j * dy

    def cs(fun):
        xs, ys = (x0 - dx / 2, x0 + dx / 2), (y0 - dy / 2, y0 + dy / 2)
        return fun(xs[1], ys[1]) - fun(xs[0], ys[1]) - fun(xs[1], ys[0]) + fun(xs[0], ys[0])

    if i == 0 and j == 0 and a == 0:
        ref = 2 * dx * np.arcsinh(dy / dx) + 2 * dy * np.arcsinh(dx / dy)  # Love's self term
    else:
        ref = _cell_integral(lambda y, x: 1 / np.sqrt(x * x + y * y + a * a), x0, y0, dx, dy)
    assert cs(lambda x, y: love_corner(x, y, a)) == pytest.approx(ref, rel=1e-9)
    if a > 0:
        ref2 = _cell_integral(lambda y, x: a / (x * x + y * y + a * a) ** 1.5, x0, y0, dx, dy)
        assert cs(lambda x, y: solid_angle_corner(x, y, a)) == pytest.approx(ref2, rel=1e-9)


@pytest.mark.parametrize("h", [1e-9, 0.5e-6, 3e-6, 20e-6, 1e-3])
def test_coating_equal_to_substrate_gives_love(h):
    L = love_coefficients(N, N, DX, DX / 3, STEEL.E_star)
    K = layer_coefficients(Body(STEEL, Coating(STEEL, h)), N, N, DX, DX / 3)
    np.testing.assert_allclose(K, L, rtol=1e-13, atol=1e-15 * np.abs(L).max())


@pytest.mark.parametrize("coating", [B4C, SOFT])
def test_limits_in_h(coating):
    """h -> 0 tends to the substrate's Love coefficients, h -> inf to the coating's."""
    Ls = love_coefficients(N, N, DX, DX, STEEL.E_star)
    Lc = love_coefficients(N, N, DX, DX, coating.E_star)
    errs0 = [
        np.abs(layer_coefficients(Body(STEEL, Coating(coating, h)), N, N, DX, DX) - Ls).max()
        / Ls.max()
        for h in (1e-8, 1e-9, 1e-10)
    ]
    # the thin layer's own compliance is first order in h: errors fall tenfold per decade
    assert errs0[-1] < 1e-3, errs0
    np.testing.assert_allclose(np.array(errs0[:-1]) / errs0[1:], 10.0, rtol=0.05)
    errsi = [
        np.abs(layer_coefficients(Body(STEEL, Coating(coating, h)), N, N, DX, DX) - Lc).max()
        / Lc.max()
        for h in (1e-2, 1e-1, 1.0)
    ]
    assert errsi[-1] < 1e-4 and errsi[0] > errsi[1] > errsi[2], errsi


def test_rigid_substrate_limits():
    co = Material(200e9, 0.5)
    K0 = layer_coefficients(Body(RIGID, Coating(co, 1e-10)), N, N, DX, DX)
    Lc = love_coefficients(N, N, DX, DX, co.E_star)
    assert np.abs(K0).max() < 1e-3 * Lc.max()
    Kinf = layer_coefficients(Body(RIGID, Coating(co, 1.0)), N, N, DX, DX)
    np.testing.assert_allclose(Kinf, Lc, rtol=1e-5, atol=1e-6 * Lc.max())


@pytest.mark.parametrize(("coating", "substrate"), [(B4C, STEEL), (Material(200e9, 0.5), RIGID)])
def test_remainder_is_second_order_and_matches_hankel_quadrature(coating, substrate):
    split = LayerSplit.of(Layer(coating, substrate))
    t = np.array([1e-3, 2e-3])
    r = split.remainder(t)
    assert abs(r[1] / r[0] - 4) < 0.05  # rho(t) = O(t^2)
    h = 10 * DX
    g_space = _remainder_space(split, h, N, N, DX, DX)
    g_k = _remainder_kspace(split, h, N, N, DX, DX, oversample=8)
    for i, j in [(0, 0), (5, 2), (30, 30)]:
        rr = np.hypot(i, j) * DX
        ref = integrate.quad(
            lambda tt, rr=rr: split.remainder(np.array([tt]))[0] * j0(tt * rr / h) * tt,
            0,
            40,
            limit=400,
        )[0] / (2 * np.pi * h * h) * DX * DX
        scale = np.abs(g_space).max()
        assert abs(g_space[j, i] - ref) < 4e-3 * scale  # ref is a midpoint value
        assert abs(g_k[j, i] - g_space[j, i]) < 1e-6 * scale


@pytest.mark.parametrize("coating", [B4C, SOFT])
def test_branches_agree_at_switch(coating):
    """Remainder by FFT just below the switch thickness, by Hankel transform just above."""
    hs = H_SWITCH * DX
    Ka = layer_coefficients(Body(STEEL, Coating(coating, hs * (1 - 1e-9))), N, N, DX, DX)
    Kb = layer_coefficients(Body(STEEL, Coating(coating, hs * (1 + 1e-9))), N, N, DX, DX)
    assert np.abs(Ka - Kb).max() < 1e-7 * np.abs(Ka).max()


def test_circulant_layout():
    q = np.arange(12.0).reshape(3, 4)  # ny = 2, nx = 3
    c = circulant(q)
    assert c.shape == (4, 6)
    assert c[0, 0] == q[0, 0] and c[0, 5] == q[0, 1] and c[3, 4] == q[1, 2]


def _hertz_pressure_displacement(body, a, p0, r, interface):
    """Exact u(r) under p0 sqrt(1 - r^2/a^2): (1/2pi) int u~(k) P(k) J0(kr) k dk."""
    from coathertz.fft.frf import Layer

    layer = Layer(body.coating.material, body.material, interface)
    Ec, h = body.coating.material.E_star, body.coating.h
    xg, wg = np.polynomial.legendre.leggauss(8)
    edges = np.linspace(0.0, 400.0 / a, 3001)
    half = 0.5 * np.diff(edges)
    k = (edges[:-1, None] + half[:, None] * (xg + 1)).ravel()
    w = (half[:, None] * wg).ravel()
    x = k * a
    P = 2 * np.pi * p0 * a**2 * (np.sin(x) - x * np.cos(x)) / x**3  # 2-D FT of the pressure
    F = layer.factor(k * h)
    return float(np.sum(w * 2 / (Ec * k) * F * P * j0(k * r) * k) / (2 * np.pi))


@pytest.mark.parametrize(
    ("body", "interface"),
    [
        (Body(STEEL, Coating(Material(600e9, 0.25), 30e-6)), "bonded"),
        (Body(STEEL, Coating(SOFT, 200e-6)), "bonded"),
        (Body(RIGID, Coating(Material(100e9, 0.45), 50e-6)), "bonded"),
        (Body(RIGID, Coating(Material(100e9, 0.45), 50e-6)), "frictionless"),
    ],
)
def test_coefficients_end_to_end_against_hankel_transform(body, interface):
    """K * p on the grid against the exact displacement under a Hertzian pressure.

    Measured relative errors at r = 0 and r ~ a/2: <= 8e-4 at n = 32, <= 3e-4 at n = 64,
    <= 8e-5 at n = 128 (the error comes from collocating the square-root edge).
    """
    from coathertz.fft.influence import body_coefficients
    from coathertz.fft.solver import Convolver, get_backend

    a, p0 = 1e-4, 1e9
    for n, tol in ((64, 4e-4), (128, 1.2e-4)):
        dx = 2.4 * a / n
        K = body_coefficients(body, n, n, dx, dx, interface)
        x = (np.arange(n) - n // 2) * dx
        X, Y = np.meshgrid(x, x)
        p = p0 * np.sqrt(np.clip(1 - (X**2 + Y**2) / a**2, 0, None))
        u = Convolver(circulant(K), get_backend())(p[None])[0]
        i5 = round(0.5 * a / dx)
        for i, r in ((0, 0.0), (i5, i5 * dx)):
            ex = _hertz_pressure_displacement(body, a, p0, r, interface)
            assert u[n // 2, n // 2 + i] / ex - 1 == pytest.approx(0, abs=tol), (n, r)


@pytest.mark.parametrize(("nx", "ny", "dx", "dy"), [(24, 24, 1e-6, 1e-6), (24, 16, 1e-6, 1e-6),
                                                    (24, 24, 1e-6, 0.5e-6)])
def test_fast_coefficient_paths_are_bitwise_the_direct_ones(nx, ny, dx, dy):
    """The shared-value and symmetric evaluations of the coefficients (one pass for the three
    corner functions; the remainder on the quadrant ``ky >= 0`` or its upper triangle) give
    exactly the values of the direct evaluations they replace: no round-off changed."""
    from scipy import fft as sfft

    from coathertz.fft.influence import (
        _corner_sum,
        _layer_corner_sums,
        _radial_quadrant,
        _radial_symmetric,
        d_solid_angle_corner,
    )

    a = 0.7e-6
    fast = _layer_corner_sums(nx, ny, dx, dy, a)
    for f, got in zip((love_corner, solid_angle_corner, d_solid_angle_corner), fast, strict=True):
        np.testing.assert_array_equal(got, _corner_sum(f, nx, ny, dx, dy, a))
    split = LayerSplit.of(Layer(Material(600e9, 0.25), STEEL))
    kx = 2 * np.pi * sfft.rfftfreq(4 * nx, dx)
    ky = 2 * np.pi * np.abs(sfft.fftfreq(4 * ny, dy)[: 2 * ny + 1])
    fun = lambda k: split.remainder(k * 3e-6)  # noqa: E731
    np.testing.assert_array_equal(_radial_quadrant(fun, kx, ky),
                                  fun(np.hypot(kx[None, :], ky[:, None])))
    x = np.linspace(0.0, 5.0, 37)
    np.testing.assert_array_equal(_radial_symmetric(np.exp, x), np.exp(np.hypot(x[None, :], x[:, None])))


@pytest.mark.parametrize(("nx", "ny", "dx", "dy"), [(24, 24, 1e-6, 1e-6), (24, 16, 1e-6, 1e-6),
                                                    (32, 32, 1e-6, 0.4e-6)])
def test_kspace_remainder_by_dct_is_the_padded_inverse_fft(nx, ny, dx, dy):
    """The thin-layer remainder by a 2-D DCT-I of its frequency quadrant equals the inverse real
    FFT of the whole (even) over-sampled frequency grid it replaced, to round-off: both sum
    the same ~(4n)^2 terms of size <= max|g_hat|, so the difference is a few ulps of the
    largest coefficient (1e-16 relative measured; asserted at 1e-13, far below the 1e-9 the
    branches agree to at the switch)."""
    from scipy import fft as sfft

    split = LayerSplit.of(Layer(Material(600e9, 0.25), STEEL))
    h = 1.5 * dx
    Mx, My = 4 * nx, 4 * ny
    kx = 2 * np.pi * sfft.rfftfreq(Mx, dx)
    ky = 2 * np.pi * sfft.fftfreq(My, dy)
    g_hat = split.remainder(np.hypot(kx[None, :], ky[:, None]) * h)
    g_hat *= np.sinc(kx * dx / (2 * np.pi))[None, :] * np.sinc(ky * dy / (2 * np.pi))[:, None]
    want = sfft.irfft2(g_hat, s=(My, Mx))[: ny + 1, : nx + 1]
    got = _remainder_kspace(split, h, nx, ny, dx, dy)
    assert got.shape == (ny + 1, nx + 1)
    err = np.abs(got - want).max() / np.abs(want).max()
    assert err < 1e-13, f"DCT-I vs padded irfft2: {err:.2e} of the largest coefficient"
