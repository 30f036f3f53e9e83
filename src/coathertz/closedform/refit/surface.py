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

import contextlib
import threading
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from coathertz.blas import blas_threads
from coathertz.errors import CoatHertzError

CHUNK = 256  # fewest points per matrix product
CHUNK_MAX = 4096  # most points per matrix product
W_DOUBLES = 49152  # W of one chunk at most about this many values (384 kB: in one core's L2)
TABLE_CHUNK = 16384  # points per set of Chebyshev tables (their buffers are kept per thread)


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
    so it runs at matrix-product speed from cache; chunks of ``CHUNK`` to ``CHUNK_MAX`` points
    keep ``W`` within ``W_DOUBLES`` values (one core's L2 cache).
    The matrix of coefficients and the index maps are built once per set of surfaces
    (``_Plan``); tables, ``W`` and the product are written into buffers reused chunk by
    chunk (no temporaries: the evaluation rate is that of the matrix product plus a few
    element-wise passes, ``tests/benchmarks/bench_refit.py``).
    """
    first = surfaces[0]
    X = np.asarray(X, dtype=float)
    if any((s.variables, s.lo, s.hi) != (first.variables, first.lo, first.hi) for s in surfaces[1:]):
        return [s(X) for s in surfaces]
    return _plan(tuple(surfaces)).evaluate(X)


_PLANS: dict[tuple[int, ...], tuple[tuple[Surface, ...], _Plan]] = {}


def _plan(surfaces: tuple[Surface, ...]) -> _Plan:
    """The cached ``_Plan`` of ``surfaces`` (keyed by identity; the surfaces are kept alive
    with it, so an identity is never reused while cached)."""
    key = tuple(id(s) for s in surfaces)
    hit = _PLANS.get(key)
    if hit is None or any(a is not b for a, b in zip(hit[0], surfaces, strict=True)):
        if len(_PLANS) > 64:
            _PLANS.clear()
        hit = (surfaces, _Plan(surfaces))
        _PLANS[key] = hit
    return hit[1]


class _Plan:
    """The evaluation of several surfaces over the same variables (:func:`evaluate_shared`):
    ``big[m n0 + i, r]`` is surface m's coefficient of the term ``(i, *rest[r])``; ``pick`` the rows
    of the full tensor of the tables after the first that are ``rest`` indices (None: all of them,
    in order)."""

    def __init__(self, surfaces: tuple[Surface, ...]) -> None:
        first = surfaces[0]
        d = len(first.variables)
        rest = tuple(sorted({r for s in surfaces for r in s._layout[0]}))
        where = {r: k for k, r in enumerate(rest)}
        n0 = max(s.degrees[0] for s in surfaces) + 1
        # rows padded with zeros to a multiple of 4 (the matrix product's register block: 63 -> 64
        # rows take 8 % less time on this machine's OpenBLAS, measured)
        big = np.zeros((-(-len(surfaces) * n0 // 4) * 4, len(rest)))
        for m, s in enumerate(surfaces):
            rs, C = s._layout
            big[m * n0 : m * n0 + C.shape[0], [where[r] for r in rs]] = C
        self.degs = tuple(max(s.degrees[v] for s in surfaces) for v in range(d))
        self.pick = None
        if d > 1:
            flat = np.ravel_multi_index(np.array(rest).T, tuple(k + 1 for k in self.degs[1:]))
            if not np.array_equal(flat, np.arange(np.prod([k + 1 for k in self.degs[1:]]))):
                self.pick = flat
        self.big, self.n0, self.count, self.d = big, n0, len(surfaces), d
        self.lo = np.asarray(first.lo)[:, None]
        self.hi = np.asarray(first.hi)[:, None]
        self._local = threading.local()  # work buffers (:meth:`_buffer`), one set per thread

    def _buffer(self, name: str, size: int) -> np.ndarray:
        """A flat work buffer of at least ``size`` doubles, kept per thread and reused from call to
        call: fresh large arrays cost a page fault per 4 kB on first touch (measured: the
        Chebyshev tables at 5 ns per value in fresh arrays against 0.7 in reused ones)."""
        bufs = self._local.__dict__
        buf = bufs.get(name)
        if buf is None or buf.size < size:
            buf = bufs[name] = np.empty(size)
        return buf[:size]

    def evaluate(self, X: np.ndarray) -> list[np.ndarray]:
        n = X.shape[1]
        out = np.empty((self.count, n))
        chunk = min(max(CHUNK, min(CHUNK_MAX, W_DOUBLES // self.big.shape[1])), n)
        block = min(TABLE_CHUNK, n)
        rows = np.cumprod([k + 1 for k in self.degs[1:]])
        stages = [self._buffer(f"stage{k}", int(r) * chunk) for k, r in enumerate(rows[1:])]
        bbuf = self._buffer("product", self.big.shape[0] * chunk)
        tbuf = self._buffer("tables", sum(k + 1 for k in self.degs) * block)
        # single-threaded BLAS over many chunks: a threaded product of this size only waits for
        # its second thread (measured, the one-alpha elastic bars on a busy 2-core machine: 18.6
        # against 1.0 us of CPU per case); the callers' threads use the cores (rule.in_blocks)
        with blas_threads(1) if n > 4 * chunk else contextlib.nullcontext():
            self._chunks(X, out, chunk, stages, bbuf, tbuf)
        return list(out)

    def _chunks(self, X: np.ndarray, out: np.ndarray, chunk: int, stages: list[np.ndarray],
                bbuf: np.ndarray, tbuf: np.ndarray) -> None:
        d, n = X.shape
        for t0 in range(0, n, TABLE_CHUNK):
            Xb = X[:, t0 : t0 + TABLE_CHUNK]
            m = Xb.shape[1]
            S = (2.0 * np.clip(Xb, self.lo, self.hi) - (self.lo + self.hi)) / (self.hi - self.lo)
            tabs, at = [], 0
            for v in range(d):
                k = self.degs[v] + 1
                tabs.append(_table(S[v], self.degs[v], tbuf[at : at + k * m].reshape(k, m)))
                at += k * m
            for c0 in range(0, m, chunk):
                c1 = min(c0 + chunk, m)
                self._product([t[:, c0:c1] for t in tabs], out[:, t0 + c0 : t0 + c1], stages, bbuf)

    def _product(self, tabs: list[np.ndarray], out: np.ndarray, stages: list[np.ndarray],
                 bbuf: np.ndarray) -> None:
        """One cache-sized chunk: ``tabs`` are the Chebyshev tables of its points; the values go
        to ``out`` (surfaces x points); ``stages`` and ``bbuf`` are the buffers of the partial
        tensors and of the matrix product."""
        T0, n = tabs[0], tabs[0].shape[1]
        if len(tabs) == 1:
            W = np.ones((1, n))
        else:
            W = tabs[1]
            for T, buf in zip(tabs[2:], stages, strict=True):  # the full tensor of the tables after the first
                nxt = buf[: W.shape[0] * T.shape[0] * n].reshape(W.shape[0] * T.shape[0], n)
                np.multiply(W[:, None, :], T[None, :, :], out=nxt.reshape(W.shape[0], T.shape[0], n))
                W = nxt
            if self.pick is not None:
                W = W[self.pick]
        B = np.matmul(self.big, W, out=bbuf[: self.big.shape[0] * n].reshape(self.big.shape[0], n))
        np.einsum("min,in->mn", B[: self.count * self.n0].reshape(self.count, self.n0, n), T0, out=out)


def _table(s: np.ndarray, degree: int, out: np.ndarray) -> np.ndarray:
    """:func:`chebyshev_table` into ``out`` without temporaries (the same operations, so the same
    values)."""
    out[0] = 1.0
    if degree >= 1:
        out[1] = s
    if degree >= 2:
        s2 = 2.0 * s
        for k in range(2, degree + 1):
            np.multiply(s2, out[k - 1], out=out[k])
            out[k] -= out[k - 2]
    return out
