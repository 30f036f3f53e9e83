"""The fitting half of the second closed form (:mod:`coathertz.closedform.refit.corrected`):
least-squares fits of its correction surfaces on the training tables (``coathertz fit-alpha``).
"""

from __future__ import annotations

import numpy as np

from coathertz.closedform.refit import model as M
from coathertz.closedform.refit.corrected import correction_weight
from coathertz.closedform.refit.surface import Surface, chebyshev_table, term_set
from coathertz.errors import CoatHertzError
from coathertz.fitalpha.fit import FitSettings, error_stats


def _design(cols, settings: FitSettings, config: str) -> tuple[Surface, np.ndarray]:
    """The zero surface over the box of ``config`` and the design matrix ``v(H) * basis`` of the
    columns ``cols``."""
    terms = term_set(settings.degrees, settings.cross or None)
    lo = tuple(b[0] for b in M.BOXES[config])
    hi = tuple(b[1] for b in M.BOXES[config])
    proto = Surface(M.VARIABLES[config], lo, hi, terms, tuple(0.0 for _ in terms))
    X = M.variables(config, cols.get("E"), cols["H"], cols["nu_c"], cols.get("nu_s", 0.3))
    H = np.asarray(cols["H"], dtype=float)
    return proto, correction_weight(config, H)[:, None] * proto.design(X)


def fit_corrected(q: str, cols, base_log_bar: np.ndarray, settings: FitSettings,
                  config: str = "elastic") -> tuple[Surface, dict]:
    """Fit ``C_q`` by linear least squares (a ridge of ``settings.ridge``; ``settings.reweight``
    Lawson passes towards the minimax fit) to ``ln bar_exact - base_log_bar`` on the rows ``cols``
    (columns ``E, H, nu_c, nu_s, {q}_bar``). Returns the surface and its training error [%]."""
    proto, A = _design(cols, settings, config)
    terms = proto.terms
    y = np.log(np.asarray(cols[f"{q}_bar"], dtype=float)) - base_log_bar
    wt = np.ones(len(y))
    reg = np.sqrt(settings.ridge) * np.eye(len(terms))
    for _ in range(settings.reweight + 1):
        sw = np.sqrt(wt / wt.mean())
        c = np.linalg.lstsq(np.vstack([A * sw[:, None], reg]), np.concatenate([y * sw, np.zeros(len(terms))]),
                            rcond=None)[0]
        r = np.abs(A @ c - y)
        wt = wt * (r / max(r.max(), 1e-300)) + 1e-3
    surface = Surface(proto.variables, proto.lo, proto.hi, terms, tuple(float(x) for x in c))
    return surface, error_stats(100.0 * np.expm1(A @ c - y))


def grid_index(X: np.ndarray, decimals: int = 9) -> tuple[list[np.ndarray], np.ndarray] | None:
    """If the points ``X`` (``(d, n)``) are a complete tensor grid, its node values per variable
    and the ``(n_1, ..., n_d)`` array of row indices; else None."""
    R = np.round(np.asarray(X, dtype=float), decimals)
    nodes, pos = [], []
    for row in R:
        u, inv = np.unique(row, return_inverse=True)
        nodes.append(u)
        pos.append(inv)
    shape = tuple(len(u) for u in nodes)
    if int(np.prod(shape)) != R.shape[1]:
        return None
    idx = np.full(shape, -1)
    idx[tuple(pos)] = np.arange(R.shape[1])
    if np.any(idx < 0):
        return None
    return nodes, idx


def fit_tensor(proto: Surface, X: np.ndarray, y: np.ndarray, row_weight: np.ndarray) -> np.ndarray | None:
    """Least squares of ``row_weight * sum_k c_k prod_v T(s_v)`` = ``y`` for a full tensor term set on
    a complete tensor grid, one variable at a time: the design matrix is a Kronecker product (the
    row weight depends on the first variable only), so its pseudo-inverse is the product of the
    per-variable pseudo-inverses. Returns the coefficients in ``proto.terms`` order, or None when
    ``X`` is not a complete grid, the weight varies along other variables, or the terms are not a
    full tensor."""
    g = grid_index(X)
    if g is None:
        return None
    _nodes, idx = g
    degs = proto.degrees
    full = {tuple(t) for t in proto.terms}
    if len(full) != int(np.prod([k + 1 for k in degs])):
        return None
    wv = np.asarray(row_weight, dtype=float)[idx]
    w1 = wv.reshape(wv.shape[0], -1)[:, 0]
    if not np.allclose(wv, w1.reshape((-1,) + (1,) * (wv.ndim - 1)), rtol=1e-12, atol=0):
        return None
    Y = np.asarray(y, dtype=float)[idx]
    S = proto.scaled(X)
    C = Y
    for v in range(len(degs)):
        line = S[v][np.moveaxis(idx, v, 0).reshape(idx.shape[v], -1)[:, 0]]
        T = chebyshev_table(line, degs[v]).T  # (n_v, deg_v + 1)
        if v == 0:
            T = w1[:, None] * T
        P = np.linalg.pinv(T, rcond=1e-13)
        C = np.moveaxis(np.tensordot(P, np.moveaxis(C, v, 0), axes=(1, 0)), 0, v)
    return np.array([C[tuple(t)] for t in proto.terms])


def tensor_surface(variables, box, degrees, X, y, row_weight) -> Surface:
    """A full tensor Chebyshev surface fitted to ``y`` on the complete grid ``X`` (:func:`fit_tensor`)."""
    terms = term_set(degrees, (tuple(degrees[:2]),) if len(degrees) > 2 else None)
    lo, hi = tuple(b[0] for b in box), tuple(b[1] for b in box)
    proto = Surface(tuple(variables), lo, hi, terms, tuple(0.0 for _ in terms))
    c = fit_tensor(proto, X, y, row_weight)
    if c is None:
        raise CoatHertzError("tensor fit: the rows are not a complete tensor grid")
    return Surface(proto.variables, lo, hi, terms, tuple(float(x) for x in c))
