"""Cell influence coefficients of a (coated) half-space from its FRF.

``K[j, i]`` is the surface normal displacement at the centre of cell ``(0, 0)`` due to a unit
uniform pressure on the ``dx x dy`` cell centred at ``(i dx, j dy)`` [m/Pa]. By symmetry only the
quadrant ``0 <= i <= nx, 0 <= j <= ny`` is computed; :func:`circulant` places it in the
``2 ny x 2 nx`` wrap-around array used by the zero-padded DC-FFT (Liu, Wang & Liu 2000), so
the cyclic convolution with a zero-padded pressure equals the linear (half-space) one exactly.

How the FRF is turned into cell coefficients
--------------------------------------------
Sampling ``u~(w) = 2 F(w h) / (Ec* w)`` (eq 13) on the FFT grid would (i) mishandle the
``1/w`` singularity at ``w = 0`` and (ii) wrap periodic images of a slowly decaying (``1/r``)
kernel into the coefficients. Instead the layer factor is split as

.. math::  \\frac{F(t) - 1}{t} = (F_0 - 1) \\frac{e^{-ct}}{t} + \\beta e^{-ct}
           + \\gamma t e^{-ct} + \\rho(t),  \\qquad t = w h,

with ``F0 = F(0) = Ec*/Es*`` and ``beta, gamma`` chosen from the Taylor coefficients of ``F``
(computed by a Cauchy integral, :func:`~coathertz.fft.frf.taylor_coefficients`) so that
``rho(t) = O(t^2)``. Every split-off term has a closed-form cell integral (``a = c h``):

* ``2/(E w)``           -> ``1/(pi E r)``: Love's rectangle formula (:func:`love_corner`, a = 0);
* ``2 e^{-a w}/(E w)``  -> ``1/(pi E sqrt(r^2 + a^2))``: the same corner function with a > 0;
* ``e^{-a w}``          -> ``a / (2 pi (r^2 + a^2)^{3/2})``: the solid-angle corner function;
* ``w e^{-a w}``        -> ``-d/da`` of the previous one.

Hence the homogeneous part is exact (coating = substrate gives ``F = 1``, all other terms zero:
Love's coefficients to rounding) and the ``1/w`` singularity is handled in closed form. The
remainder ``rho`` is bounded, ``O(w^2)`` at the origin (its kernel has zero mean and zero first
moment, so wrapped images decay like ``r^-5``) and decays like ``e^{-2 w h}``. It is transformed
numerically in one of two ways:

* ``h < H_SWITCH`` cells (thin layers): sampled on a 2x over-sampled frequency grid (period
  ``4 nx dx``: the nearest image lies ``3 nx dx >= 12 h`` away, and the ``r^-5`` tail makes
  images negligible) and multiplied by the cell's transform ``sinc(kx dx/2) sinc(ky dy/2)``
  before the inverse transform (a 2-D DCT-I of the quadrant ``kx, ky >= 0``: the samples are
  even). Truncation at the Nyquist frequency matters only when ``h < dx``.
  Then the remainder kernel is narrower than a cell and has zero mean, and its exact cell
  integrals are ``O((h/dx)^3)`` small.
* ``h >= H_SWITCH`` cells: a radial Hankel transform
  ``g(r) = (1/2 pi) int u~_rem(w) J0(w r) w dw`` by composite Gauss--Legendre quadrature,
  tabulated in ``s = r/h`` up to the grid's reach (rounded up to a power of ``2^(1/8)``) or
  ``R_CUT h`` (cubic spline, 513 points; the table depends on the layer and the reach only and
  is cached, so the nested grids of a solve share one). Beyond ``R_CUT h`` the ``r^-5, r^-7``
  far field of the ``t^3, t^5`` terms of ``rho`` is used. Each cell is integrated with 3 x 3 Gauss points
  (2 x 2 once the kernel is 8 cells wide; the two differ by < 2e-7 of the largest
  coefficient). A frequency grid of spacing ``2 pi / L`` could not
  resolve a kernel wider than the domain; this branch has no images at all.

The two branches agree to better than 1e-9 of the largest coefficient at the switch (tested),
and ``K * p`` under a Hertzian pressure matches the exact Hankel-transform displacement to
< 1e-4 at 128 cells (tested, bonded and frictionless).

Both bodies may be coated: compliances add, so their coefficient arrays add.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from scipy import fft as sfft
from scipy.interpolate import CubicSpline
from scipy.special import j0

from coathertz.errors import CoatHertzError
from coathertz.fft.frf import Layer, StackFRF, taylor_coefficients
from coathertz.materials import Body

C_DECAY = 2.0  # c of the split-off terms e^{-c w h}: matches theta = e^{-2 w h} of eq (13)
H_SWITCH = 4.0  # remainder by radial Hankel transform when h >= H_SWITCH cells, else by FFT
R_CUT = 60.0  # radial table up to R_CUT h; beyond, the r^-5, r^-7 far field of the remainder


def love_corner(x, y, a=0.0):
    """Corner function of ``int int dx dy / sqrt(x^2 + y^2 + a^2)``.

    ``x asinh(y/sqrt(x^2+a^2)) + y asinh(x/sqrt(y^2+a^2)) - a atan(xy/(a rho))``; for ``a = 0``
    Love's (1929) formula (Johnson 1985, eq 3.25). The terms ``x ln sqrt(x^2+a^2)`` dropped
    from ``x ln(y + rho)`` cancel in the corner sum; the asinh form avoids cancellation.
    """
    sx = np.sqrt(x * x + a * a)
    sy = np.sqrt(y * y + a * a)
    out = x * np.arcsinh(y / sx) + y * np.arcsinh(x / sy)
    if np.any(a != 0):
        rho = np.sqrt(x * x + y * y + a * a)
        out = out - a * np.arctan2(x * y, a * rho)
    return out


def solid_angle_corner(x, y, a):
    """Corner function of ``int int a dx dy / (x^2 + y^2 + a^2)^{3/2}``: ``atan(xy/(a rho))``."""
    rho = np.sqrt(x * x + y * y + a * a)
    return np.arctan2(x * y, a * rho)


def d_solid_angle_corner(x, y, a):
    """``d/da`` of :func:`solid_angle_corner`.

    ``-xy (rho^2 + a^2) / (rho (a^2 rho^2 + x^2 y^2))``.
    """
    rho2 = x * x + y * y + a * a
    rho = np.sqrt(rho2)
    return -x * y * (rho2 + a * a) / (rho * (a * a * rho2 + (x * y) ** 2))


def _corner_sum(fun, nx, ny, dx, dy, *args):
    """Cell integrals for offsets 0..nx, 0..ny from corner values on the lattice (i - 1/2) d."""
    xc = (np.arange(nx + 2) - 0.5) * dx
    yc = (np.arange(ny + 2) - 0.5) * dy
    Fc = fun(xc[None, :], yc[:, None], *args)
    return _corner_diff(Fc)


def _corner_diff(Fc: np.ndarray) -> np.ndarray:
    """The corner sum ``F(++) - F(+-) - F(-+) + F(--)`` of corner values ``Fc``."""
    return Fc[1:, 1:] - Fc[1:, :-1] - Fc[:-1, 1:] + Fc[:-1, :-1]


def _layer_corner_sums(nx, ny, dx, dy, a) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The corner sums of :func:`love_corner`, :func:`solid_angle_corner` and
    :func:`d_solid_angle_corner` at depth ``a > 0``, in one pass.

    The same expressions as the three functions, evaluated once where they share a value
    (``rho``, ``xy``, the arc tangent), so the sums are bitwise those of :func:`_corner_sum`
    with each function (tested). On a square lattice (``nx = ny``, ``dx = dy``) Love's two
    ``asinh`` terms are each other's transpose and one of them is computed.
    """
    xc = (np.arange(nx + 2) - 0.5) * dx
    yc = (np.arange(ny + 2) - 0.5) * dy
    x, y = xc[None, :], yc[:, None]
    xy = x * y
    rho2 = x * x + y * y + a * a
    rho = np.sqrt(rho2)
    atan = np.arctan2(xy, a * rho)
    sx = np.sqrt(x * x + a * a)
    first = x * np.arcsinh(y / sx)
    if nx == ny and dx == dy:  # y asinh(x / sy) is the transpose of x asinh(y / sx)
        love = first + first.T
    else:
        sy = np.sqrt(y * y + a * a)
        love = first + y * np.arcsinh(x / sy)
    love = love - a * atan
    d_solid = -xy * (rho2 + a * a) / (rho * (a * a * rho2 + xy**2))
    return _corner_diff(love), _corner_diff(atan), _corner_diff(d_solid)


