"""Huber's (1904) closed-form stress field under a Hertzian pressure (Johnson 1985, eq 3.44-3.46).

Implemented here, independently of the package, from the published formulas.
"""

from __future__ import annotations

import numpy as np


def huber(r, z, a: float, nu: float):
    """(sigma_r, sigma_theta, sigma_z, tau_rz) / p0 at (r, z), z > 0 or r > a on z = 0."""
    r, z = np.broadcast_arrays(np.asarray(r, float), np.asarray(z, float))
    q = r * r + z * z - a * a
    u = 0.5 * (q + np.sqrt(q * q + 4 * a * a * z * z))
    su = np.sqrt(u)
    zu = np.divide(z, su, out=np.zeros_like(z), where=su > 0)
    inside = (su == 0) & (r <= a)
    zu = np.where(inside, np.sqrt(np.clip(1 - (r / a) ** 2, 0, None)), zu)
    den = u * u + a * a * z * z
    # surface inside the contact: u ~ a^2 z^2 / (a^2 - r^2), so a^2 u / den -> a^2 / (a^2 - r^2)
    lim = np.asarray(a * a / np.where(inside, a * a - r * r, 1.0), dtype=float)
    frac = np.divide(a * a * u, den, out=lim, where=den > 0)
    at = np.where(su > 0, su / a * np.arctan2(a, su), 0.0)
    r2 = np.where(r > 0, r * r, 1.0)
    # 1 - (z/sqrt u)^3 without cancellation near the axis: v = u - z^2 solves
    # v^2 + v (z^2 + a^2 - r^2) - r^2 z^2 = 0
    b = z * z + a * a - r * r
    root = np.sqrt(b * b + 4 * r * r * z * z)
    v = np.where(b > 0, 2 * r * r * z * z / np.where(b > 0, b + root, 1.0), 0.5 * (root - b))
    x = np.divide(v, u, out=np.ones_like(u), where=u > 0)
    one_minus = np.where(inside, 1 - zu**3, -np.expm1(1.5 * np.log1p(-np.minimum(x, 1.0))))
    first = (1 - 2 * nu) / 3 * a * a / r2 * one_minus
    # r -> 0 limit of the first term (axis): (1 - 2 nu) a^2 / (2 (a^2 + z^2))
    first = np.where(r > 0, first, (1 - 2 * nu) * a * a / (2 * (a * a + z * z)))
    sr = first + zu**3 * frac + zu * ((1 - nu) * u / (a * a + u) + (1 + nu) * at - 2)
    st = -first - zu * (2 * nu + (1 - nu) * u / (a * a + u) - (1 + nu) * at)
    sz = -(zu**3) * frac
    trz = -np.divide(r * z * z, den, out=np.zeros_like(u), where=den > 0) * (
        a * a * su / (a * a + u))
    return sr, st, sz, trz


def hertz_on_grid(n: int, width: float, a: float = 1.0):
    """Hertz's pressure ``sqrt(1 - (r/a)^2)`` (p0 = 1) at the cell centres of an ``n x n`` FFT grid
    spanning ``width``: ``(grid, X, Y, R, p)``."""
    from coathertz.fft.grid import Grid

    g = Grid(n, n, width / n, width / n)
    X, Y = np.meshgrid(g.x, g.y)
    R = np.hypot(X, Y)
    return g, X, Y, R, np.sqrt(np.clip(1 - (R / a) ** 2, 0, None))
