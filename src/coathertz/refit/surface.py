"""Smooth surfaces ``f(x_1, ..., x_d) = sum_k c_k prod_v T_{i_kv}(s_v(x_v))`` (Chebyshev products).

Each variable ``x_v`` is clamped to its range ``[lo_v, hi_v]`` and mapped to ``s_v in [-1, 1]``;
outside the range the surface is therefore *held at its boundary value*, which is what makes the
refitted alpha give the right limits (:mod:`coathertz.refit.model`). A surface is continuous
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

CHUNK = 65536


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

    @property
    def degrees(self) -> tuple[int, ...]:
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
    def _groups(self) -> tuple[tuple[tuple[int, ...], np.ndarray], ...]:
        """Terms grouped by their degrees in the variables after the first two: each group is a
        small dense matrix over the first two variables (trimmed to its largest degrees)."""
        groups: dict[tuple[int, ...], dict[tuple[int, int], float]] = {}
        for t, c in zip(self.terms, self.coef, strict=True):
            head = (t[0], t[1] if len(t) > 1 else 0)
            g = groups.setdefault(tuple(t[2:]), {})
            g[head] = g.get(head, 0.0) + c
        out = []
        for tail, g in sorted(groups.items()):
            n0 = max(i for i, _ in g) + 1
            n1 = max(j for _, j in g) + 1
            C = np.zeros((n1, n0))
            for (i, j), c in g.items():
                C[j, i] = c
            out.append((tail, C))
        return tuple(out)

    @cached_property
    def _stacked(self) -> tuple[np.ndarray, tuple[tuple[tuple[int, ...], int, int], ...]]:
        """All group blocks stacked into one matrix (rows: the second variable's degrees of every
        group; columns: the first variable's degrees), and per group ``(tail, first row, rows)``."""
        n0 = max(C.shape[1] for _, C in self._groups)
        rows, index, r = [], [], 0
        for tail, C in self._groups:
            block = np.zeros((C.shape[0], n0))
            block[:, : C.shape[1]] = C
            rows.append(block)
            index.append((tail, r, C.shape[0]))
            r += C.shape[0]
        return np.vstack(rows), tuple(index)

    def __call__(self, X: np.ndarray) -> np.ndarray:
        """Values at the points ``X`` (shape ``(d, n)``), vectorised: one matrix product over the
        first variable for all terms, then the second variable and the tails elementwise."""
        X = np.asarray(X, dtype=float)
        d = len(self.variables)
        if X.ndim != 2 or X.shape[0] != d:
            raise CoatHertzError(f"Surface expects X of shape ({d}, n), got {X.shape}")
        n = X.shape[1]
        out = np.empty(n)
        degs = self.degrees
        big, index = self._stacked
        chunk = int(min(CHUNK, max(2048, 2**21 // big.shape[0])))
        for s in range(0, n, chunk):
            S = self.scaled(X[:, s : s + chunk])
            tabs = [chebyshev_table(S[v], degs[v]) for v in range(d)]
            if d == 1:
                tabs.append(np.ones((1, S.shape[1])))
            B = big[:, : tabs[0].shape[0]] @ tabs[0]
            acc = np.zeros(S.shape[1])
            for tail, r0, nr in index:
                val = np.einsum("jn,jn->n", B[r0 : r0 + nr], tabs[1][:nr]) if nr > 1 else B[r0].copy()
                for v, k in enumerate(tail, start=2):
                    if k:
                        val *= tabs[v][k]
                acc += val
            out[s : s + chunk] = acc
        return out

    def to_dict(self) -> dict:
        return {"variables": list(self.variables), "lo": list(self.lo), "hi": list(self.hi),
                "terms": [list(t) for t in self.terms], "coef": [float(c) for c in self.coef]}

    @classmethod
    def from_dict(cls, d: dict) -> Surface:
        return cls(tuple(d["variables"]), tuple(map(float, d["lo"])), tuple(map(float, d["hi"])),
                   tuple(tuple(int(i) for i in t) for t in d["terms"]), tuple(map(float, d["coef"])))


def evaluate_shared(surfaces: Sequence[Surface], X: np.ndarray) -> list[np.ndarray]:
    """Values of several surfaces with the same variables, ranges and terms at the points ``X``:
    the Chebyshev tables are built once and one matrix product serves all of them (the fast path
    of the corrected form, whose a, delta and p surfaces share their terms)."""
    first = surfaces[0]
    if any((s.variables, s.lo, s.hi, s.terms) != (first.variables, first.lo, first.hi, first.terms)
           for s in surfaces[1:]):
        return [s(X) for s in surfaces]
    X = np.asarray(X, dtype=float)
    d, n = X.shape
    degs = first.degrees
    stacks = [s._stacked for s in surfaces]
    big = np.vstack([b for b, _ in stacks])
    rows = stacks[0][0].shape[0]
    index = stacks[0][1]
    outs = [np.empty(n) for _ in surfaces]
    chunk = int(min(CHUNK, max(2048, 2**21 // big.shape[0])))
    for s0 in range(0, n, chunk):
        S = first.scaled(X[:, s0 : s0 + chunk])
        tabs = [chebyshev_table(S[v], degs[v]) for v in range(d)]
        if d == 1:
            tabs.append(np.ones((1, S.shape[1])))
        tails = {}
        for tail, _, _ in index:
            f = None
            for v, k in enumerate(tail, start=2):
                if k:
                    f = tabs[v][k] if f is None else f * tabs[v][k]
            tails[tail] = f
        B = big[:, : tabs[0].shape[0]] @ tabs[0]
        for m, out in enumerate(outs):
            acc = np.zeros(S.shape[1])
            for tail, r0, nr in index:
                r = m * rows + r0
                val = np.einsum("jn,jn->n", B[r : r + nr], tabs[1][:nr]) if nr > 1 else B[r].copy()
                if tails[tail] is not None:
                    val *= tails[tail]
                acc += val
            out[s0 : s0 + chunk] = acc
    return outs
