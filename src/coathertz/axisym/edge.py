r"""Edge enrichment of the Galerkin basis for thin layers (method ``axisym``).

For a layer much thinner than the contact (``H = h/a << 1``) the auxiliary function ``g(x)`` has
a boundary layer of width ~``H`` at the contact edge ``x = 1``: even Legendre polynomials resolve
it only with ``N ~ 3/sqrt(H)`` modes (measured: ``a`` within 1e-8 needs ``N^2 H ~ 4-12``, i.e.
~600 modes at ``H = 1e-5``). Here the basis ``phi_n = (-1)^n P_{2n}`` is enriched with edge
functions at geometric scales ``L_j`` from ``H/8`` up to the resolution of the Legendre basis,

.. math::  \psi_j(x) = e^{\beta_j (x - 1)},\qquad \beta_j = 1/L_j,\qquad
           \Psi_j(\xi) = \int_0^1 \psi_j \cos\xi x\,dx
           = \mathrm{Re}\,\frac{e^{i\xi} - e^{-\beta_j}}{\beta_j + i\xi},

whose cosine transforms are closed forms, so that every Galerkin entry is a one-dimensional
integral ``int_0^inf M(xi/a) Phi_p Phi_q dxi`` exactly as for the Legendre modes. Beyond the direct
rule (``xi > X0``) every basis function is ``Re(U_p(xi) e^{i xi})`` with a smooth envelope
(``U = (C_n - i S_n)/xi`` for ``j_{2n}``, DLMF 10.49.2; ``U = 1/(beta + i xi)`` for ``psi_j``), and
``Phi_p Phi_q = Re(U_p conj(U_q))/2 + Re(U_p U_q e^{2 i xi})/2``: the smooth part on geometric Gauss
panels, the oscillating part by parts at ``X0`` (as for the Legendre tail in
:mod:`coathertz.axisym.solver`). Gram entries ``<phi_m, psi_j>`` come from a composite Gauss rule
graded towards ``x = 1``; ``<psi_i, psi_j>`` and the right-hand sides are closed forms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.polynomial import legendre as npleg

#: Smallest decay rate used: ``exp(-beta)`` is dropped from ``Psi_j`` and the Gram entries on
#: ``[0, 1/2]`` need no more than the rule below (``exp(-beta/2) < 1e-14``).
BETA_MIN = 64.0


@dataclass(frozen=True)
class EdgeBasis:
    """Decay rates ``beta_j`` (in units of ``1/a``) of the edge functions ``exp(beta_j (x - 1))``."""

    beta: tuple[float, ...]

    @property
    def size(self) -> int:
        return len(self.beta)

    def array(self) -> np.ndarray:
        return np.asarray(self.beta, dtype=float)


def edge_basis(H: float, n_modes: int, ratio: float = 2.0, fine: float = 8.0,
               coarse: float = 1.0) -> EdgeBasis:
    """Scales ``L_j`` geometric (``ratio``) from ``H / fine`` to ``coarse / (2N - 2)^2`` (the
    finest scale of ``P_{2N-2}`` at ``x = 1``), ``beta_j = 1/L_j >= BETA_MIN``."""
    l_max = max(2 * n_modes - 2, 2)
    L_hi = min(coarse / (l_max * l_max), 1.0 / BETA_MIN)
    L_lo = H / fine
    if L_lo >= L_hi:
        return EdgeBasis(())
    n = math.floor(math.log(L_hi / L_lo) / math.log(ratio) + 1e-9) + 1
    L = L_lo * ratio ** np.arange(n)
    return EdgeBasis(tuple(float(b) for b in 1.0 / L))


@lru_cache(maxsize=16)
def graded_rule(n_modes: int, L_min: float) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss rule on ``[0, 1]`` in ``t = 1 - x`` (nodes ``t``, weights): panels halving
    towards ``x = 1`` (``t = 0``) down to ``L_min / 4``, ``max(48, 2N)`` nodes each (exact for
    ``P_{2N-2}`` times a smooth factor). Built in ``t`` so that ``exp(-beta t)`` keeps its relative
    accuracy for ``beta`` up to ~1e10 (``x - 1`` would lose it)."""
    K = max(1, math.ceil(math.log2(4.0 / L_min)))
    b = np.concatenate([[1.0], 2.0 ** -np.arange(1, K + 1, dtype=float), [0.0]])
    z, w = npleg.leggauss(max(48, 2 * n_modes))
    lo, hi = b[1:, None], b[:-1, None]
    t = (0.5 * (hi - lo) * z + 0.5 * (hi + lo)).ravel()
    wt = (0.5 * (hi - lo) * w).ravel()
    return t, wt


def legendre_signed(n_modes: int, x: np.ndarray) -> np.ndarray:
    """``phi_n(x) = (-1)^n P_{2n}(x)``, shape ``(n_modes, x.size)``."""
    V = npleg.legvander(x, 2 * n_modes - 2)[:, ::2].T
    return V * np.where(np.arange(n_modes) % 2, -1.0, 1.0)[:, None]


def gram_cross(n_modes: int, beta: np.ndarray) -> np.ndarray:
    """``<phi_m, psi_j> = int_0^1 (-1)^m P_{2m}(x) exp(beta_j (x - 1)) dx``, shape ``(N, J)``."""
    t, w = graded_rule(n_modes, float(1.0 / beta.max()))
    E = np.exp(-beta[None, :] * t[:, None])  # (nt, J)
    return legendre_signed(n_modes, 1.0 - t) @ (E * w[:, None])


