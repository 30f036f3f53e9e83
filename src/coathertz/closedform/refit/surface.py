"""Smooth surfaces ``f(x_1, ..., x_d) = sum_k c_k prod_v T_{i_kv}(s_v(x_v))`` (Chebyshev products).

Each variable ``x_v`` is clamped to its range ``[lo_v, hi_v]`` and mapped to ``s_v in [-1, 1]``;
outside the range the surface is therefore *held at its boundary value*, which is what makes the
refitted alpha give the right limits (:mod:`coathertz.closedform.refit.model`). A surface is continuous
and infinitely differentiable inside its box, continuous everywhere: no jumps.

Evaluation groups the terms by their degrees in the variables after the first two; one BLAS
product over the first variable serves every group, and the rest is elementwise (about one
multiply-add per term of the first two variables' tensor per group).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from coathertz.errors import CoatHertzError

CHUNK = 1024  # points per matrix product (W stays in cache)
TABLE_CHUNK = 32768  # points per set of Chebyshev tables


def chebyshev_table(s: np.ndarray, degree: int) -> np.ndarray:
    """``T_0(s) ... T_degree(s)`` stacked along axis 0."""
    out = np.empty((degree + 1, *s.shape))
    out[0] = 1.0
    if degree >= 1:
        out[1] = s
    for k in range(2, degree + 1):
        out[k] = 2.0 * s * out[k - 1] - out[k - 2]
    return out


def term_set(degrees: Sequence[int],
             cross: Sequence[Sequence[int]] | None = None) -> tuple[tuple[int, ...], ...]:
    """Multi-indices of a surface.

    ``degrees[0..1]`` bound a full tensor product in the first two variables (the main
    surface); every further variable ``v`` enters with degree ``1..degrees[v]`` multiplied by
    the first two variables up to the degrees ``cross[v - 2]`` (lower order corrections), and
    products of two further variables with total degree <= max(degrees[2:]) enter with the
    constant of the first two variables.
    """
    d = len(degrees)
    terms = set()
    main = (degrees[0], degrees[1] if d > 1 else 0)
    for i in range(main[0] + 1):
        for j in range(main[1] + 1 if d > 1 else 1):
            terms.add((i, j, *([0] * (d - 2)))[:d])
    for v in range(2, d):
        ci, cj = cross[v - 2] if cross else (2, 2)
        for k in range(1, degrees[v] + 1):
            for i in range(ci + 1):
                for j in range(cj + 1):
                    idx = [0] * d
                    idx[0], idx[1], idx[v] = i, j, k
                    terms.add(tuple(idx))
    if d > 3:
        top = max(degrees[2:])
        for v in range(2, d):
            for w in range(v + 1, d):
                for k in range(1, degrees[v] + 1):
                    for m in range(1, degrees[w] + 1):
                        if k + m <= top:
                            idx = [0] * d
                            idx[v], idx[w] = k, m
                            terms.add(tuple(idx))
    return tuple(sorted(terms, key=lambda t: (sum(t), t)))


@dataclass(frozen=True)
class Surface:
    """A clamped Chebyshev-product surface (see the module docstring).

    Parameters
    ----------
    variables
        Names of the variables, in the order of the rows of ``X`` (e.g. ``("log10_H", "log10_E",
        "nu_c", "nu_s")``).
    lo, hi
        Range of each variable; values outside are clamped.
    terms
        Multi-indices ``(i_1, ..., i_d)`` of the Chebyshev degrees of each term.
    coef
        Coefficient of each term.
    """

    variables: tuple[str, ...]
    lo: tuple[float, ...]
    hi: tuple[float, ...]
    terms: tuple[tuple[int, ...], ...]
    coef: tuple[float, ...]

    def __post_init__(self) -> None:
        d = len(self.variables)
        if not (len(self.lo) == len(self.hi) == d):
            raise CoatHertzError("Surface: lo, hi and variables must have the same length")
        if any(not (h > lo) for lo, h in zip(self.lo, self.hi, strict=True)):
            raise CoatHertzError("Surface: every range must satisfy lo < hi")
        if len(self.terms) != len(self.coef):
            raise CoatHertzError("Surface: one coefficient per term")
        if any(len(t) != d or min(t) < 0 for t in self.terms):
            raise CoatHertzError(f"Surface: every term needs {d} non-negative degrees")

    @cached_property
    def degrees(self) -> tuple[int, ...]:
        """The highest degree of each variable over the terms (computed once: every evaluation
        asks)."""
        return tuple(int(max(t[v] for t in self.terms)) for v in range(len(self.variables)))

    def scaled(self, X: np.ndarray) -> np.ndarray:
        """Clamp each row of ``X`` (shape ``(d, n)``) to its range and map it to [-1, 1]."""
        X = np.asarray(X, dtype=float)
        lo = np.asarray(self.lo)[:, None]
        hi = np.asarray(self.hi)[:, None]
        return (2.0 * np.clip(X, lo, hi) - (lo + hi)) / (hi - lo)

    def design(self, X: np.ndarray) -> np.ndarray:
        """Design matrix ``Phi[n, k]`` of the terms at the points ``X`` (``(d, n)``)."""
        S = self.scaled(X)
        tabs = [chebyshev_table(S[v], dg) for v, dg in enumerate(self.degrees)]
        Phi = np.ones((S.shape[1], len(self.terms)))
        for k, t in enumerate(self.terms):
            for v, i in enumerate(t):
                if i:
                    Phi[:, k] *= tabs[v][i]
        return Phi

    @cached_property
    def _layout(self) -> tuple[tuple[tuple[int, ...], ...], np.ndarray]:
        """The terms as a matrix: ``rest`` lists the distinct multi-indices of the variables after
        the first, and ``C[i, r]`` is the coefficient of the term ``(i, *rest[r])``."""
        rest = tuple(sorted({tuple(t[1:]) for t in self.terms}))
        where = {r: k for k, r in enumerate(rest)}
        C = np.zeros((self.degrees[0] + 1, len(rest)))
        for t, c in zip(self.terms, self.coef, strict=True):
            C[t[0], where[tuple(t[1:])]] += c
        return rest, C

    def __call__(self, X: np.ndarray) -> np.ndarray:
        """Values at the points ``X`` (shape ``(d, n)``), vectorised (:func:`evaluate_shared`)."""
        X = np.asarray(X, dtype=float)
        d = len(self.variables)
        if X.ndim != 2 or X.shape[0] != d:
            raise CoatHertzError(f"Surface expects X of shape ({d}, n), got {X.shape}")
        return evaluate_shared([self], X)[0]

    def to_dict(self) -> dict:
        return {"variables": list(self.variables), "lo": list(self.lo), "hi": list(self.hi),
                "terms": [list(t) for t in self.terms], "coef": [float(c) for c in self.coef]}

    @classmethod
    def from_dict(cls, d: dict) -> Surface:
        return cls(tuple(d["variables"]), tuple(map(float, d["lo"])), tuple(map(float, d["hi"])),
                   tuple(tuple(int(i) for i in t) for t in d["terms"]), tuple(map(float, d["coef"])))


def evaluate_shared(surfaces: Sequence[Surface], X: np.ndarray) -> list[np.ndarray]:
    """Values of several surfaces with the same variables and ranges at the points ``X``.

    Per chunk of points: the products of the Chebyshev tables of the variables after the first
    (one row per distinct multi-index ``rest`` of any surface) form ``W``; one matrix product
    ``[C_1; C_2; ...] @ W`` (rows: each surface's degrees in the first variable) contracts every
    term but the first variable's, which a final weighted sum over the few rows of its table
    finishes. The product's inner dimension is the number of ``rest`` indices (hundreds for the
    tensor surfaces of the corrected form) and its output only ``(surfaces x degree) x chunk``,
    so it runs at matrix-product speed from cache; chunks of ``CHUNK`` points keep ``W`` in cache.
    """
    first = surfaces[0]
    X = np.asarray(X, dtype=float)
    if any((s.variables, s.lo, s.hi) != (first.variables, first.lo, first.hi) for s in surfaces[1:]):
        return [s(X) for s in surfaces]
    d, n = X.shape
    rest = tuple(sorted({r for s in surfaces for r in s._layout[0]}))
    where = {r: k for k, r in enumerate(rest)}
    n0 = max(s.degrees[0] for s in surfaces) + 1
    big = np.zeros((len(surfaces) * n0, len(rest)))
    for m, s in enumerate(surfaces):
        rs, C = s._layout
        big[m * n0 : m * n0 + C.shape[0], [where[r] for r in rs]] = C
    degs = tuple(max(s.degrees[v] for s in surfaces) for v in range(d))
    pick = None  # rows of the full tensor that are rest indices (None: all of them, in order)
    if d > 1:
        flat = np.ravel_multi_index(np.array(rest).T, tuple(k + 1 for k in degs[1:]))
        if not np.array_equal(flat, np.arange(np.prod([k + 1 for k in degs[1:]]))):
            pick = flat
    outs = [np.empty(n) for _ in surfaces]

    def block(t0: int) -> None:  # tables for many points at once (few Python steps) ...
        S_all = first.scaled(X[:, t0 : t0 + TABLE_CHUNK])
        tabs_all = [chebyshev_table(S_all[v], degs[v]) for v in range(d)]
        for c0 in range(0, S_all.shape[1], CHUNK):  # ... the product in cache-sized pieces
            _product(big, [t[:, c0 : c0 + CHUNK] for t in tabs_all], pick, n0, outs, t0 + c0)

    for t0 in range(0, n, TABLE_CHUNK):
        block(t0)
    return outs


def _product(big: np.ndarray, tabs: list[np.ndarray], pick: np.ndarray | None, n0: int,
             outs: list[np.ndarray], s0: int) -> None:
    """One cache-sized chunk of :func:`evaluate_shared`: ``tabs`` are the Chebyshev tables of
    its points, the values go to ``outs[m][s0 : s0 + chunk]``."""
    T0, n = tabs[0], tabs[0].shape[1]
    W = tabs[1] if len(tabs) > 1 else np.ones((1, n))
    for T in tabs[2:]:  # the full tensor of the tables of the variables after the first
        W = (W[:, None, :] * T[None, :, :]).reshape(-1, n)
    if pick is not None:
        W = W[pick]
    B = (big @ W).reshape(len(outs), n0, n)
    for m, out in enumerate(outs):
        out[s0 : s0 + n] = np.einsum("in,in->n", B[m], T0)
