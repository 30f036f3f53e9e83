r"""Contact edge of an elastic-plastic indentation: node bracket and one radius estimator.

Bracket
    ``[a_lo, a_hi] = [r of the last node carrying load, r of the first free node]``: the discrete
    contact edge lies between them whatever the edge's shape.
Radius ``a`` (one estimator for elastic and plastic edges)
    Outside the edge the gap opens like ``g = c (r - a)^m``: ``m = 3/2`` at a Hertzian
    (square-root pressure) edge, ``m -> 1`` at the edge of a fully plastic contact, whose
    pressure stays finite up to the edge. The exponent is chosen from the data: for every ``m``
    in ``[0.5, 2]`` (steps of 0.05) ``g^{1/m}`` is fitted linearly in ``r`` on the 2nd to 6th free
    nodes (the first free node is skipped: its gap is dominated by the discretisation of the
    edge, cf. :mod:`coathertz.fem.post`); the ``m`` with the smallest relative residual wins
    and ``a`` is the fit's root. A root outside ``[a_lo - s, a_hi + s]`` (``s`` the node spacing
    there) is replaced by the nearest end of that interval (recorded in ``clipped``). The root
    is not snapped into the bracket: snapping makes ``a`` jump by node spacings from one
    increment to the next (measured: p_mean scatter 11 % at 12 elements across a_ref), while
    the free root follows Kogut & Etsion's a(delta) within about 2 % on the same mesh (it lies
    up to ~ 2 % inside the last loaded node, whose nodal force the Q2 edge spreads outwards).
    Uncertainty ``a_err``: half the spread of the roots over the exponents whose residual is at
    most twice the best, and at least a tenth of the node spacing.

No switching: the same estimator is used at every increment; ``p_mean = W / (pi a^2)`` and the
bracket's ``[W / (pi a_hi^2), W / (pi a_lo^2)]`` are both reported.
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.errors import ConvergenceError

#: Exponents ``m`` of the gap ``c (r - a)^m`` tried by :func:`edge_radius`.
EXPONENTS = np.round(np.arange(0.5, 2.0001, 0.05), 2)
#: Free nodes used by the fit (after the first free node, which is skipped).
N_FIT = 5


def edge_radius(r: np.ndarray, gap: np.ndarray, active: np.ndarray) -> dict:
    """Bracket, radius estimate, its uncertainty and the chosen gap exponent.

    Parameters
    ----------
    r
        Radii of the contact candidates [m], increasing.
    gap
        Gap of every candidate [m] (``> 0`` outside the contact).
    active
        Candidates in contact (a disc: all nodes up to the last one).

    Returns
    -------
    dict
        ``a_lo``, ``a_hi`` (bracket) [m], ``a`` [m], ``a_err`` [m], ``m`` (exponent),
        ``clipped`` (bool).

    Raises
    ------
    ConvergenceError
        Fewer than ``N_FIT + 1`` free candidates beyond the contact (the caller sizes the
        candidate zone so that this cannot happen).
    """
    ia = np.nonzero(active)[0]
    last = int(ia.max())
    gi = np.arange(last + 2, last + 2 + N_FIT)
    if gi[-1] >= len(r):
        raise ConvergenceError("contact reaches the end of the candidate zone: no free nodes to fit the edge")
    a_lo, a_hi = float(r[last]), float(r[last + 1])
    s = a_hi - a_lo
    x = r[gi]
    g = np.clip(gap[gi], 0.0, None)
    roots, res = [], []
    for m in EXPONENTS:
        y = g ** (1.0 / m)
        c1, c0 = np.polyfit(x, y, 1)
        fit = c1 * x + c0
        scale = max(float(np.abs(y).max()), 1e-300)
        res.append(float(np.sqrt(np.mean((y - fit) ** 2))) / scale)
        roots.append(-c0 / c1 if c1 > 0 else math.nan)
    res_a = np.array(res)
    roots_a = np.array(roots)
    ok = np.isfinite(roots_a)
    if not ok.any():
        a, m, err, clipped = 0.5 * (a_lo + a_hi), math.nan, 0.5 * s, True
    else:
        best = int(np.argmin(np.where(ok, res_a, np.inf)))
        a, m = float(roots_a[best]), float(EXPONENTS[best])
        near = ok & (res_a <= 2.0 * res_a[best] + 1e-15)
        err = max(0.5 * float(np.ptp(roots_a[near])), 0.1 * s)
        clipped = not (a_lo - s <= a <= a_hi + s)
        a = min(max(a, a_lo - s), a_hi + s)
    return {"a_lo": a_lo, "a_hi": a_hi, "a": a, "a_err": err, "m": m, "clipped": clipped}
