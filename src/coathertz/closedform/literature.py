"""Literature approximations the paper compares against, eqs (8)-(12).

Each function states its source, the configuration it assumes and its stated validity range;
outside that range it still evaluates but issues :class:`~coathertz.errors.FittedRangeWarning`.

* eq (8): Vorovich & Ustinov (1959), thick layer (h/a > 1.5) on a rigid base, rigid parabolic
  indenter; normalised by the coating-half-space Hertz values (a0c, ...), series in H = h/a0c.
  The paper quotes it with nu_c = 0.5 (figure 7) and describes it as the bonded case. Our FFT
  solver with both interfaces (``tests/fft/test_literature_rigid.py``) shows the series is that
  of a layer **resting without friction** on the base: its 1/H coefficient of delta, 0.504,
  matches the frictionless layer's 0.496 (independent of nu, as the series is), while a bonded
  incompressible layer has 0.751; a and p agree with the frictionless solution to ~1e-4 at H >= 3.
* eq (9): Keer (1964), same with an elastic indenter, C_E = E2*/(Ec* + E2*).
* eq (10): Matthewson (1981), thin (h/a < 1/2) incompressible (nu_c = 1/2) layer **bonded**
  to a rigid base, rigid sphere; tau = h/a.
* eq (11): Stevanovic et al. (2001), rigid substrate, curve fit in tau = h/a.
* eq (12): Stevanovic et al. (2001), elastic substrate, gamma = a0c/a0s, H = h/a0s.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy import special

from coathertz.errors import CoatHertzError, FittedRangeWarning


def _arr(name: str, x, *, positive: bool = True) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    if positive and np.any(~(x > 0)):
        raise CoatHertzError(f"{name} must be > 0")
    return x


def _out(x):
    return float(x) if np.ndim(x) == 0 else x


def _warn_outside(name: str, x: np.ndarray, lo: float, hi: float, source: str) -> None:
    bad = (x < lo) | (x > hi)
    if np.any(bad):
        warnings.warn(
            f"{source}: {name} outside its stated validity range [{lo:g}, {hi:g}] at "
            f"{int(np.count_nonzero(bad))} point(s)",
            FittedRangeWarning,
            stacklevel=3,
        )


def vorovich_ustinov(H, *, warn: bool = True):
    """Vorovich & Ustinov series, eqs (8a)-(8c): ``(delta_bar, a_bar, p_bar)`` against H = h/a0c.

    Stated for thick layers, h/a > 1.5 (checked here as H > 1.5, since a ~ a0c there). It
    matches a layer resting without friction on a rigid base (see the module docstring).
    """
    H = _arr("H", H)
    if warn:
        _warn_outside("H", H, 1.5, np.inf, "Vorovich-Ustinov eq (8)")
    d = 1 - 0.504 / H - 0.225 / H**3 - 0.098 / H**5 - 0.197 / H**6  # eq (8a)
    a = 1 - 0.113 / H**3 + 0.114 / H**5 + 0.025 / H**6 - 0.004 / H**7  # eq (8b)
    p = 1 + 0.225 / H**3 - 0.018 / H**5 - 0.0126 / H**6 + 0.013 / H**7  # eq (8c)
    return _out(d), _out(a), _out(p)


def keer(H, C_E, *, warn: bool = True):
    """Keer (1964), eqs (9a)-(9b): ``(delta_bar, a_bar)`` for an elastic indenter.

    ``C_E = E2*/(Ec* + E2*)``; C_E = 1 (rigid indenter) recovers the leading terms of eq (8).
    """
    H = _arr("H", H)
    C_E = np.asarray(C_E, dtype=float)
    if np.any((C_E < 0) | (C_E > 1)):
        raise CoatHertzError("C_E must satisfy 0 <= C_E <= 1")
    if warn:
        _warn_outside("H", H, 1.5, np.inf, "Keer eq (9)")
    d = 1 - 0.504 * C_E / H - C_E**2 * (0.225 / H**3 + 0.098 / H**5)  # eq (9a)
    a = 1 + C_E * (-0.113 / H**3 + 0.114 / H**5 + 0.025 * C_E / H**6)  # eq (9b)
    return _out(d), _out(a)


def matthewson_c(tau):
    """c = x K0(x)/K1(x) at x = sqrt(6)/(3 tau), eq (10) (exponentially scaled, no overflow)."""
    tau = _arr("tau", tau)
    x = np.sqrt(6.0) / (3.0 * tau)
    return _out(x * special.k0e(x) / special.k1e(x))


def matthewson_a_bar(tau, nu_c=0.5, *, warn: bool = True):
    """Matthewson (1981), eq (10): ``a/a0c`` against tau = h/a for a thin bonded layer.

    ``(a_bar)^-3 = 3 pi (1 - nu_c) / (64 tau) [9 + 1/(4 tau^2) + 3/(2 tau^2 (2 + c))]``,
    derived for an incompressible layer (nu_c = 1/2) and tau < 1/2.
    """
    tau = _arr("tau", tau)
    nu_c = np.asarray(nu_c, dtype=float)
    if warn:
        _warn_outside("tau", tau, 0.0, 0.5, "Matthewson eq (10)")
        if np.any(np.abs(nu_c - 0.5) > 1e-9):
            warnings.warn("Matthewson eq (10) assumes nu_c = 0.5", FittedRangeWarning, stacklevel=2)
    c = np.asarray(matthewson_c(tau))
    bracket = 9.0 + 1.0 / (4.0 * tau**2) + 3.0 / (2.0 * tau**2 * (2.0 + c))
    inv3 = 3.0 * np.pi * (1.0 - nu_c) / (64.0 * tau) * bracket  # eq (10)
    return _out(inv3 ** (-1.0 / 3.0))


def matthewson_load(a, R, tau, E_c, nu_c=0.5):
    """Matthewson's load-radius relation, eq (10) first form: W [N] for contact radius a [m]."""
    a, R, tau, E_c = (_arr(n, v) for n, v in (("a", a), ("R", R), ("tau", tau), ("E_c", E_c)))
    c = np.asarray(matthewson_c(tau))
    bracket = 9.0 + 1.0 / (4.0 * tau**2) + 3.0 / (2.0 * tau**2 * (2.0 + c))
    return _out(np.pi * E_c * a**3 / (16.0 * (1.0 + nu_c) * R * tau) * bracket)


