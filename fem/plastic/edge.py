r"""Contact edge of an elastic-plastic indentation: node bracket and one radius estimator.

Bracket
    ``[a_lo, a_hi] = [r of the last node carrying load, r of the first free node]``: the discrete
    contact edge lies between them whatever the edge's shape.
Radius ``a`` (one estimator for elastic and plastic edges): a fit of the pressure's own decay
    Near the edge the pressure is taken as

    .. math:: p(r) = c\,(1 - r^2/a^2)_+^{\,n},

    ``n = 1/2`` at a Hertzian edge (exact for the whole Hertz distribution, Johnson eq 4.9),
    ``n -> 0`` at the edge of a fully plastic contact, whose pressure stays finite up to the edge.
    The fit is made on the nodal contact forces themselves, not on nodal pressures: the model's
    consistent Q2 nodal loads ``int p N_i 2 pi r dr`` (the same integral that makes the FE's
    contact forces) are matched in least squares to the forces of the loaded nodes with
    ``r >= F_WINDOW a_lo`` and of the first :data:`N_FREE` free nodes (zero force). The force of
    the last loaded node tells how far the pressure reaches into its shape function's support,
    which gives the edge to a fraction of the node spacing; the vertex / mid-side force
    oscillation of Q2 node-to-surface contact averages out over the window. ``c`` enters
    linearly and is eliminated (variable projection); ``a`` and ``n`` (in ``[0, 1.5]``, chosen
    from the data) are found by a bounded minimisation started from the best point of a coarse
    grid. The radius is kept in ``[a_lo - 2 s, a_lo + 2 s]`` (``s = a_hi - a_lo``, :data:`T_RANGE`);
    a fit that ends on a bound is recorded in ``clipped``.

    Measured (rigid sphere on an elastic-perfectly-plastic half-space, E/Y = 1000, nu = 0.3,
    25 approach increments to delta/delta_c = 50; scatter = largest departure of an increment's
    ``p_mean`` from the log-log interpolation between its neighbours, delta/delta_c >= 20):
    1.7 % on the default mesh and 3.3 % on the coarse one, against 3.7 % and 6.7 % for the
    earlier gap fit ``c (r - a)^m``, whose root jumped with the exponent chosen on a shifting
    window of free nodes; on the coarse mesh the FE load itself oscillates by +-2 % as the edge
    passes the nodes (``tests/plasticity/test_edge_path.py``).
Unresolved contact
    A contact narrower than one Q2 edge (:data:`MIN_LOADED`; e.g. the first increment of a deep
    path, which ends at first yield on a mesh sized for the deepest contact) has no decay to fit:
    ``a`` is then the bracket's middle and ``a_err`` its half-width (``clipped`` is set).
Uncertainty ``a_err``
    The standard error of ``a`` from the linearised least-squares problem in ``(c, a, n)`` with
    the fit's residual variance, at least 5 % of the node spacing and at most half of it (the
    bracket's half-width: beyond that the bracket itself is the better statement). On Hertz
    (delta/delta_c < 1) the error against sqrt(R delta) was at most 1.6 a_err (coarse mesh).

No switching: the same estimator is used at every increment; ``p_mean = W / (pi a^2)`` and the
bracket's ``[W / (pi a_hi^2), W / (pi a_lo^2)]`` are both reported.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares

from coathertz.errors import CoatHertzError, ConvergenceError

#: The fit window: loaded nodes with ``r >= F_WINDOW * a_lo`` (the outer half of the contact).
F_WINDOW = 0.5
#: Free nodes (zero force) beyond the edge included in the fit.
N_FREE = 2
#: Range of the radius, ``a = a_lo + t (a_hi - a_lo)`` with ``t`` in this range: from two node
#: spacings inside the last loaded node (a Q2 vertex just beyond an edge in the first half of an
#: element carries a small force) to one beyond the first free node.
T_RANGE = (-2.0, 2.0)
#: A contact whose last loaded node has an index below this (the axis node and at most one more:
#: less than one Q2 edge) is not fitted: ``a`` is the bracket's middle, ``a_err`` its half-width.
MIN_LOADED = 2
#: Range of the pressure exponent ``n``.
N_RANGE = (0.0, 1.5)
#: Start points of the fit refined (the best of the coarse grid); the deepest minimum is kept.
N_STARTS = 3
#: Gauss-Legendre points per element (the element holding the edge uses a graded rule).
_GX, _GW = np.polynomial.legendre.leggauss(10)


def check_q2_layout(r: np.ndarray) -> None:
    """Raise :class:`~coathertz.errors.CoatHertzError` unless ``r`` are the nodes of consecutive
    Q2 edges: vertices at even indices, mid-side nodes halfway between them (the surface of the
    FE model)."""
    if len(r) < 3 or len(r) % 2 == 0:
        raise CoatHertzError(f"contact candidates: expected the 2k+1 nodes of k Q2 surface edges, "
                             f"got {len(r)}")
    mid = 0.5 * (r[0:-2:2] + r[2::2])
    if not np.allclose(r[1::2], mid, rtol=0.0, atol=1e-9 * float(r[-1])):
        raise CoatHertzError("contact candidates: mid-side nodes are not halfway between the vertices")


def consistent_loads(r: np.ndarray, a: float, n: float, e0: int, e1: int) -> np.ndarray:
    """Consistent nodal loads ``int p N_i 2 pi r dr`` [N per unit c] of ``p = (1 - r^2/a^2)_+^n`` on
    the Q2 surface edges ``e0 .. e1 - 1`` (edge ``k`` spans nodes ``2k, 2k+1, 2k+2``).

    In the edge holding ``a`` the part ``[r_0, a]`` is integrated with ``x = a - (a - r_0) s^2``,
    which turns the ``(a - x)^n`` edge behaviour into the smooth ``s^(2n+1)``.
    """
    k = np.arange(e0, e1)
    ra, rb = r[2 * k], r[2 * k + 2]
    k, ra, rb = k[ra < a], ra[ra < a], rb[ra < a]
    s = 0.5 * (_GX + 1.0)
    inside = (rb <= a)[:, None]
    x = np.where(inside, ra[:, None] + (rb - ra)[:, None] * s, a - (a - ra)[:, None] * s**2)
    wq = np.where(inside, 0.5 * (rb - ra)[:, None] * _GW, 0.5 * _GW * 2.0 * (a - ra)[:, None] * s)
    p = np.clip(1.0 - (x / a) ** 2, 0.0, None) ** n * 2.0 * math.pi * x * wq
    t = (x - ra[:, None]) / (rb - ra)[:, None]
    # Q2 shape functions of the nodes at t = 0, 1/2, 1; for one j the nodes 2k + j are distinct
    F = np.zeros(len(r))
    F[2 * k] += (2.0 * (t - 0.5) * (t - 1.0) * p).sum(axis=1)
    F[2 * k + 1] += (-4.0 * t * (t - 1.0) * p).sum(axis=1)
    F[2 * k + 2] += (2.0 * t * (t - 0.5) * p).sum(axis=1)
    return F


def _fit(r: np.ndarray, lam: np.ndarray, last: int) -> tuple[float, float, float, float]:
    """``(a, n, relative residual, standard error of a)`` of the pressure fit on the window."""
    s = float(r[last + 1] - r[last])
    j0 = int(np.searchsorted(r, F_WINDOW * r[last]))
    j0 = min(j0 - j0 % 2, max(last - 3, 0) - max(last - 3, 0) % 2)  # at least 4 loaded nodes
    j1 = min(last + N_FREE, len(r) - 1)
    e0, e1 = max(j0 // 2 - 1, 0), min(j1 // 2 + 1, (len(r) - 1) // 2)  # every edge touching the window
    idx = np.arange(j0, j1 + 1)
    target = lam[idx]
    scale = max(float(np.abs(target).max()), 1e-300)
    t_lo, t_hi = T_RANGE  # a = r[last] + t s

    def model(x: np.ndarray) -> tuple[np.ndarray, float]:
        f = consistent_loads(r, float(r[last] + x[0] * s), float(x[1]), e0, e1)[idx]
        ff = float(f @ f)
        return f, (float(f @ target) / ff if ff > 0 else 0.0)

    def residual(x: np.ndarray) -> np.ndarray:
        f, c = model(x)
        return (c * f - target) / scale

    # start points between the nodes (at a node the loads' derivative in a jumps)
    grid = [(t, n) for t in np.linspace(t_lo + 0.25, t_hi - 0.25, 8) for n in np.linspace(*N_RANGE, 4)]
    # the objective can have several local minima of nearly equal depth: a single start from the
    # grid's best point would follow whichever start wins by round-off, so the best N_STARTS grid
    # points are each refined and the deepest minimum kept
    ranked = sorted(grid, key=lambda x: float(np.linalg.norm(residual(np.array(x)))))
    sol = min((least_squares(residual, np.array(x0), bounds=([t_lo, N_RANGE[0]], [t_hi, N_RANGE[1]]),
                             diff_step=1e-7, xtol=1e-12, ftol=1e-12, gtol=1e-12)
               for x0 in ranked[:N_STARTS]), key=lambda so: float(so.cost))
    sol.fun = float(np.linalg.norm(sol.fun))
    # standard error of a: linearised least squares in (c, t, n) with the residual's variance
    f0, c0 = model(sol.x)
    h = 1e-4
    J = [f0]
    for j in range(2):
        xp = sol.x.copy()
        xp[j] += h if xp[j] + h <= (t_hi, N_RANGE[1])[j] else -h
        J.append(c0 * (model(xp)[0] - f0) / (xp[j] - sol.x[j]))
    Jm = np.column_stack(J)
    dof = max(len(idx) - 3, 1)
    sigma2 = float(np.sum((c0 * f0 - target) ** 2)) / dof
    try:
        se_t = math.sqrt(sigma2 * float(np.linalg.inv(Jm.T @ Jm)[1, 1]))
    except (np.linalg.LinAlgError, ValueError):
        se_t = math.inf
    return float(r[last] + sol.x[0] * s), float(sol.x[1]), float(sol.fun), se_t * s


def edge_radius(r: np.ndarray, lam: np.ndarray, active: np.ndarray) -> dict:
    """Bracket, radius estimate, its uncertainty and the pressure exponent at the edge.

    Parameters
    ----------
    r
        Radii of the contact candidates [m], increasing: the nodes of consecutive Q2 surface
        edges (:func:`check_q2_layout`).
    lam
        Nodal contact force of every candidate [N] (``>= 0``, zero off the contact).
    active
        Candidates in contact (a disc: all nodes up to the last one).

    Returns
    -------
    dict
        ``a_lo``, ``a_hi`` (bracket) [m], ``a`` [m], ``a_err`` [m], ``n`` (pressure exponent
        of the fit), ``residual`` (relative), ``clipped`` (bool).

    Raises
    ------
    ConvergenceError
        Fewer than :data:`N_FREE` free candidates beyond the contact (the caller sizes the
        candidate zone so that this cannot happen).
    """
    check_q2_layout(r)
    last = int(np.nonzero(active)[0].max())
    if last + N_FREE >= len(r):
        raise ConvergenceError("contact reaches the end of the candidate zone: no free nodes to fit the edge")
    a_lo, a_hi = float(r[last]), float(r[last + 1])
    s = a_hi - a_lo
    if last < MIN_LOADED:  # the contact spans less than a Q2 edge: no decay to fit
        return {"a_lo": a_lo, "a_hi": a_hi, "a": 0.5 * (a_lo + a_hi), "a_err": 0.5 * s, "n": math.nan,
                "residual": math.nan, "clipped": True}
    lam = np.where(active, np.asarray(lam, dtype=float), 0.0)
    a, n, res, se = _fit(r, lam, last)
    err = min(max(se, 0.05 * s), 0.5 * s)
    clipped = not (a_lo + (T_RANGE[0] + 1e-6) * s < a < a_lo + (T_RANGE[1] - 1e-6) * s)
    return {"a_lo": a_lo, "a_hi": a_hi, "a": a, "a_err": err, "n": n, "residual": res, "clipped": clipped}
