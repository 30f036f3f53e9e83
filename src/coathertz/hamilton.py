r"""Hamilton's (1983) explicit stress field under a sliding Hertzian sphere (closed form).

G. M. Hamilton, "Explicit equations for the stresses beneath a sliding spherical contact",
Proc. Instn Mech. Engrs 197C (1983) 53--59. A homogeneous half-space (Poisson's ratio
:math:`\nu`) carries Hertz's pressure :math:`p = p_0\sqrt{1 - r^2/a^2}` and, in full sliding,
the shear traction :math:`q = \mu p` along :math:`+x` (acting on the body). The field is the
sum of the normal part (Hamilton's eqs for the load :math:`P`, equivalent to Huber's 1904
field, Johnson 1985 eq 3.44) and :math:`\mu` times the tangential part (Hamilton's eqs for
:math:`Q`). With :math:`a = 1` and (Hamilton's auxiliaries)

.. math::

    A = r^2 + z^2 - 1,\quad S = \sqrt{A^2 + 4 z^2},\quad M = \sqrt{(S + A)/2},\quad
    N = \sqrt{(S - A)/2},\quad \phi = \arctan(1/M),

    G = M^2 - N^2 + z M - N,\quad H = 2 M N + M + z N,

every component is an explicit algebraic function of :math:`x, y, z` and these
(:func:`normal_part`, :func:`tangential_part`). On the axis :math:`r = 0` the limits are taken
separately (Hamilton's eqs for :math:`r = 0`).

Conventions (as :mod:`coathertz.fft.stresses`): ``z >= 0`` is the depth, tension positive,
Voigt order ``xx, yy, zz, yz, xz, xy``; :math:`\sigma_{zz}(0) = -p`, :math:`\sigma_{xz}(0) = -q`.
On the surface inside the contact this gives Johnson's (1985, sec. 7.2)
:math:`\sigma_x = \sigma_r^{Hertz} - (4 + \nu)\pi\mu x/(8a)\, p_0`.

This module is a closed form only: the FFT's own stresses are checked against it
(``tests/stresses/test_hamilton.py``), it shares no code with any solver.
"""

from __future__ import annotations

import numpy as np

from coathertz.stress_summary import von_mises

__all__ = ["normal_part", "sliding_stresses", "tangential_part", "von_mises_max_xz"]


def _aux(x, y, z):
    x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
    r2 = x * x + y * y
    A = r2 + z * z - 1.0
    S = np.sqrt(A * A + 4.0 * z * z)
    M = np.sqrt(np.maximum(0.5 * (S + A), 0.0))
    N = np.sqrt(np.maximum(0.5 * (S - A), 0.0))
    phi = np.arctan2(1.0, M)
    return x, y, z, r2, A, S, M, N, phi


def _safe(v):
    """``v`` with zeros replaced by one (the axis limits are taken separately)."""
    return np.where(v > 0, v, 1.0)


def normal_part(x, y, z, nu: float) -> np.ndarray:
    """Stresses / p0 under Hertz's pressure (a = 1): shape ``(6,) + broadcast shape``.

    Hamilton (1983) eqs for the normal load; on the axis
    :math:`\\sigma_x = \\sigma_y = (1 + \\nu)(z \\arctan(1/z) - 1) + 1/(2 (1 + z^2))`,
    :math:`\\sigma_z = -1/(1 + z^2)` (Johnson eq 3.45).
    """
    x, y, z, r2, A, S, M, N, phi = _aux(x, y, z)
    Ss, rs = _safe(S), _safe(r2)
    G = M * M - N * N + z * M - N
    H = 2.0 * M * N + M + z * N
    # common bracket of the lateral stresses
    lat = (1 - nu) * N * z * z - (1 - 2 * nu) / 3.0 * (N * S + 2.0 * A * N + 1.0) - nu * M * z
    sxx = (1 + nu) * z * phi + ((y * y - x * x) / rs * lat - N * (x * x + 2 * nu * y * y)
                                 - M * x * x * z / Ss) / rs
    syy = (1 + nu) * z * phi + ((x * x - y * y) / rs * lat - N * (y * y + 2 * nu * x * x)
                                 - M * y * y * z / Ss) / rs
    szz = -N + z * M / Ss
    sxy = (x * y * (1 - 2 * nu) / rs**2 * (-N * r2 + 2.0 / 3.0 * N * (S + 2.0 * A) - z * (z * N + M)
                                           + 2.0 / 3.0)
           + x * y * z / rs**2 * (-M * r2 / Ss - z * N + M))
    GH = _safe(G * G + H * H)
    shear = z * (N / Ss - z * H / GH)
    sxz = -x * shear
    syz = -y * shear
    axis = r2 == 0
    if np.any(axis):
        za = np.where(axis, z, 1.0)
        lat_axis = (1 + nu) * (za * np.arctan2(1.0, za) - 1.0) + 0.5 / (1.0 + za * za)
        sxx = np.where(axis, lat_axis, sxx)
        syy = np.where(axis, lat_axis, syy)
        szz = np.where(axis, -1.0 / (1.0 + za * za), szz)
        sxy = np.where(axis, 0.0, sxy)
    return np.stack([sxx, syy, szz, syz, sxz, sxy])