@lru_cache(maxsize=32)
def edge_blocks(n_modes: int, beta: tuple[float, ...], gram_tol: float) -> tuple[np.ndarray, ...]:
    """The parts of the enriched system that do not depend on ``a`` (cached per basis):
    ``<phi_m, psi_j>``, ``<psi_i, psi_j>``, ``<psi_j, 1>``, ``<psi_j, x^2>``,
    ``int_0^1 psi_j dx`` and ``T``: an orthonormal basis (columns, coefficients in the enriched
    basis) of the numerically independent part of its span, the Gram eigenvectors with
    eigenvalues above ``gram_tol`` times the largest, scaled by ``lambda^-1/2``."""
    b = np.asarray(beta, dtype=float)
    gc, ge = gram_cross(n_modes, b), gram_edge(b)
    m = np.arange(n_modes)
    G = np.zeros((n_modes + b.size, n_modes + b.size))
    G[m, m] = 1.0 / (4.0 * m + 1.0)
    G[:n_modes, n_modes:] = gc
    G[n_modes:, :n_modes] = gc.T
    G[n_modes:, n_modes:] = ge
    lam, V = np.linalg.eigh(G)
    keep = lam > gram_tol * lam[-1]
    T = V[:, keep] / np.sqrt(lam[keep])
    out = (gc, ge, rhs_edge(b), edge_integral(b), T)
    for arr in out:
        arr.flags.writeable = False
    return out


def gram_edge(beta: np.ndarray) -> np.ndarray:
    """``<psi_i, psi_j> = (1 - exp(-(b_i + b_j))) / (b_i + b_j)``."""
    s = beta[:, None] + beta[None, :]
    return -np.expm1(-s) / s


def rhs_edge(beta: np.ndarray) -> np.ndarray:
    """``<psi_j, 1>`` and ``<psi_j, x^2>`` (columns), closed forms."""
    b = beta
    one = -np.expm1(-b) / b
    x2 = 1.0 / b - 2.0 / b**2 + 2.0 / b**3 - np.exp(-b) * 2.0 / b**3
    return np.stack([one, x2], axis=1)


def psi_hat(beta: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """``Psi_j(xi)`` (rows ``j``), with ``exp(-beta)`` dropped (``beta >= BETA_MIN``)."""
    b = beta[:, None]
    return (b * np.cos(xi) + xi * np.sin(xi)) / (b * b + xi * xi)


def edge_integral(beta: np.ndarray) -> np.ndarray:
    """``int_0^1 psi_j dx``."""
    return -np.expm1(-beta) / beta


def edge_Q(beta: np.ndarray, e: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """The edge functions' part of ``Q(rho) = -int_0^1 g'(x)/x ds`` of
    :func:`coathertz.axisym.solver.pressure` (``p = E_ref/(pi a) sqrt(1 - rho^2) Q``,
    ``x^2 = rho^2 + (1 - rho^2) s^2``): ``-sum_j e_j beta_j int_0^1 exp(beta_j (x - 1)) / x ds``.

    The integrand is concentrated where ``1 - x <~ 1/beta``, i.e.
    ``1 - s <~ 1/(beta (1 - rho^2))``: Gauss panels halving towards ``s = 1`` down to
    ``1/(4 beta_max)``, 8 nodes each (against 32 nodes and ``1/(64 beta_max)``: 3e-12 relative,
    tested).
    """
    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    out = np.zeros_like(rho)
    if beta.size == 0:
        return out
    u, ws = _edge_s_rule(float(beta.max()))  # u = 1 - s
    s = 1.0 - u
    ok = np.flatnonzero(rho < 1.0)
    r2 = rho[ok, None] ** 2
    x = np.sqrt(r2 + (1.0 - r2) * s[None, :] ** 2)  # (n_rho, n_s)
    # g_e'(x) = sum_j e_j beta_j exp(-beta_j t), t = 1 - x = (1 - rho^2) u (2 - u) / (1 + x)
    # (accurate for t << 1): each term only where beta_j t < 37 (exp(-37) < 1e-16), on the nodes
    # sorted by t
    t = ((1.0 - r2) * (u * (2.0 - u))[None, :] / (1.0 + x)).ravel()
    order = np.argsort(t, kind="stable")
    ts = t[order]
    acc = np.zeros_like(ts)
    for bj, ej in zip(beta, e, strict=True):
        n = int(np.searchsorted(ts, 37.0 / bj))
        acc[:n] += (ej * bj) * np.exp(-bj * ts[:n])
    wq = (ws[None, :] / x).ravel()[order]
    rows = np.repeat(np.arange(ok.size), s.size)[order]
    out[ok] = -np.bincount(rows, weights=acc * wq, minlength=ok.size)
    return out


@lru_cache(maxsize=16)
def _edge_s_rule(beta_max: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss rule in ``u = 1 - s`` on ``[0, 1]``: panels halving towards ``u = 0``."""
    z, w = npleg.leggauss(8)
    K = max(1, math.ceil(math.log2(4.0 * beta_max)))
    b = np.concatenate([[1.0], 2.0 ** -np.arange(1, K + 1, dtype=float), [0.0]])
    lo, hi = b[1:, None], b[:-1, None]
    return (0.5 * (hi - lo) * z + 0.5 * (hi + lo)).ravel(), (0.5 * (hi - lo) * w).ravel()
