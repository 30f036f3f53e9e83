"""Galerkin--Legendre solution of the axisymmetric layered contact (see the package docstring).

For a contact radius ``a`` (``x = t/a``, ``xi = k a``) the auxiliary function
``g(x) = sum_n c_n P_{2n}(x)`` solves

.. math::  g(x) + \\frac{2}{\\pi} \\int_0^1 \\tilde K(x, y) g(y)\\,dy = \\delta - \\frac{a^2}{R} x^2,
           \\qquad \\tilde K(x,y) = \\int_0^\\infty M(\\xi/a) \\cos \\xi x \\cos \\xi y\\, d\\xi,

and with ``int_0^1 P_{2m}(x) cos(xi x) dx = (-1)^m j_{2m}(xi)`` the Galerkin equations for
``d_n = (-1)^n c_n`` read

.. math::  \\frac{d_m}{4m+1} + \\frac{2}{\\pi} \\sum_n A_{mn} d_n = (-1)^m \\int_0^1 P_{2m} f\\,dx,
           \\qquad A_{mn} = \\int_0^\\infty M(\\xi / a)\\, j_{2m}(\\xi) j_{2n}(\\xi)\\, d\\xi .
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.polynomial import chebyshev as npcheb
from numpy.polynomial import legendre as npleg
from scipy.linalg import lu_factor, lu_solve

from coathertz.axisym.bessel import spherical_jn_all
from coathertz.axisym.kernel import PairCompliance
from coathertz.errors import ConvergenceError

#: What a user can change when the solver fails (the method's own settings, not another method's).
MODES_HINT = ("change the Legendre modes (--modes N on the command line, n_modes=N in Python, "
              "2 to 400) or the edge functions (edge=, edge_modes=, edge_ratio= in Python)")

# --- xi quadrature ------------------------------------------------------------------------------


@dataclass(frozen=True)
class XiRule:
    """Composite Gauss--Legendre rule on ``[0, X]`` in ``xi = k a``.

    Panels are geometric (ratio 2) from ``xi_min`` to ``xi_split`` (resolving ``M(xi/a)`` for thick
    layers, where it varies on the scale ``a/h``), then of width ``panel`` up to ``X``.
    """

    order: int = 16
    panel: float = 3.0
    xi_min: float = 2.0**-14
    xi_split: float = 4.0

    def breakpoints(self, X: float) -> np.ndarray:
        geo = self.xi_min * 2.0 ** np.arange(0, round(math.log2(self.xi_split / self.xi_min)) + 1)
        n_uni = max(1, math.ceil((X - self.xi_split) / self.panel))
        uni = self.xi_split + self.panel * np.arange(1, n_uni + 1)
        return np.concatenate([[0.0], geo, uni])

    def nodes(self, X: float) -> tuple[np.ndarray, np.ndarray]:
        b = self.breakpoints(X)
        z, w = npleg.leggauss(self.order)
        lo, hi = b[:-1, None], b[1:, None]
        x = 0.5 * (hi - lo) * z[None, :] + 0.5 * (hi + lo)
        ww = 0.5 * (hi - lo) * w[None, :]
        return x.ravel(), ww.ravel()


@dataclass
class _Table:
    xi: np.ndarray
    w: np.ndarray
    J: np.ndarray  # (n_modes, n_xi): j_{2n}(xi)


_TABLES: dict[tuple, _Table] = {}


def bessel_table(n_modes: int, X: float, rule: XiRule) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nodes, weights and ``j_{2n}`` on them for ``xi <= X`` (tables grow and are cached)."""
    key = (n_modes, rule)
    tab = _TABLES.get(key)
    if tab is None or tab.xi[-1] < X:
        X_new = X if tab is None else max(X, 2.0 * tab.xi[-1])
        xi, w = rule.nodes(X_new)
        J = np.empty((n_modes, xi.size))
        for i in range(0, xi.size, 2048):  # in chunks: the odd orders are never stored whole
            J[:, i:i + 2048] = spherical_jn_all(2 * n_modes - 2, xi[i:i + 2048])[::2]
        tab = _Table(xi, w, J)
        _TABLES[key] = tab
        if len(_TABLES) > 8:
            _TABLES.pop(next(iter(_TABLES)))
    n = int(np.searchsorted(tab.xi, X, side="right"))
    # whole panels only
    n = min(tab.xi.size, math.ceil(n / rule.order) * rule.order)
    return tab.xi[:n], tab.w[:n], tab.J[:, :n]