@lru_cache(maxsize=16)
def _love_unit(nx: int, ny: int, dx: float, dy: float) -> np.ndarray:
    """Love's corner sums (E*-independent, cached per grid; read-only)."""
    out = _corner_sum(love_corner, nx, ny, dx, dy, 0.0)
    out.flags.writeable = False
    return out


def love_coefficients(nx: int, ny: int, dx: float, dy: float, E_star: float) -> np.ndarray:
    """Homogeneous half-space coefficients (Love), quadrant ``(ny+1, nx+1)`` [m/Pa]."""
    if np.isinf(E_star):
        return np.zeros((ny + 1, nx + 1))
    return _love_unit(nx, ny, float(dx), float(dy)) / (np.pi * E_star)


@dataclass(frozen=True)
class LayerSplit:
    """The split of ``(F(t) - 1)/t`` described in the module docstring."""

    layer: Layer
    F0: float
    beta: float
    gamma: float
    c: float = C_DECAY

    @classmethod
    def of(cls, layer: Layer, c: float = C_DECAY) -> LayerSplit:
        F = taylor_coefficients(layer.factor, n=3, radius=0.1, m=48)
        F0 = layer.F0
        beta = F[1] + c * (F0 - 1.0)
        gamma = F[2] + beta * c - (F0 - 1.0) * c * c / 2.0
        return cls(layer, F0, float(beta), float(gamma), c)

    @cached_property
    def rho_odd(self) -> tuple[float, float]:
        """Coefficients of ``t^3`` and ``t^5`` in ``rho(t)`` (they set its far field)."""

        def rho_c(z):
            e = np.exp(-self.c * z)
            F = self.layer.factor(z)
            s = (self.F0 - 1.0) * e / z + self.beta * e + self.gamma * z * e
            return (F - 1.0) / z - s

        co = taylor_coefficients(rho_c, n=6, radius=0.1, m=64)
        return float(co[3]), float(co[5])

    def remainder(self, t: np.ndarray) -> np.ndarray:
        """``rho(t)``, O(t^2) at 0 (set to 0 for t < 1e-6, where it is below 1e-12)."""
        t = np.asarray(t, dtype=float)
        out = np.zeros_like(t)
        m = t >= 1e-6
        tm = t[m]
        e = np.exp(-self.c * tm)
        F = self.layer.factor(tm)
        out[m] = ((F - 1.0) - (self.F0 - 1.0) * e) / tm - self.beta * e - self.gamma * tm * e
        return out