def tangential_part(x, y, z, nu: float) -> np.ndarray:
    """Stresses / (mu p0) under the shear traction ``q = p`` along +x (a = 1).

    Hamilton (1983) eqs for the tangential load; on the axis only
    :math:`\\sigma_{xz} = -1 + \\tfrac32 z \\arctan(1/z) - z^2/(2 (1 + z^2))` is non-zero.
    """
    x, y, z, r2, A, S, M, N, phi = _aux(x, y, z)
    Ss, rs = _safe(S), _safe(r2)
    x2, y2, z2 = x * x, y * y, z * z
    cx = 1.5 - 2.0 * x2 / rs  # (3/2 - 2 x^2/r^2)
    hx = 0.5 - 2.0 * x2 / rs  # (1/2 - 2 x^2/r^2)
    hy = 0.5 - 2.0 * y2 / rs
    k = 1.0 - 2.0 * nu
    lin = -k * (S / 6.0 + A / 3.0)  # -(1 - 2 nu)(S/6 + A/3)
    r4 = rs * rs
    sxx = (-x * (nu / 4.0 + 1.0) * phi
           + x * M / r4 * (cx * (nu * (S - 2.0 * A) + z2) + x2 * z2 / Ss + 7.0 * nu * r2 / 4.0
                           - 2.0 * nu * x2 + r2)
           + x * z * N / r4 * (cx * (lin - 0.5 * (z2 + 3.0)) + x2 / Ss - nu * r2 / 4.0 - 7.0 * r2 / 4.0)
           + 4.0 * x * z / (3.0 * r4) * cx * k)
    syy = (-0.75 * nu * x * phi
           + x * M / r4 * (hy * (nu * (S - 2.0 * A + r2) + z2) + y2 * z2 / Ss + 0.75 * nu * r2)
           + x * z * N / r4 * (hy * (lin - 0.5 * z2 - 1.5) + y2 / Ss - 0.75 * nu * r2 - 0.25 * r2)
           + 4.0 * x * z / (3.0 * r4) * hy * k)
    szz = 0.5 * x * z * N / rs * (1.0 - (r2 + z2 + 1.0) / Ss)
    sxy = (0.5 * y * (nu / 2.0 - 1.0) * phi
           + y * M / r4 * (x2 * z2 / Ss + nu * ((S - 2.0 * A) * hx - 2.0 * x2 + r2 / 4.0) + r2 / 2.0
                           + z2 * hx)
           + y * z * N / r4 * (hx * (lin - 0.5 * z2 - 1.5 - 0.5 * r2) + nu * r2 / 4.0 + x2 / Ss
                               - 0.5 * y2 - 1.5 * x2)
           + 4.0 * y * z / (3.0 * r4) * hx * k)
    syz = 0.5 * x * y * z / r4 * (M * (0.5 + (0.5 * z2 - 1.5 - 0.5 * r2) / Ss)
                                  + 0.5 * z * N * (-3.0 + (5.0 + z2 + r2) / Ss))
    sxz = (1.5 * z * phi + z * M / rs * (1.0 + x2 / rs - x2 / Ss)
           + N / rs * (-0.75 * (S + 2.0 * A) + z2 - 0.75 - 0.25 * r2 + 0.5 * z2 * hx))
    axis = r2 == 0
    if np.any(axis):
        za = np.where(axis, z, 1.0)
        zero = np.zeros_like(sxx)
        sxx, syy, szz, sxy, syz = (np.where(axis, zero, v) for v in (sxx, syy, szz, sxy, syz))
        sxz = np.where(axis, -1.0 + 1.5 * za * np.arctan2(1.0, za) - 0.5 * za * za / (1.0 + za * za), sxz)
    return np.stack([sxx, syy, szz, syz, sxz, sxy])


def sliding_stresses(x, y, z, nu: float, mu: float) -> np.ndarray:
    """Stresses / p0 at ``(x, y, z) / a`` under a sphere sliding along +x with friction ``mu``."""
    return normal_part(x, y, z, nu) + mu * tangential_part(x, y, z, nu)


def von_mises_max_xz(nu: float, mu: float, nx: int = 241, nz: int = 121, zmax: float = 1.0,
                     xmax: float = 1.2) -> tuple[float, float, float, float]:
    """Largest von Mises stress / p0 in the plane ``y = 0`` (where it lies, by symmetry) on an
    ``nx x nz`` grid over ``|x| <= xmax``, ``0 <= z <= zmax`` (units of a), refined by a
    parabola through the grid maximum and its neighbours in x and in z:
    ``(vm_max, x, z, surface_max)`` with ``surface_max`` the largest value on ``z = 0``."""
    xs = np.linspace(-xmax, xmax, nx)
    zs = np.linspace(0.0, zmax, nz)
    X, Z = np.meshgrid(xs, zs)
    vm = von_mises(sliding_stresses(X, 0.0 * X, Z, nu, mu), axis=0)
    k, i = np.unravel_index(np.argmax(vm), vm.shape)
    value, xm, zm = float(vm[k, i]), float(xs[i]), float(zs[k])
    for axis, coords in ((1, xs), (0, zs)):
        j = i if axis == 1 else k
        if 0 < j < len(coords) - 1:
            f = vm[k, j - 1:j + 2] if axis == 1 else vm[j - 1:j + 2, i]
            den = f[0] - 2 * f[1] + f[2]
            if den < 0:
                t = 0.5 * (f[0] - f[2]) / den
                value += -0.125 * (f[0] - f[2]) ** 2 / den
                step = coords[1] - coords[0]
                if axis == 1:
                    xm += t * step
                else:
                    zm += t * step
    return value, xm, zm, float(vm[0].max())
