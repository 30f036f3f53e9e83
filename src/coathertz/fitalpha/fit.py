"""Fitting the alpha surfaces to a sweep: Gauss-Newton on the prediction error itself.

For each quantity the unknowns are the coefficients ``c`` of ``ln alpha = Phi c``
(:class:`~coathertz.closedform.refit.surface.Surface`). The residual is the relative error of the
prediction in log form, ``r_n = ln bar_pred(alpha(c); x_n) - ln bar_exact(x_n)``, so the fit
minimises what the user sees, also where no single alpha reproduces the exact value (there the
inverted alpha of fig 4 does not exist). Its Jacobian is ``g_n Phi_n`` with the sensitivity
``g = d ln bar / d ln alpha`` of eq (17) (central differences). A small ridge term keeps the
coefficients bounded where the bars do not depend on alpha (E near 1, H -> 0 or inf).

A few Lawson-style re-weighting passes (weights grow where the error is largest) move the
least-squares solution towards the minimax one, since the claim is on the *maximum* error.
Everything is deterministic: the same sweep gives the same coefficients.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from coathertz.closedform.refit.surface import Surface, term_set


@dataclass(frozen=True)
class FitSettings:
    """Knobs of one surface fit (all stored in the data file's provenance)."""

    degrees: tuple[int, ...]
    cross: tuple[tuple[int, int], ...] = ()
    ridge: float = 1e-8
    iterations: int = 40
    reweight: int = 6
    reweight_power: float = 1.0
    init_from_inverse: bool = False

    def to_dict(self) -> dict:
        return {"degrees": list(self.degrees), "cross": [list(c) for c in self.cross], "ridge": self.ridge,
                "iterations": self.iterations, "reweight": self.reweight,
                "reweight_power": self.reweight_power, "init_from_inverse": self.init_from_inverse}

    @classmethod
    def from_dict(cls, d: Mapping) -> FitSettings:
        return cls(tuple(int(x) for x in d["degrees"]),
                   tuple(tuple(int(x) for x in c) for c in d.get("cross", ())),
                   float(d.get("ridge", 1e-8)), int(d.get("iterations", 40)), int(d.get("reweight", 6)),
                   float(d.get("reweight_power", 1.0)), bool(d.get("init_from_inverse", False)))


@dataclass(frozen=True)
class FitResult:
    surface: Surface
    residual: np.ndarray  # ln(pred/exact) on the training points
    weights: np.ndarray


def _gauss_newton(Phi: np.ndarray, c: np.ndarray, resid: Callable[[np.ndarray], np.ndarray],
                  sens: Callable[[np.ndarray], np.ndarray], w: np.ndarray, ridge: float,
                  iterations: int) -> np.ndarray:
    """Levenberg-Marquardt on ``sum w r^2 + ridge |c|^2`` with ``r`` a function of ``Phi c``."""
    sw = np.sqrt(w)
    lam = 1e-3

    def cost(cc):
        r = resid(Phi @ cc)
        return float(np.sum(w * r * r) + ridge * cc @ cc)

    f = cost(c)
    for _ in range(iterations):
        z = Phi @ c
        r = resid(z)
        J = (sens(z) * sw)[:, None] * Phi
        rhs = -(J.T @ (sw * r)) - ridge * c
        A = J.T @ J + ridge * np.eye(len(c))
        improved = False
        for _ in range(12):
            step = np.linalg.solve(A + lam * np.diag(np.diag(A) + 1e-12), rhs)
            f_new = cost(c + step)
            if np.isfinite(f_new) and f_new < f:
                c, lam, improved = c + step, max(lam / 4, 1e-9), True
                rel = (f - f_new) / max(f, 1e-300)
                f = f_new
                break
            lam *= 8
        if not improved or rel < 1e-10:
            break
    return c


def fit_surface(
    variables: tuple[str, ...],
    box: tuple[tuple[float, float], ...],
    X: np.ndarray,
    log_bar_exact: np.ndarray,
    bar_of_alpha: Callable[[np.ndarray], np.ndarray],
    settings: FitSettings,
    alpha0: float = 1.5,
) -> FitResult:
    """Fit ``ln alpha`` on the points ``X`` (``(d, n)``) to reproduce ``log_bar_exact``.

    ``bar_of_alpha(alpha)`` returns the predicted bars at the n points for a vector of alpha.
    """
    terms = term_set(settings.degrees, settings.cross or None)
    lo = tuple(b[0] for b in box)
    hi = tuple(b[1] for b in box)
    proto = Surface(variables, lo, hi, terms, tuple(0.0 for _ in terms))
    Phi = proto.design(X)
    y = np.asarray(log_bar_exact, dtype=float)

    from coathertz.closedform.refit.model import ln_alpha

    def resid(z):
        with np.errstate(all="ignore"):
            return np.log(bar_of_alpha(np.exp(ln_alpha(z)))) - y

    def sens(z, h=1e-4):
        return (resid(z + h) - resid(z - h)) / (2 * h)

    c = np.zeros(len(terms))
    c[0] = np.log(alpha0)
    if settings.init_from_inverse:
        # start from a sensitivity-weighted least-squares fit of the inverted ln alpha (fig 4)
        grid = np.geomspace(1e-3, 1e3, 200)
        with np.errstate(all="ignore"):
            R = np.stack([resid(np.full(len(y), np.log(g))) for g in grid], axis=1)
        s_ = np.sign(R)
        cross = (s_[:, :-1] * s_[:, 1:]) <= 0
        has = cross.any(axis=1)
        k = np.argmax(cross, axis=1)
        la = np.log(grid[k]) + np.log(grid[1] / grid[0]) * R[np.arange(len(y)), k] / (
            R[np.arange(len(y)), k] - R[np.arange(len(y)), np.minimum(k + 1, len(grid) - 1)])
        la = np.where(has & np.isfinite(la), la, np.log(alpha0))
        g = np.abs(sens(la))
        wt = np.where(has, g / (g + 0.01), 1e-3)
        A = Phi * np.sqrt(wt)[:, None]
        c = np.linalg.solve(A.T @ A + 1e-6 * np.eye(len(terms)), A.T @ (la * np.sqrt(wt)))
    w = np.ones(len(y))
    for _ in range(settings.reweight + 1):
        c = _gauss_newton(Phi, c, resid, sens, w / w.sum() * len(w), settings.ridge, settings.iterations)
        r = resid(Phi @ c)
        a = np.abs(r)
        w = w * (a / max(a.max(), 1e-300)) ** settings.reweight_power + 1e-3
    surface = Surface(variables, lo, hi, terms, tuple(float(x) for x in c))
    return FitResult(surface, resid(Phi @ c), w)


def error_stats(err_percent: np.ndarray) -> dict[str, float]:
    """max, 99th percentile and RMS of |err| [%] (NaN-free input)."""
    a = np.abs(np.asarray(err_percent, dtype=float))
    if a.size == 0:
        return {"n": 0, "max": float("nan"), "p99": float("nan"), "rms": float("nan")}
    return {"n": int(a.size), "max": float(a.max()), "p99": float(np.percentile(a, 99)),
            "rms": float(np.sqrt(np.mean(a * a)))}


def single_alpha_floor(bar_of_alpha: Callable[[np.ndarray], np.ndarray], log_bar_exact: np.ndarray,
                       bounds: tuple[float, float] = (1e-3, 1e3), n_scan: int = 400) -> np.ndarray:
    """The smallest |err| [%] that *any* alpha in ``bounds`` achieves at each point.

    Zero where some alpha reproduces the exact bar (the predicted bar crosses it as alpha is
    scanned: fig 4's inverted alpha exists); otherwise the closest approach on the scan. This
    is the structural limit of the one-alpha form of eqs (1), (17), (18), independent of how
    alpha is fitted. ``bar_of_alpha(alpha)`` takes an ``(n, n_scan)`` array.
    """
    y = np.asarray(log_bar_exact, dtype=float)
    grid = np.geomspace(bounds[0], bounds[1], n_scan)
    with np.errstate(all="ignore"):
        r = np.log(bar_of_alpha(np.broadcast_to(grid, (len(y), n_scan)))) - y[:, None]
    r = np.where(np.isfinite(r), r, np.inf)
    s = np.sign(r)
    crosses = np.any(s[:, :-1] * s[:, 1:] <= 0, axis=1)
    floor = 100.0 * np.expm1(np.min(np.abs(r), axis=1))
    return np.where(crosses, 0.0, floor)
