"""Contact size and peak pressure from a discrete pressure field.

* :func:`area_radius` -- the paper's ``a_num = sqrt(S / pi)`` (Section 3), ``S`` the area of
  the cells carrying pressure. A cell is in or out, so the error scatters and is first order:
  against the exact axisymmetric solution (25 cases of the paper's families) up to 0.61 % at
  n = 128, 0.29 % at 256, biased positive.
* :func:`moment_axes` -- semi-axes of an elliptical contact from the second moments of the
  contact set, scaled so that ``pi r_a r_b = S`` (first estimate of the shape).
* :func:`gap_fit_axes` -- the sub-cell estimator for coated bodies. Just outside a smooth edge
  the gap grows like ``(r - a)^{3/2}``: ``g^{2/3}`` crosses zero linearly at the edge. It is
  fitted (quadratic in ``S = (x/r_a)^2 + (y/r_b)^2``) on the non-contact cells of a band
  ``GAP_BAND_CELLS = 2`` cells wide outside the contact, so the band shrinks with the cell:
  a coating only a few cells thick has its own boundary layer at the edge (width ~h), which
  a band fixed in units of ``a`` straddles (the previous ``p^2`` fit over >= 0.25 a converged
  to a value up to 0.8 % off). The gap is the smooth part of the discrete solution (a
  convolution of the pressure); the pressure of the last contact cells carries the
  collocation error of the edge, so a fit of ``p^2`` inside over a few cells scatters more.
  Measured against the exact axisymmetric solution over the paper's circular families
  (elastic substrate E = 1/4, 4 and H = 0.01-3, rigid substrate nu_c = 0.3-0.5 and
  H = 0.05-3, bonded and frictionless; 24 coated cases), on grids re-fitted to the contact
  (:mod:`coathertz.fft.grid`): max |error| 0.36 % at n = 64, 0.128 % at 128, 0.024 % at
  256, observed order about 2. Over 55 more thin cases (E = 1/4-4, H = 0.01-0.03, bonded
  and frictionless) the error is at most 0.067 % at n = 128 where the coating spans a cell
  or more, and 0.037 % at n = 256. A coating thinner than a cell is the limit: its edge
  boundary layer (width ~h; the exact pressure rises from 0.01 to 0.08 p0 within 0.04 cells
  of the edge at E = 4, H = 0.01) lies inside the cell next to the edge, and stiff coatings
  are then off by up to +0.169 % at n = 128 (bonded E = 4, h = 0.64 cells; frictionless
  E = 3, h = 0.51 cells: +0.160 %). The fit on the *exact* gap sampled at the same cells is
  already +0.044 % off there, and the grid's own gap is 2-10 % high within a cell of the
  edge. Tried without success for that regime (E = 4, H = 0.01 at n = 128 in brackets):
  other bands and degrees (+0.118 to +0.25 %), a joint
  fit of ``p^2`` inside and ``g^{2/3}`` outside with one root (+0.156 %), a global fit of
  ``sqrt(1 - r^2/a^2)`` times a polynomial (ill-conditioned, up to 1.7 %), Richardson with
  the grid of cells twice as large (+0.015 %, but +0.118 % on frictionless and +0.101 % on
  bonded E = 3, H = 0.01), an alias-free cell integral of the layer remainder (+0.115 %),
  smaller margins, and a plane-strain 1-D emulation of the grid's edge bias (predicted
  +0.23 % where the 3-D grid gives +0.128 %). :class:`~coathertz.fft.method.FFTMethod`
  therefore resolves the coating: by default it solves such a case again on the same domain
  with the ``n`` that gives the coating a cell (``layer_cells``; all 79 cases then within
  0.1 % at n = 128), and flags the result where it does not.
  Ellipses: a fit in a sector around each axis (the gap's
  intensity varies along the edge); Hertz ellipse with dy = dx/3 at n = 128: r_a +0.02 %,
  r_b +0.05 % (the ``p^2`` fit with the moment shape: -0.18 %, +0.19 %).
* :func:`edge_fit_axes` -- for uncoated circular contacts: ``p^2`` is exactly linear in ``s`` (Hertz),
  so a quadratic in ``s`` fitted over an outer band ``EDGE_BAND_CELLS`` cells and at least
  ``EDGE_BAND_MIN`` of the radius wide averages the collocation scatter best: |error|
  <= 1e-4 for n >= 64 against Hertz.
* :func:`peak_pressure` -- ``p0 = max p`` (the cell at the origin is a collocation point).
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.fft.grid import Grid

EDGE_BAND_CELLS = 8
EDGE_BAND_MIN = 0.25


def contact_area(p: np.ndarray, grid: Grid) -> float:
    """``S`` = area of the cells with ``p > 0`` [m^2]."""
    return float(np.count_nonzero(p > 0)) * grid.cell_area


def contact_extent(p: np.ndarray, grid: Grid) -> tuple[float, float]:
    """Half-widths ``(x, y)`` of the cells with ``p > 0``, to their outer edges [m] (0 without
    contact)."""
    m = p > 0
    if not np.any(m):
        return 0.0, 0.0
    rows, cols = np.nonzero(m)
    return (float(np.max(np.abs(grid.x[cols]))) + grid.dx / 2,
            float(np.max(np.abs(grid.y[rows]))) + grid.dy / 2)


def area_radius(p: np.ndarray, grid: Grid) -> float:
    """``a_num = sqrt(S / pi)`` (Section 3)."""
    return math.sqrt(contact_area(p, grid) / math.pi)


def peak_pressure(p: np.ndarray) -> float:
    return float(np.max(p))


def moment_axes(p: np.ndarray, grid: Grid) -> tuple[float, float]:
    """``(r_a, r_b)`` along x and y from the second moments of the contact set (area-exact)."""
    m = p > 0
    if not np.any(m):
        return (0.0, 0.0)
    X, Y = np.meshgrid(grid.x, grid.y)
    # uniform ellipse: <x^2> = r_a^2 / 4; include the cell's own variance dx^2/12
    ra = 2.0 * math.sqrt(max(np.mean(X[m] ** 2) + grid.dx**2 / 12, 0.0))
    rb = 2.0 * math.sqrt(max(np.mean(Y[m] ** 2) + grid.dy**2 / 12, 0.0))
    S = contact_area(p, grid)
    k = math.sqrt(S / (math.pi * ra * rb))
    return (ra * k, rb * k)


def edge_fit_axes(
    p: np.ndarray, grid: Grid, r_a: float, r_b: float
) -> tuple[float, float] | None:
    """Semi-axes from a fit of ``p^2`` near the edge (see module docstring); for Hertz only.

    ``r_a, r_b`` are first estimates (e.g. :func:`moment_axes`) that fix the shape; the result
    rescales them by the fitted root ``s*`` of ``p^2(s)``. ``None`` when the band holds too
    few cells or the fit has no root. The band is a quarter of the radius wide: exact for a
    Hertzian ``p^2`` (linear in ``s``) but biased for coated bodies, where
    :func:`gap_fit_axes` is used instead.
    """
    if r_a <= 0 or r_b <= 0:
        return None
    X, Y = np.meshgrid(grid.x, grid.y)
    s = (X / r_a) ** 2 + (Y / r_b) ** 2
    cells = min(r_a / grid.dx, r_b / grid.dy)
    w = max(EDGE_BAND_CELLS / cells, EDGE_BAND_MIN)
    band = (p > 0) & (s >= (1.0 - min(w, 0.9)) ** 2)
    if np.count_nonzero(band) < 6:
        return None
    sb, pb = s[band] - 1.0, p[band] ** 2
    pb = pb / pb.max()
    A = np.stack([sb * sb, sb, np.ones_like(sb)], axis=1)
    (c2, c1, c0), *_ = np.linalg.lstsq(A, pb, rcond=None)
    roots = np.roots([c2, c1, c0]) if abs(c2) > 1e-12 * abs(c1) else np.array([-c0 / c1])
    roots = roots[np.isreal(roots)].real
    if roots.size == 0:
        return None
    ds = roots[np.argmin(np.abs(roots))]
    k = math.sqrt(max(1.0 + ds, 0.0))
    # the contact set fixes the edge to within a cell: a fit outside that (a pressure that is
    # not square-root-like on the grid scale, e.g. thin incompressible layers) is clipped
    lim = 1.0 / cells
    k = min(max(k, 1.0 - lim), 1.0 + lim)
    return (r_a * k, r_b * k)


#: Width of the band of cells outside the contact used by :func:`gap_fit_axes` [cells].
GAP_BAND_CELLS = 2.0
#: ``sin^2`` of the half-angle of the sectors around the axes used for an ellipse (30 deg).
SECTOR_SIN2 = 0.25


def gap_fit_axes(
    p: np.ndarray,
    gap: np.ndarray,
    grid: Grid,
    r_a: float,
    r_b: float,
    *,
    circular: bool = False,
    band_cells: float = GAP_BAND_CELLS,
) -> tuple[float, float] | None:
    """Semi-axes where the gap just outside the contact closes (sub-cell; see module docstring).

    Near a smooth edge the gap grows like ``(r - a)^{3/2}``, so ``g^{2/3}`` is a smooth
    function that crosses zero linearly at the edge. It is fitted by least squares on the
    non-contact cells (``p = 0``, ``g > 0``) within ``band_cells`` cells outside the first
    estimate ``(r_a, r_b)``: as a quadratic in ``S = (x/r_a)^2 + (y/r_b)^2`` for a circle
    (``circular``); for an ellipse (where the gap's intensity varies along the edge) in a
    sector of +-30 degrees around each axis, with ``sin^2`` of the angle from the axis and its
    product with ``S - 1`` as extra terms; the roots on the axes are the semi-axes. The band scales with
    the cell, not with the contact, so the fit's truncation error falls like ``dx^2``.

    Returns ``None`` when the band holds too few cells or the fit has no root within two cells
    of the estimate (the caller falls back to the area estimate).
    """
    if r_a <= 0 or r_b <= 0:
        return None
    x = grid.x / r_a
    y = grid.y / r_b
    X = np.broadcast_to((x * x)[None, :], grid.shape)
    Y = np.broadcast_to((y * y)[:, None], grid.shape)
    cells = min(r_a / grid.dx, r_b / grid.dy)
    rho_max = (1.0 + band_cells / cells) ** 2
    sel = (p <= 0) & (gap > 0) & (X + Y < rho_max)
    if np.count_nonzero(sel) < (12 if circular else 24):
        return None
    Xs, Ys = X[sel], Y[sel]
    v = np.cbrt(gap[sel]) ** 2
    v = v / v.max()
    lim = 2.0 / cells  # the contact set fixes the edge to within about a cell
    if circular:
        S = Xs + Ys - 1.0
        c2, c1, c0 = np.polyfit(S, v, 2)
        k = _root_near_one(c0, c1, c2)
        if k is None or abs(k - 1.0) > lim:
            return None
        return (r_a * k, r_b * k)
    # an ellipse: the gap's intensity varies along the edge, so each semi-axis is fitted in a
    # sector around its axis, with the angular variation (sin^2 phi, even about the axis) of
    # the root and of the slope as extra terms; the root on the axis is the semi-axis
    S = Xs + Ys
    ks = []
    for across in (Ys, Xs):  # x axis: across = Y; y axis: across = X
        s2 = across / S  # sin^2 of the angle from the axis (in scaled coordinates)
        sec = s2 < SECTOR_SIN2
        if np.count_nonzero(sec) < 12:
            return None
        t, w, vv = S[sec] - 1.0, s2[sec], v[sec]
        A = np.stack([np.ones_like(t), t, t * t, w, w * t], axis=1)
        c, *_ = np.linalg.lstsq(A, vv, rcond=None)
        ks.append(_root_near_one(c[0], c[1], c[2]))
    kx, ky = ks
    if kx is None or ky is None or max(abs(kx - 1.0), abs(ky - 1.0)) > lim:
        return None
    return (r_a * kx, r_b * ky)


def _root_near_one(c0: float, c1: float, c2: float) -> float | None:
    """``sqrt(1 + t)`` for the root ``t`` of ``c0 + c1 t + c2 t^2`` nearest 0 (None if none)."""
    if abs(c2) > 1e-12 * abs(c1):
        roots = np.roots([c2, c1, c0])
        roots = roots[np.isreal(roots)].real
    elif c1 != 0:
        roots = np.array([-c0 / c1])
    else:
        return None
    if roots.size == 0:
        return None
    t = roots[np.argmin(np.abs(roots))]
    return math.sqrt(1.0 + t) if t > -1.0 else None