def stevanovic_rigid(tau):
    """Stevanovic et al. (2001), eq (11): ``a/a0c = 1 - 1.04 exp(-1.73 tau^0.734)``."""
    tau = _arr("tau", tau)
    return _out(1.0 - 1.04 * np.exp(-1.73 * tau**0.734))


def stevanovic_elastic(H, gamma):
    """Stevanovic et al. (2001), eq (12): ``a/a0s`` with ``gamma = a0c/a0s`` and H = h/a0s."""
    H = _arr("H", H)
    gamma = _arr("gamma", gamma)
    g8 = gamma ** (np.pi / 8.0)
    d = 1.0 + (gamma - 1.0) * (1.0 - np.exp(-g8 * (np.pi * (2.0 * H / (1.0 + gamma)) ** np.pi) ** 0.25))
    a = 1.0 + (gamma - 1.0) * (1.0 - np.exp(-g8 * (np.pi * (H / d) ** np.pi) ** 0.25))  # eq (12)
    return _out(a)


def stevanovic_star(a_num, a0s, a0c, h):
    """Stevanovic's variables, eq (20): ``(a_star, tau_star)``."""
    a_star = (np.asarray(a_num) - a0s) / (a0c - a0s)  # eq (20a)
    tau_star = np.cbrt(np.asarray(h) / np.asarray(a_num) * np.sqrt(a0c / a0s))  # eq (20b)
    return _out(a_star), _out(tau_star)
