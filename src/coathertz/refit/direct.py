r"""The second closed form: a direct smooth fit of the bars (elastic substrate, circular).

Where no single alpha reproduces the exact bar (:func:`coathertz.refit.fit.single_alpha_floor`:
e.g. the maximum pressure under soft, nearly incompressible coatings around H ~ 0.1), the
one-alpha structure of eqs (17)-(18) cannot reach the target however alpha is fitted. This
form drops eq (17) and fits the bars themselves:

.. math::

    \ln \bar q = k_q \ln E \; w(H) + w(H)\,(1 - w(H))\; S_q(\log_{10} H, \log_{10} E, \nu_c, \nu_s),
    \qquad w(H) = \frac{H}{1 + H},

with :math:`k_a = -1/3`, :math:`k_\delta = -2/3`, :math:`k_p = 2/3` and a clamped Chebyshev
surface :math:`S_q` fitted by linear least squares. Limits: :math:`H \to 0` gives
:math:`\bar q \to 1` (substrate Hertz) and :math:`H \to \infty` gives :math:`\bar q \to E^{k_q}`
(coating Hertz), both approached like :math:`H^{\pm 1}`, as the exact solutions are.

:func:`fit_corrected` is the third form, usually the most accurate: the refit alpha of eqs (17)-(18)
times ``exp(w(1 - w) C_q)``, a smooth correction with the same vanishing limits.
"""

from __future__ import annotations

import numpy as np

from coathertz.extended import EXPONENT
from coathertz.refit import model as M
from coathertz.refit.fit import FitSettings, error_stats
from coathertz.refit.surface import Surface, term_set


def weight(H) -> np.ndarray:
    H = np.asarray(H, dtype=float)
    return H / (1.0 + H)


def log_bar(surface: Surface, q: str, E, H, nu_c=0.3, nu_s=0.3) -> np.ndarray:
    """``ln bar_q`` of the direct form (flattened broadcast shape)."""
    X = M.variables("elastic", E, H, nu_c, nu_s)
    E = 10.0 ** X[1]
    w = weight(10.0 ** X[0])
    return EXPONENT[q] * np.log(E) * w + w * (1.0 - w) * surface(X)


def _design(cols, settings: FitSettings) -> tuple[Surface, np.ndarray, np.ndarray]:
    """The zero surface over the elastic box, the blend weight ``w(H)`` and the design matrix
    ``w (1 - w) * basis`` (the correction vanishes in both Hertz limits) of the columns ``cols``."""
    terms = term_set(settings.degrees, settings.cross or None)
    lo = tuple(b[0] for b in M.BOXES["elastic"])
    hi = tuple(b[1] for b in M.BOXES["elastic"])
    proto = Surface(M.VARIABLES["elastic"], lo, hi, terms, tuple(0.0 for _ in terms))
    X = M.variables("elastic", cols["E"], cols["H"], cols["nu_c"], cols["nu_s"])
    w = weight(np.asarray(cols["H"], dtype=float))
    return proto, w, (w * (1 - w))[:, None] * proto.design(X)


def fit(q: str, cols, settings: FitSettings, reweight: int = 4) -> tuple[Surface, dict]:
    """Fit ``S_q`` to the columns ``E, H, nu_c, nu_s, {q}_bar`` (linear least squares with a few
    Lawson re-weighting passes towards the minimax fit)."""
    proto, w, A = _design(cols, settings)
    terms = proto.terms
    y = np.log(np.asarray(cols[f"{q}_bar"], dtype=float)) - EXPONENT[q] * np.log(cols["E"]) * w
    wt = np.ones(len(y))
    for _ in range(reweight + 1):
        sw = np.sqrt(wt / wt.mean())
        Aw = A * sw[:, None]
        c = np.linalg.solve(Aw.T @ Aw + settings.ridge * np.eye(len(terms)), Aw.T @ (y * sw))
        r = np.abs(A @ c - y)
        wt = wt * (r / max(r.max(), 1e-300)) + 1e-3
    surface = Surface(proto.variables, proto.lo, proto.hi, terms, tuple(float(x) for x in c))
    return surface, error_stats(100.0 * np.expm1(A @ c - y))


def fit_corrected(q: str, cols, base_log_bar: np.ndarray, settings: FitSettings) -> tuple[Surface, dict]:
    """The corrected one-alpha form: ``ln bar = ln bar_alpha + w(1 - w) C_q(...)``, i.e. the refit
    alpha of eqs (17)-(18) times a smooth factor that vanishes in both Hertz limits. ``C_q`` is fitted
    by linear least squares to the residual ``ln bar_exact - base_log_bar`` of the one-alpha rule."""
    proto, _w, A = _design(cols, settings)
    terms = proto.terms
    y = np.log(np.asarray(cols[f"{q}_bar"], dtype=float)) - base_log_bar
    c = np.linalg.solve(A.T @ A + settings.ridge * np.eye(len(terms)), A.T @ y)
    surface = Surface(proto.variables, proto.lo, proto.hi, terms, tuple(float(x) for x in c))
    return surface, error_stats(100.0 * np.expm1(A @ c - y))


def log_correction(surface: Surface, E, H, nu_c=0.3, nu_s=0.3) -> np.ndarray:
    """``w(1 - w) C_q`` of the corrected form (flattened broadcast shape)."""
    X = M.variables("elastic", E, H, nu_c, nu_s)
    w = weight(10.0 ** X[0])
    return w * (1.0 - w) * surface(X)