# --- thin layers: the xi integral beyond X0 in closed form ------------------------------------------
#
# For xi >= X0 the spherical Bessel functions are evaluated from their exact finite expansions
# (DLMF 10.49.2) ``j_l(x) = [sin(x - l pi/2) P_l(x) + cos(x - l pi/2) Q_l(x)] / x`` with
# ``P_l = sum_{k even} (-1)^{k/2} a_k(l) x^-k``, ``Q_l = sum_{k odd} (-1)^{(k-1)/2} a_k(l) x^-k``,
# ``a_k(l) = (l+k)! / (2^k k! (l-k)!)``. For ``l = 2m``:
# ``j_{2m} = (-1)^m (S_m sin x + C_m cos x) / x`` and
#
# .. math::  j_{2m} j_{2n} = \frac{(-1)^{m+n}}{2x^2}\Bigl[S_mS_n + C_mC_n
#            + \mathrm{Re}\bigl((C_m - iS_m)(C_n - iS_n) e^{2ix}\bigr)\Bigr].
#
# The non-oscillating part is integrated on geometric Gauss panels (``M(xi/a)/xi^2`` varies on the
# scale ``xi``); the oscillating part ``int_X0^inf G(x) e^{2ix} dx`` by integration by parts,
# ``-e^{2iX0} sum_j (-1)^j G^(j)(X0) / (2i)^(j+1)`` (four terms; each is ~ 1/X0 of the previous
# one, ``G`` being smooth on the scale ``X0``), the derivatives by a 5-point stencil of step
# ``X0/20``. The cost is then independent of ``h``: the direct rule covers ``[0, X0]`` only.

#: Terms of the finite expansion kept: a_k(l)/X0^k < 8^k/k! < 1e-22 beyond.
_N_ASYM = 56


def tail_start(n_modes: int, panel: float) -> float:
    """``X0``: where the direct xi rule stops and the closed-form tail starts (``>= l^2 / 16`` with
    ``l = 2N - 2``, so that the finite expansion has terms ``<= 8^k/k! <= 420``: at most ~3 digits
    lost to cancellation; ``l^2/16`` agrees with ``l^2/8`` to 2e-14 at N = 160, ``l^2/32`` does
    not); at least 512)."""
    l_max = 2 * n_modes - 2
    X0 = max(l_max * l_max / 16.0, 512.0)
    return panel * math.ceil(X0 / panel)


def direct_end(n_modes: int, rule: XiRule) -> float:
    """End of the direct xi rule: the first panel breakpoint at or beyond :func:`tail_start`."""
    X0 = tail_start(n_modes, rule.panel)
    return rule.xi_split + rule.panel * math.ceil((X0 - rule.xi_split) / rule.panel)