@lru_cache(maxsize=64)
def _split_of(layer: Layer | StackFRF) -> LayerSplit:
    """:meth:`LayerSplit.of`, cached per layer (its Taylor coefficients are Cauchy integrals)."""
    return LayerSplit.of(layer)


def _remainder_kspace(split, h, nx, ny, dx, dy, oversample=2):
    """The remainder's cell-integrated kernel / ``(2 h / Ec*)`` on the quadrant, by the inverse
    transform of its samples on a frequency grid of period ``oversample * 2 n`` cells.

    The samples are even in ``kx`` and ``ky``, so the inverse 2-D FFT of the ``My x Mx`` grid is
    the (unnormalised) 2-D DCT-I of its ``(My/2 + 1) x (Mx/2 + 1)`` quadrant divided by
    ``Mx My``: the same numbers to round-off (1e-16 of the largest) from a quarter of the
    samples, about twice as fast at n = 128 (the remainder's evaluation dominates).
    """
    Mx, My = oversample * 2 * nx, oversample * 2 * ny
    kx = 2 * np.pi * sfft.rfftfreq(Mx, dx)  # 0 .. Mx/2
    ky = 2 * np.pi * np.abs(sfft.fftfreq(My, dy)[: My // 2 + 1])  # 0 .. My/2
    g_hat = _radial_quadrant(lambda k: split.remainder(k * h), kx, ky)
    g_hat *= np.sinc(kx * dx / (2 * np.pi))[None, :]
    g_hat *= np.sinc(ky * dy / (2 * np.pi))[:, None]
    g = sfft.dctn(g_hat, type=1) / (Mx * My)  # cell-integrated kernel / (2 h / Ec*)
    return g[: ny + 1, : nx + 1]


def _radial_quadrant(fun, kx: np.ndarray, ky: np.ndarray) -> np.ndarray:
    """``fun(hypot(kx, ky))`` on ``ky[:, None] x kx[None, :]``, ``fun`` elementwise; evaluated
    on the upper triangle only when ``kx`` and ``ky`` are equal (bitwise the same values)."""
    if kx.size == ky.size and np.array_equal(kx, ky):
        return _radial_symmetric(fun, kx)
    return fun(np.hypot(kx[None, :], ky[:, None]))


def _radial_symmetric(fun, x: np.ndarray) -> np.ndarray:
    """``fun(hypot(x[None, :], x[:, None]))`` with ``fun`` (elementwise) evaluated on the upper
    triangle only: ``hypot`` is symmetric, so the result is bitwise the full evaluation."""
    iu, ju = _triangle(x.size)
    vals = fun(np.hypot(x[ju], x[iu]))
    out = np.empty((x.size, x.size))
    out[iu, ju] = vals
    out[ju, iu] = vals
    return out


def _triangle(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Row and column indices (int32) of the upper triangle of an ``n x n`` array, read-only;
    cached up to ``n = 1600`` (10 MB each; the triangle of a larger array is made when needed)."""
    return _triangle_cached(n) if n <= 1600 else _triangle_of(n)


@lru_cache(maxsize=16)
def _triangle_cached(n: int) -> tuple[np.ndarray, np.ndarray]:
    return _triangle_of(n)


def _triangle_of(n: int) -> tuple[np.ndarray, np.ndarray]:
    iu, ju = np.triu_indices(n)
    iu, ju = iu.astype(np.int32), ju.astype(np.int32)
    iu.flags.writeable = False
    ju.flags.writeable = False
    return iu, ju


#: Radial tables are made for reaches ``S = rcut / h`` rounded up to this ratio, so that the nested
#: grids of one solve (same domain, same layer) and cases differing only in load share a table.
S_STEP = 2.0 ** 0.125


@lru_cache(maxsize=64)
def _radial_table(split: LayerSplit, S: float) -> CubicSpline:
    """``h^2 g(s)`` for ``s = r/h`` in ``[0, S]``: the remainder's radial Hankel transform
    ``(1/2 pi) int rho(t) t J0(s t) dt`` (composite Gauss--Legendre, 16 nodes per panel, two
    panels per period of ``J0`` at ``s = S``, up to ``t = 16`` where ``rho ~ e^{-2t}`` is below
    1e-13, or ``16 h/h_top`` for a stack whose top layer is ``h_top`` thick), tabulated at 513
    points (cubic spline). It depends on the layer and ``S`` only, not on ``h`` or the grid,
    hence cached."""
    # rho decays like exp(-2 t) for one layer; a stack's like exp(-2 t h_top/h) (its top layer)
    tmax = 32.0 / min(split.c, 2.0) / getattr(split.layer, "top_fraction", 1.0)
    s, t, w, J = _hankel_nodes(tmax, S)
    return CubicSpline(s, (J @ (split.remainder(t) * t * w)) / (2 * np.pi))


@lru_cache(maxsize=32)
def _hankel_nodes(tmax: float, S: float) -> tuple[np.ndarray, ...]:
    """The nodes of :func:`_radial_table`: ``s`` (513 points on ``[0, S]``), the Gauss--Legendre
    nodes ``t`` and weights ``w`` on ``[0, tmax]`` and the matrix ``J0(s t)`` (read-only).

    They depend on ``tmax`` and ``S`` only, not on the layer: cases with different coatings
    whose grids reach the same ``S`` (rounded to powers of :data:`S_STEP`) share the matrix,
    whose Bessel functions cost most of a table (up to 513 x 1216 values, 5 MB; the 31
    reaches of the quick report's grids take 45 MB)."""
    xg, wg = _leggauss(16)
    panels = int(max(8, tmax * S / (4 * np.pi)))
    edges = np.linspace(0.0, tmax, panels + 1)
    half = 0.5 * np.diff(edges)
    t = (edges[:-1, None] + half[:, None] * (xg[None, :] + 1)).ravel()
    w = (half[:, None] * wg[None, :]).ravel()
    s = np.linspace(0.0, S, 513)
    J = j0(np.outer(s, t))
    for a in (s, t, w, J):
        a.flags.writeable = False
    return s, t, w, J


@lru_cache(maxsize=8)
def _leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss--Legendre nodes and weights on ``[-1, 1]`` (cached; read-only)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


def _table_reach(rmax_over_h: float) -> float:
    """``S = rcut/h``: ``R_CUT``, or the grid's reach rounded up to a power of :data:`S_STEP`."""
    if rmax_over_h >= R_CUT:
        return R_CUT
    return min(R_CUT, S_STEP ** math.ceil(math.log(rmax_over_h) / math.log(S_STEP) - 1e-9))


def _remainder_space(split: LayerSplit, h, nx, ny, dx, dy):
    rmax = np.hypot((nx + 1) * dx, (ny + 1) * dy)
    S = _table_reach(rmax / h)
    rcut = S * h
    spline = _radial_table(split, S)
    # beyond rcut: far field of the |k|^3 and |k|^5 terms of rho (int k^4 J0 = 9/r^5,
    # int k^6 J0 = -225/r^7), matched to the table at rcut
    r3, r5 = split.rho_odd
    tail = (9.0 * r3 * h**3 / rcut**5 - 225.0 * r5 * h**5 / rcut**7) / (2 * np.pi)
    scale_tail = float(spline(S)) / (h * h) / tail if tail != 0 and rcut < rmax else 1.0

    def g(rr):
        out = spline(np.minimum(rr, rcut) / h) / (h * h)
        far = rr > rcut
        if np.any(far):
            rf = rr[far]
            out[far] = scale_tail * (9.0 * r3 * h**3 / rf**5 - 225.0 * r5 * h**5 / rf**7) / (
                2 * np.pi
            )
        return out

    # Gauss points per cell and axis: 3 for kernels 4-8 cells wide, 2 beyond (error (dx/h)^4)
    gx, gw = _leggauss(3 if h < 2 * H_SWITCH * max(dx, dy) else 2)
    xs = (np.arange(nx + 1)[:, None] * dx + gx[None, :] * dx / 2).ravel()
    ys = (np.arange(ny + 1)[:, None] * dy + gx[None, :] * dy / 2).ravel()
    if nx == ny and dx == dy:  # symmetric in x and y: g on the upper triangle only (bitwise)
        vals = _radial_symmetric(g, xs)
    else:
        vals = g(np.hypot(xs[None, :], ys[:, None]))
    m = gx.size
    vals = vals.reshape(ny + 1, m, nx + 1, m)
    out = np.einsum("iajb,a,b->ij", vals, gw, gw)
    return out * (dx * dy / 4.0)


def layer_coefficients(
    coating_body: Body, nx: int, ny: int, dx: float, dy: float, interface: str = "bonded"
) -> np.ndarray:
    """Cell coefficients of a coated body (quadrant ``(ny+1, nx+1)``) [m/Pa].

    See the module docstring for the method. ``coating_body.coating.h = 0`` gives the substrate.
    """
    if coating_body.is_stacked:  # the stack's F in t = w h (h: total thickness)
        h = sum(L.h for L in coating_body.layers)
        layer = StackFRF(coating_body.layers, coating_body.material, h)
        cmat = layer.coating
    elif coating_body.coating is None or coating_body.coating.h == 0:
        return love_coefficients(nx, ny, dx, dy, coating_body.material.E_star)
    else:
        cmat = coating_body.coating.material
        h = coating_body.coating.h
        layer = Layer(cmat, coating_body.material, interface)
    Ec = cmat.E_star
    split = _split_of(layer)
    a = split.c * h
    love_a, solid, d_solid = _layer_corner_sums(nx, ny, dx, dy, a)
    K = _love_unit(nx, ny, float(dx), float(dy)).copy()
    K += (split.F0 - 1.0) * love_a
    K += split.beta * h * solid
    K -= split.gamma * h * h * d_solid
    K /= np.pi * Ec
    if h < H_SWITCH * max(dx, dy):
        rem = _remainder_kspace(split, h, nx, ny, dx, dy)
    else:
        rem = _remainder_space(split, h, nx, ny, dx, dy)
    return K + rem * (2.0 * h / Ec)


def body_coefficients(
    body: Body, nx: int, ny: int, dx: float, dy: float, interface: str = "bonded"
) -> np.ndarray:
    """Cell coefficients of one body: zero if rigid, Love if uncoated, else layered."""
    if body.is_rigid:
        return np.zeros((ny + 1, nx + 1))
    if body.is_coated or body.is_stacked:
        return layer_coefficients(body, nx, ny, dx, dy, interface)
    return love_coefficients(nx, ny, dx, dy, body.material.E_star)


def circulant(quadrant: np.ndarray) -> np.ndarray:
    """Place quadrant coefficients (offsets 0..n) in the ``2 ny x 2 nx`` wrap-around array.

    Index ``i`` of the result holds offset ``i`` for ``i <= n`` and ``i - 2n`` above; with a
    pressure zero-padded to ``2n`` the cyclic convolution is the exact linear convolution.
    """
    ny1, nx1 = quadrant.shape
    nx, ny = nx1 - 1, ny1 - 1
    if nx < 1 or ny < 1:
        raise CoatHertzError("quadrant must be at least 2 x 2")
    ix = np.arange(2 * nx)
    iy = np.arange(2 * ny)
    ix = np.minimum(ix, 2 * nx - ix)
    iy = np.minimum(iy, 2 * ny - iy)
    return quadrant[iy[:, None], ix[None, :]]