def _asym_SC(n_modes: int, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Signed ``(-1)^m S_m(x)`` and ``(-1)^m C_m(x)`` (shape ``(n_modes, x.size)``), real or
    complex ``x`` with ``|x| >= l^2/16``."""
    x = np.asarray(x)
    u = 1.0 / x
    lv = 2.0 * np.arange(n_modes)[:, None]
    a = np.ones((n_modes, 1))
    S = np.ones((n_modes, x.size), dtype=x.dtype)
    C = np.zeros_like(S)
    uk = np.ones_like(x)
    for k in range(min(2 * n_modes - 2, _N_ASYM)):
        a = a * (lv + k + 1) * (lv - k) / (2.0 * (k + 1))  # a_{k+1}(l); 0 from k + 1 > l on
        uk = uk * u
        kk = k + 1
        if kk % 2 == 0:
            S = S + (-1.0) ** (kk // 2) * a * uk
        else:
            C = C + (-1.0) ** ((kk - 1) // 2) * a * uk
    sg = np.where(np.arange(n_modes) % 2, -1.0, 1.0)[:, None]
    return sg * S, sg * C


_TAIL: dict[tuple[int, float], tuple] = {}


def _tail_table(n_modes: int, X0: float, X1: float) -> tuple[np.ndarray, ...]:
    """Nodes, weights, ``S``, ``C`` on geometric Gauss panels (ratio 1.5, 16 nodes) from ``X0``
    to at least ``X1``, and ``Z = C - iS`` on the 5-point stencil at ``X0``; cached per
    ``(N, X0)`` and extended when a thinner layer needs more panels (the nodes do not depend on
    ``a`` or ``h``)."""
    key = (n_modes, float(X0))
    tab = _TAIL.get(key)
    n_pan = max(1, math.ceil(math.log(max(X1, 2.0 * X0) / X0) / math.log(1.5)))
    if tab is None or tab[0] < n_pan:
        n_pan = max(n_pan, 0 if tab is None else 2 * tab[0])
        b = X0 * 1.5 ** np.arange(n_pan + 1)
        z, w = npleg.leggauss(16)
        lo, hi = b[:-1, None], b[1:, None]
        x = (0.5 * (hi - lo) * z + 0.5 * (hi + lo)).ravel()
        wx = (0.5 * (hi - lo) * w).ravel()
        S, C = _asym_SC(n_modes, x)
        xs = X0 + (X0 / 20.0) * np.arange(-2, 3)
        S5, C5 = _asym_SC(n_modes, xs)
        tab = (n_pan, x, wx, S, C, xs, C5 - 1j * S5)
        _TAIL[key] = tab
        if len(_TAIL) > 8:
            _TAIL.pop(next(iter(_TAIL)))
    n = 16 * max(1, math.ceil(math.log(max(X1, 2.0 * X0) / X0) / math.log(1.5)))
    _, x, wx, S, C, xs, Z = tab
    return x[:n], wx[:n], S[:, :n], C[:, :n], xs, Z


def tail_matrix(pc: PairCompliance, a: float, n_modes: int, X0: float, X1: float) -> np.ndarray:
    """``int_X0^inf M(xi/a) j_{2m} j_{2n} dxi`` in closed form (the smooth part on panels up to at
    least ``X1``, where ``M`` has decayed; the oscillating part by parts)."""
    # non-oscillating part
    x, w, S, C, xs, Z = _tail_table(n_modes, X0, X1)
    wm = 0.5 * w * pc.M(x / a) / (x * x)
    A = (S * wm) @ S.T + (C * wm) @ C.T
    # oscillating part: integration by parts at X0
    return A + _by_parts(0.5 * pc.M(xs / a) / (xs * xs), Z, xs[1] - xs[0], X0)


def _by_parts(g: np.ndarray, Z: np.ndarray, s: float, X0: float) -> np.ndarray:
    """Real part of ``int_X0^inf G(x) e^{2ix} dx`` by parts, ``G(x) = g(x) Z(x) Z(x)^T``, from its
    values at the five points ``X0 + (j - 2) s`` (columns of ``Z``, entries of ``g``): ``G`` and
    its first three derivatives at ``X0`` by fourth-order differences.

    Every term is a combination of the five ``G_j = g_j Z_j Z_j^T``, so the sum is
    ``Z diag(gamma) Z^T`` with ``gamma_j = g_j sum_k alpha_k D_kj`` (``D``: the difference
    stencils, ``alpha_k = -e^{2iX0} (-1)^k / (2i)^(k+1)``): one product instead of five outer
    products."""
    D = np.array([[0.0, 0.0, 1.0, 0.0, 0.0],
                  [1.0, -8.0, 0.0, 8.0, -1.0],
                  [-1.0, 16.0, -30.0, 16.0, -1.0],
                  [-1.0, 2.0, 0.0, -2.0, 1.0]]) / np.array([[1.0], [12.0 * s], [12.0 * s * s], [2.0 * s**3]])
    i2 = 2.0j
    alpha = -np.exp(2.0j * X0) * np.array([1.0 / i2, -1.0 / i2**2, 1.0 / i2**3, -1.0 / i2**4])
    gamma = g * (alpha @ D)
    return ((Z * gamma) @ Z.T).real


# --- solution at a given contact radius ----------------------------------------------------------


@dataclass(frozen=True)
class RadiusSolution:
    """Solution with contact radius ``a`` prescribed (smooth edge enforced through ``delta``).

    ``g(x) = sum_n c_n P_{2n}(x) + sum_j e_j exp(beta_j (x - 1))``: the second sum (edge
    functions, :mod:`coathertz.axisym.edge`) only for thin layers solved with the enriched basis
    (``beta`` empty otherwise; ``c`` alone is then ``g`` to within the edge boundary layer)."""

    a: float
    delta: float
    W: float
    c: np.ndarray  # Legendre coefficients of g(x) on P_0, P_2, ... [m]
    d_unit: tuple[np.ndarray, np.ndarray] = field(repr=False)
    n_xi: int = 0
    beta: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    e: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)  # edge coefficients [m]


def _rhs(n_modes: int) -> np.ndarray:
    b = np.zeros((n_modes, 2))
    b[0, 0] = 1.0  # f = 1
    b[0, 1] = 1.0 / 3.0  # f = x^2 = P0/3 + 2 P2/3
    if n_modes > 1:
        b[1, 1] = -2.0 / 15.0  # (-1)^1 int_0^1 x^2 P2 dx
    return b


def _dM_dlogk(pc: PairCompliance, k: np.ndarray, eta: float = 1e-3) -> np.ndarray:
    """``dM/d(log k)`` by the 4-point central stencil in ``log k`` (error ~eta^4 ~ 1e-12,
    round-off ~1e-13: ``M`` is smooth on the scale 1 in ``log k``)."""
    e1, e2 = math.exp(eta), math.exp(2.0 * eta)
    k = np.asarray(k, dtype=float)
    m = pc.M(np.stack([k * e1, k / e1, k * e2, k / e2]))  # one call: M's overhead once, not four times
    return (8.0 * (m[0] - m[1]) - (m[2] - m[3])) / (12.0 * eta)


def _tail_bilinear(fn, n_modes: int, beta: np.ndarray, X0: float, X1: float,
                   V: np.ndarray | None = None) -> np.ndarray:
    """``int_X0^inf fn(xi) Phi_p Phi_q dxi`` beyond the direct rule (``fn``: weight as a function
    of ``xi``) for the Legendre basis enriched with edge functions of rates ``beta``; with ``V``
    (coefficient columns) the small matrix ``V^T [...] V`` without forming the full one.

    Every basis function is ``Re(U e^{i xi})`` there (``U = Z_n / xi`` for ``j_{2n}``, DLMF
    10.49.2; ``1/(beta + i xi)`` for ``exp(beta (x - 1))``) and
    ``Phi_p Phi_q = Re(U_p conj U_q)/2 + Re(U_p U_q e^{2 i xi})/2``: the smooth part on the
    geometric Gauss panels of :func:`_tail_table`, the oscillating part by parts at ``X0``."""
    x, w, S, C, xs, Z = _tail_table(n_modes, X0, X1)
    U, U5 = _tail_envelopes(n_modes, beta, X0, x, S, C, xs, Z)
    if V is not None:
        U, U5 = V.T @ U, V.T @ U5
    wm = 0.5 * w * fn(x)
    Ur, Ui = U.real, U.imag
    A = (Ur * wm) @ Ur.T + (Ui * wm) @ Ui.T  # Re(U diag(wm) U^H) in real arithmetic
    return A + _by_parts(0.5 * fn(xs), U5, xs[1] - xs[0], X0)


_ENV: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}
_BASIS: dict[tuple, np.ndarray] = {}


def _tail_envelopes(n_modes: int, beta: np.ndarray, X0: float, x: np.ndarray, S: np.ndarray,
                    C: np.ndarray, xs: np.ndarray, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The envelopes ``U`` of :func:`_tail_bilinear` on the tail nodes ``x`` and on the stencil
    ``xs``; they depend on the basis and the nodes only (not on ``a`` or ``h``): cached per
    ``(N, beta, X0, number of nodes)`` (two to six times per solve otherwise)."""
    key = (n_modes, beta.tobytes(), float(X0), x.size)
    env = _ENV.get(key)
    if env is None:
        U = np.concatenate([(C - 1j * S) / x, 1.0 / (beta[:, None] + 1j * x[None, :])])
        U5 = np.concatenate([Z / xs, 1.0 / (beta[:, None] + 1j * xs[None, :])])
        for arr in (U, U5):
            arr.flags.writeable = False
        env = _ENV[key] = (U, U5)
        if len(_ENV) > 8:
            _ENV.pop(next(iter(_ENV)))
    return env


def _direct_basis(J: np.ndarray, xi: np.ndarray, beta: np.ndarray, rule: XiRule) -> np.ndarray:
    """``[j_{2n}(xi); Psi_j(xi)]`` on the direct nodes (the Legendre rows alone without edge
    functions); cached per ``(N, beta, rule, nodes)``: it does not depend on ``a``."""
    if not beta.size:
        return J
    key = (J.shape[0], beta.tobytes(), rule, xi.size)
    B = _BASIS.get(key)
    if B is None:
        from coathertz.axisym import edge as E

        B = np.concatenate([J, E.psi_hat(beta, xi)])
        B.flags.writeable = False
        _BASIS[key] = B
        if len(_BASIS) > 4:
            _BASIS.pop(next(iter(_BASIS)))
    return B


_CONST: dict[tuple, np.ndarray] = {}


def constant_weight_error(n_modes: int, beta: np.ndarray, rule: XiRule) -> np.ndarray:
    """The xi rule's error for a constant weight, ``Q(Phi_p Phi_q) - int_0^inf Phi_p Phi_q dxi``
    (direct rule to ``X0`` plus the closed-form tail to ``1e12 X0``), with the exact value
    ``(pi/2) <phi_p, phi_q>`` (Parseval; ``pi / (2 (4m+1)) delta_mn`` for Legendre modes).

    ``M`` is ~``M(0)`` wherever the rule errs most (small ``xi``, where ``j_{2m} j_{2n}`` are
    largest), and the identity part of the Galerkin matrix cancels ``M(0) = -1`` on a rigid base:
    there the rule's relative error (~1e-9 at 8 nodes per panel) became a 3e-7 error in delta for
    a thin incompressible layer. :func:`solve_at_radius` subtracts ``M(0)`` times this matrix
    (cached per basis; it does not depend on ``a``)."""
    key = (n_modes, tuple(float(b) for b in beta), rule)
    C = _CONST.get(key)
    if C is None:
        X0 = direct_end(n_modes, rule)
        xi, w, J = bessel_table(n_modes, X0, rule)
        m = np.arange(n_modes)
        if beta.size:
            from coathertz.axisym import edge as E

            B = np.concatenate([J, E.psi_hat(beta, xi)])
            gc, ge = E.gram_cross(n_modes, beta), E.gram_edge(beta)
            gram = np.zeros((n_modes + beta.size,) * 2)
            gram[:n_modes, n_modes:] = gc
            gram[n_modes:, :n_modes] = gc.T
            gram[n_modes:, n_modes:] = ge
        else:
            B = J
            gram = np.zeros((n_modes, n_modes))
        gram[m, m] = 1.0 / (4.0 * m + 1.0)
        T_inf = _tail_bilinear(np.ones_like, n_modes, beta, X0, 1e12 * X0)
        C = (B * w) @ B.T + T_inf - 0.5 * math.pi * gram
        C.flags.writeable = False
        _CONST[key] = C
        if len(_CONST) > 16:
            _CONST.pop(next(iter(_CONST)))
    return C


def solve_at_radius(
    pc: PairCompliance, R: float, a: float, n_modes: int, rule: XiRule, decay: float = 24.0,
    beta: np.ndarray | None = None, edge_condition: str = "point",
) -> RadiusSolution:
    """Solve the Galerkin system for contact radius ``a``; ``delta`` from the smooth edge.

    Parameters
    ----------
    beta
        Decay rates of edge functions enriching the Legendre basis (thin layers,
        :mod:`coathertz.axisym.edge`); ``None``: Legendre modes only.
    edge_condition
        ``energy`` (what :class:`~coathertz.axisym.method.AxisymMethod` uses for thin layers): the
        smooth edge as stationarity of the load at fixed ``delta``, ``dW/da|_delta = 0``, with
        ``W = 2 E_ref a (delta P_1 - q P_12)`` built from the Galerkin energies
        ``P_1 = <1, g_1>``, ``P_12 = <1, g_2> = <x^2, g_1>`` (``g_1``, ``g_2``: the solutions for
        right-hand sides ``1`` and ``x^2``) and their ``a``-derivatives
        (``d<f, L^-1 f'>/da = -<g, L' g'>``, exact for the Galerkin system): these are
        variational, their error is quadratic in that of ``g``, so they stay accurate when a thin
        layer's edge boundary layer is not resolved (measured, B4C example at ``H = 1e-3``: 1e-8
        at 48 modes against 4e-6 for ``g(1) = 0``). ``point`` (default; exact ``g(1) = 0`` for
        readers of ``c``): ``g(1) = 0``, linear in ``delta``.
    """
    if edge_condition not in ("energy", "point"):
        raise ValueError(f"edge_condition must be 'energy' or 'point', got {edge_condition!r}")
    beta = np.zeros(0) if beta is None or not pc.terms else np.asarray(beta, dtype=float)
    N, nJ = n_modes, beta.size
    m = np.arange(N)
    sign = (-1.0) ** m
    G = np.zeros((N + nJ, N + nJ))
    G[m, m] = 1.0 / (4.0 * m + 1.0)
    rhs = _rhs(N)
    if nJ:
        from coathertz.axisym import edge as E

        gc, ge, re, ie, T = E.edge_blocks(N, tuple(float(b) for b in beta), GRAM_TOL)
        G[:N, N:] = gc
        G[N:, :N] = gc.T
        G[N:, N:] = ge
        rhs = np.concatenate([rhs, re])
        ell = np.concatenate([np.eye(1, N)[0], ie])  # v -> int_0^1 g dx
        ends = np.concatenate([sign, np.ones(nJ)])  # v -> g(1)
    else:
        ell = np.eye(1, N)[0]
        ends = sign
    n_xi = 0
    X = decay * a / pc.h_min if pc.terms else 0.0
    X0 = direct_end(N, rule)
    if pc.terms:
        xi, w, J = bessel_table(N, min(X, X0), rule)
        B = _direct_basis(J, xi, beta, rule)
        A = (B * (w * pc.M(xi / a))) @ B.T
        if X > X0:  # thin layer: the rest in closed form (cost independent of h)
            A = A + _tail_bilinear(lambda x: pc.M(x / a), N, beta, X0, X)
            # the rule's error on the constant part M(0) (constant_weight_error)
            A = A - float(pc.M(np.array([1e-12 / pc.h_min]))[0]) * constant_weight_error(N, beta, rule)
        n_xi = xi.size
    G = G + (2.0 / math.pi) * A if pc.terms else G
    if nJ:
        # the edge functions at neighbouring scales are nearly dependent: solved in an orthonormal
        # basis T of the numerically independent part of the span (edge.edge_blocks)
        D = T @ np.linalg.solve(T.T @ G @ T, T.T @ rhs)
    else:
        D = lu_solve(lu_factor(G), rhs)
    q = a * a / R
    P1, P12 = float(ell @ D[:, 0]), float(ell @ D[:, 1])
    if edge_condition == "point" or not pc.terms:
        s1, s2 = float(ends @ D[:, 0]), float(ends @ D[:, 1])  # g_1(1), g_2(1)
        if s1 <= 0:
            raise ConvergenceError(f"axisym: no smooth-edge solution at a = {a:.6g} m (g1(1) = {s1:.3g}); "
                                   f"{MODES_HINT}")
        delta = q * s2 / s1  # g(1) = delta g1(1) - q g2(1) = 0
    else:
        # a dP/da = -(2/pi) v^T (a dA/da) v, a dA/da = int (-dM/dlog k) Phi Phi dxi
        u = D.T @ B  # (2, n_xi)
        dM = -_dM_dlogk(pc, xi / a)
        Q = (u * (w * dM)) @ u.T
        if X > X0:
            Q = Q + _tail_bilinear(lambda x: -_dM_dlogk(pc, x / a), N, beta, X0, X, V=D)
        dP1, dP12 = -(2.0 / math.pi) * Q[0, 0], -(2.0 / math.pi) * Q[0, 1]
        den = P1 + dP1
        if den <= 0:
            raise ConvergenceError(f"axisym: no smooth-edge solution at a = {a:.6g} m "
                                   f"(d(a P_1)/da = {den:.3g}); {MODES_HINT}")
        # W(a; delta) = 2 E_ref (delta a P1 - a^3 P12 / R); dW/da = 0 at fixed delta
        delta = q * (3.0 * P12 + dP12) / den
    v = delta * D[:, 0] - q * D[:, 1]
    c = sign * v[:N]
    e = v[N:]
    W = 2.0 * pc.E_ref * a * (delta * P1 - q * P12)  # W = 2 pi int theta = 2 E a int_0^1 g dx
    return RadiusSolution(a, delta, W, c, (sign * D[:N, 0], sign * D[:N, 1]), n_xi, beta, e)


#: Relative eigenvalue of the enriched Gram matrix below which a direction of the span is dropped.
GRAM_TOL = 1e-15


# --- load control ---------------------------------------------------------------------------------


def initial_radius(pc: PairCompliance, R: float, W: float) -> float:
    """Hertz radius with the compliance taken at ``k = 1.2 / a`` (fixed point, a few % off)."""
    a = (3.0 * W * R / (4.0 * pc.E_ref)) ** (1.0 / 3.0)
    for _ in range(30):
        f = 1.0 + float(pc.M(np.array([1.2 / a]))[0])
        a_new = (3.0 * W * R * f / (4.0 * pc.E_ref)) ** (1.0 / 3.0)
        if abs(a_new - a) < 1e-4 * a:
            a = a_new
            break
        a = a_new
    return a


def _model_slope(pc: PairCompliance, R: float, a: float) -> float:
    """``d log W / d log a`` of the model ``W = 4 E_ref a^3 / (3 R (1 + M(1.2/a)))`` (3 for Hertz,
    up to 6 for incompressible thin layers): the first secant step."""
    eps = 1e-3

    def logW(x: float) -> float:
        a_ = math.exp(x)
        return 3.0 * x - math.log(1.0 + float(pc.M(np.array([1.2 / a_]))[0]))

    x = math.log(a)
    s = (logW(x + eps) - logW(x - eps)) / (2.0 * eps)
    return s if 1.0 < s < 10.0 else 3.0


#: Stagnation test of :func:`solve_load`: a step in ``log a`` this small with ``|log W err|`` below
#: STALL_LOAD is accepted as converged (W(a) is only smooth to round-off).
STALL_STEP = 1e-13
STALL_LOAD = 1e-9


def solve_load(
    pc: PairCompliance,
    R: float,
    W: float,
    n_modes: int,
    rule: XiRule,
    decay: float = 24.0,
    rtol: float = 1e-12,
    max_iter: int = 40,
    a_start: float | None = None,
    beta: np.ndarray | None = None,
    edge_condition: str = "energy",
) -> tuple[RadiusSolution, int]:
    """Find ``a`` with ``W(a) = W`` (secant in ``log a`` on ``log W``, bracketed), starting from
    ``a_start`` (default :func:`initial_radius`); ``beta``: edge functions (fixed in ``x = r/a``
    during the iteration, :func:`solve_at_radius`)."""
    target = math.log(W)
    x0 = math.log(initial_radius(pc, R, W) if a_start is None else a_start)

    def f(x: float) -> tuple[float, RadiusSolution]:
        s = solve_at_radius(pc, R, math.exp(x), n_modes, rule, decay, beta, edge_condition)
        return math.log(s.W) - target, s

    f0, _ = f(x0)
    x1 = x0 - f0 / _model_slope(pc, R, math.exp(x0))
    f1, s1 = f(x1)
    lo = hi = None
    for it in range(2, max_iter):
        for x_, f_ in ((x0, f0), (x1, f1)):
            if f_ < 0 and (lo is None or x_ > lo[0]):
                lo = (x_, f_)
            if f_ > 0 and (hi is None or x_ < hi[0]):
                hi = (x_, f_)
        if abs(f1) < rtol:
            return s1, it
        if abs(x1 - x0) <= STALL_STEP and abs(f1) <= STALL_LOAD:
            # the load error has reached the noise floor of W(a) (round-off of the Galerkin solve,
            # ~1e-12 for thin, nearly incompressible layers): a is pinned to 1e-13 and W met to
            # 1e-9; iterating on cannot improve either
            return s1, it
        slope = (f1 - f0) / (x1 - x0) if x1 != x0 else 3.0
        if not (0.3 < slope < 30.0):
            slope = 3.0
        x2 = x1 - f1 / slope
        if lo is not None and hi is not None and not (lo[0] < x2 < hi[0]):
            x2 = 0.5 * (lo[0] + hi[0])
        x0, f0 = x1, f1
        x1 = x2
        f1, s1 = f(x1)
    raise ConvergenceError(
        f"axisym: load iteration did not converge in {max_iter} steps (|log W err| = {abs(f1):.2e}); "
        f"{MODES_HINT}"
    )


# --- fields ---------------------------------------------------------------------------------------


@lru_cache(maxsize=64)
def _half_gauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss--Legendre nodes and weights on ``[0, 1]``."""
    z, w = npleg.leggauss(n)
    return 0.5 * (z + 1.0), 0.5 * w


def _gprime_over_x(c: np.ndarray, x: np.ndarray) -> np.ndarray:
    full = np.zeros(2 * c.size - 1)
    full[::2] = c
    return npleg.legval(x, npleg.legder(full)) / x


def _abel_integral(c: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """``-int_0^1 g'(x)/x ds`` with ``x^2 = rho^2 + (1 - rho^2) s^2`` (exact Gauss rule: the
    integrand is a polynomial of degree ``4 N - 4`` in ``s``)."""
    s, ws = _half_gauss(c.size + 2)
    r2 = rho[:, None] ** 2
    x = np.sqrt(r2 + (1.0 - r2) * s[None, :] ** 2)
    return -(_gprime_over_x(c, x) @ ws)


def pressure_shape(sol: RadiusSolution) -> np.ndarray:
    """Chebyshev coefficients (in ``v = 2 rho^2 - 1``) of ``Q = -int_0^1 g'(x)/x ds``.

    ``p(rho) = E_ref / (pi a) sqrt(1 - rho^2) Q(rho^2)`` and ``Q`` is a polynomial of degree
    ``N - 2`` in ``rho^2``, so interpolation at ``N + 1`` Chebyshev points is exact; evaluating
    it costs ``O(N)`` per point instead of ``O(N^2)``. The coefficients are linear in ``c``:
    ``_shape_matrix`` (cached per ``N``) times ``c``.
    """
    return _shape_matrix(sol.c.size) @ sol.c


@lru_cache(maxsize=16)
def _shape_matrix(n_modes: int) -> np.ndarray:
    """The linear map ``c -> pressure_shape``: ``numpy.polynomial.chebyshev.chebinterpolate`` of
    ``Q`` (degree ``N``, the first-kind points ``v_i``) with ``Q(v_i) = sum_n c_n q_n(v_i)``,
    ``q_n = -int_0^1 P'_2n(x)/x ds`` by the Gauss rule of :func:`_abel_integral` (exact: the
    integrand is a polynomial of degree ``4 N - 4`` in ``s``), the ``P'_k`` by their recurrence
    at all nodes at once (two ``legval`` passes' work, once per ``N``, instead of one per solve)."""
    deg = n_modes
    v = npcheb.chebpts1(deg + 1)
    rho2 = np.clip(0.5 * (v + 1.0), 0.0, 1.0)
    s, ws = _half_gauss(n_modes + 2)
    x = np.sqrt(rho2[:, None] + (1.0 - rho2[:, None]) * s[None, :] ** 2)  # (deg + 1, n_s), > 0
    # P_k and P'_k up to k = 2N - 2: P_{k+1} = ((2k+1) x P_k - k P_{k-1})/(k+1),
    # P'_{k+1} = P'_{k-1} + (2k+1) P_k
    q = np.empty((n_modes, deg + 1))
    p_prev, p = np.ones_like(x), x.copy()  # P_0, P_1
    d_prev, d = np.zeros_like(x), np.ones_like(x)  # P'_0, P'_1
    q[0] = 0.0
    for k in range(1, 2 * n_modes - 2):
        p_next = ((2 * k + 1) * x * p - k * p_prev) / (k + 1)
        d_next = d_prev + (2 * k + 1) * p
        p_prev, p, d_prev, d = p, p_next, d, d_next
        if (k + 1) % 2 == 0:  # P'_{2n}, 2n = k + 1
            q[(k + 1) // 2] = -((d / x) @ ws)
    m = npcheb.chebvander(v, deg)
    A = m.T @ q.T  # (deg + 1, N): chebinterpolate's np.dot(m.T, Q(v_i)) for every c = e_n
    A[0] /= deg + 1
    A[1:] /= 0.5 * (deg + 1)
    A.flags.writeable = False
    return A


def pressure(pc: PairCompliance, sol: RadiusSolution, rho: np.ndarray,
             shape: np.ndarray | None = None) -> np.ndarray:
    """``p(r = rho a)`` [Pa], ``0 <= rho <= 1``:
    ``p = (E_ref / (pi a)) sqrt(1 - rho^2) Q(rho^2)``, ``Q = -int_0^1 g'(x)/x ds``,
    ``x^2 = rho^2 + (1 - rho^2) s^2`` (the Abel inversion of ``theta = E_ref g / pi``).

    Integrated by parts, ``Q = [g(rho) - g(1) - int_0^1 (g(x(s)) - g(rho)) / s^2 ds] / (1 - rho^2)``:
    ``g(1)`` enters only as the square-root singular part ``-g(1) / (1 - rho^2)``, and the smooth
    edge makes it zero. The Galerkin ``g(1)`` is exactly zero with ``edge_condition="point"``; with
    the energy condition it is the discretisation error of a point value at the edge boundary
    layer (~1e-7 of ``g(0)`` for ``h/a = 1e-8``), so the smooth edge is imposed here:
    ``Q + g(1) / (1 - rho^2)`` (measured: p(0) then agrees between bases to 5e-10 instead of
    3e-7)."""
    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    if shape is None:
        shape = pressure_shape(sol)
    q = npcheb.chebval(2.0 * rho**2 - 1.0, shape)
    if sol.e.size:  # edge functions (thin layers)
        from coathertz.axisym.edge import edge_Q

        q = q + edge_Q(sol.beta, sol.e, rho)
    c2 = np.clip(1.0 - rho**2, 0.0, None)
    g1 = float(sol.c.sum() + sol.e.sum())
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(c2 > 0.0, np.sqrt(c2) * q + g1 / np.sqrt(c2), 0.0)
    return (pc.E_ref / (math.pi * sol.a)) * p


def peak_pressure(pc: PairCompliance, sol: RadiusSolution, n_scan: int | None = None,
                  shape: np.ndarray | None = None,
                  scan: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[float, float]:
    """Maximum of ``p(r)`` and its radius ``r_p0`` [m] (0.0 on the axis).

    A scan on ``n_scan`` points (clustered at both ends; default 129, 49 with edge functions,
    whose pressure costs a quadrature per point) brackets the maximum; six zooms of 9 points
    shrink the bracket by 4 each, and a parabola through the best three points gives the peak
    (``p`` is smooth in ``rho``; the value is exact to ~1e-13 relative). ``scan``: ``(rho, p)``
    already computed (increasing ``rho`` from 0 to 1, e.g. the profile of the fields) in place of
    the scan.
    """
    if n_scan is None:
        n_scan = 49 if sol.e.size else 129
    if shape is None:
        shape = pressure_shape(sol)

    def pv(r: np.ndarray) -> np.ndarray:
        return pressure(pc, sol, r, shape)

    if scan is not None:
        rho, p = (np.asarray(v, dtype=float) for v in scan)
        n_scan = rho.size
    else:
        rho = 0.5 * (1.0 - np.cos(np.linspace(0.0, math.pi, n_scan)))
        p = pv(rho)
    i = int(np.argmax(p))
    if i == 0 and rho[0] == 0.0 and rho[1] <= 2e-3 and p[1] < p[0]:
        # the largest value on the axis and falling to the next point (rho^2 <= 4e-6): p is a
        # smooth function of rho^2, so a maximum between gains at most |p_uu| u_1^2 / 8
        # (u = rho^2) over p(0), below 1e-12 of p0 unless p changes by 1e6 p0 per unit of rho^2;
        # the zooms below would only confirm the axis (seven pressure evaluations saved, each a
        # quadrature with edge functions)
        return float(p[0]), 0.0
    lo, hi = rho[max(i - 1, 0)], rho[min(i + 1, n_scan - 1)]
    best_r, best_p = rho[i], p[i]
    for _ in range(6):
        r = np.linspace(lo, hi, 9)
        pz = pv(r)
        j = int(np.argmax(pz))
        if pz[j] >= best_p:
            best_r, best_p = r[j], pz[j]
        step = r[1] - r[0]
        lo, hi = max(r[j] - step, 0.0), min(r[j] + step, 1.0)
    if 0.0 < best_r < 1.0:  # parabolic vertex through the best point and its neighbours
        h_ = 0.5 * (hi - lo)
        r3 = np.array([best_r - h_, best_r, best_r + h_])
        if r3[0] >= 0.0 and r3[2] <= 1.0:
            p3 = pv(r3)
            den = p3[0] - 2.0 * p3[1] + p3[2]
            if den < 0:
                rv = best_r + 0.5 * h_ * (p3[0] - p3[2]) / den
                pr = pv(np.array([rv]))[0]
                if pr > best_p:
                    best_r, best_p = rv, pr
    p_axis = float(p[0])
    if best_p <= p_axis * (1.0 + 1e-12):  # flat top on the axis: the peak is on the axis
        return max(p_axis, float(best_p)), 0.0
    return float(best_p), float(best_r * sol.a)


def displacement(pc: PairCompliance, sol: RadiusSolution, rho: np.ndarray, R: float, rule: XiRule,
                 decay: float = 24.0, max_xi: float | None = None) -> np.ndarray:
    """Combined surface normal displacement of the two bodies ``u_z(r = rho a)`` [m].

    Inside the contact ``u_z = delta - r^2/(2R)`` (the contact condition, returned as such);
    outside, ``u_z = (2/pi) int_0^1 g(x) / sqrt(rho^2 - x^2) dx`` (homogeneous part, Sneddon)
    ``+ (2/pi) sum_n d_n int M(xi/a) j_{2n}(xi) J_0(xi rho) dxi`` (layer correction), the latter
    integrated up to ``min(decay a / h, max_xi)`` (``max_xi`` bounds the cost for thin layers).
    """
    from scipy.special import j0

    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    out = sol.delta - (rho * sol.a) ** 2 / (2.0 * R)
    outside = rho > 1.0
    if not np.any(outside):
        return out
    ro = rho[outside]
    full = np.zeros(2 * sol.c.size - 1)
    full[::2] = sol.c
    s, ws = _half_gauss(sol.c.size + 24)
    # x = rho sin(phi), phi in [0, asin(1/rho)]
    phi_max = np.arcsin(1.0 / ro)
    phi = phi_max[:, None] * s[None, :]
    uh = (2.0 / math.pi) * (npleg.legval(ro[:, None] * np.sin(phi), full) @ ws) * phi_max
    if sol.e.size:  # edge functions: (2/pi) sum_j e_j int_0^1 psi_j(x) / sqrt(rho^2 - x^2) dx
        from coathertz.axisym.edge import graded_rule

        tg, wg = graded_rule(sol.c.size, float(1.0 / sol.beta.max()))
        xg = 1.0 - tg
        ge = np.exp(-sol.beta[None, :] * tg[:, None]) @ sol.e
        uh = uh + (2.0 / math.pi) * ((ge * wg)[None, :] / np.sqrt(ro[:, None] ** 2 - xg[None, :] ** 2)).sum(1)
    um = np.zeros_like(ro)
    if pc.terms:
        X = decay * sol.a / pc.h_min
        if max_xi is not None:
            X = min(X, max_xi)
        xi, w, J = bessel_table(sol.c.size, X, rule)
        d = sol.c * (-1.0) ** np.arange(sol.c.size)
        gh = d @ J
        if sol.e.size:
            from coathertz.axisym.edge import psi_hat

            gh = gh + sol.e @ psi_hat(sol.beta, xi)
        kern = gh * w * pc.M(xi / sol.a)
        um = (2.0 / math.pi) * (j0(ro[:, None] * xi[None, :]) @ kern)
    out[outside] = uh + um
    return out
