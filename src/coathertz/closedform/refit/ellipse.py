r"""Elliptical contacts: the circular refit plus one ellipticity correction per quantity.

Base prediction (eqs 5, 17, 18): each quantity uses the Hertz ellipse of eq (5) with the
equivalent modulus of the *circular* refitted alpha (``alpha_a`` for both semi-axes), at
``H = h/a0s`` with ``a0s = sqrt(r_a0 r_b0)`` of the uncoated contact. Because eq (5)'s factors
depend on Rx/Ry only, the base bars equal the circular bars.

Eq (21) (and any single alpha) cannot reproduce r_b for stiff coatings: the coated contact is
more elongated than either Hertz limit. The correction

.. math::

    \ln\frac{q}{q_\text{base}} = \log_{10}\rho\;\log_{10}E\;w(H)\;S_q(\log_{10}H, \log_{10}E,
    \log_{10}\rho), \qquad w(H) = \frac{4H}{(1+H)^2},\quad \rho = R_x/R_y,

with a Chebyshev surface :math:`S_q` fitted by linear least squares, vanishes for circles
(rho = 1), for E = 1 (Hertz) and in both Hertz limits (w -> 0 as H -> 0 or inf), so the rule
keeps every limit of the circular one.
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.closedform.refit.surface import Surface
from coathertz.errors import CoatHertzError

QUANTITIES = ("r_a", "r_b", "delta", "p")
VARIABLES = ("log10_H", "log10_E", "log10_rho")
BOX = ((-2.0, math.log10(3.0)), (math.log10(0.25), math.log10(4.0)), (0.0, 1.0))
#: circular quantity whose alpha gives the base of each elliptical quantity
BASE = {"r_a": "a", "r_b": "a", "delta": "delta", "p": "p"}


def weight(H) -> np.ndarray:
    H = np.asarray(H, dtype=float)
    return 4.0 * H / (1.0 + H) ** 2


def variables(E, H, rho) -> np.ndarray:
    E, H, rho = (np.asarray(v, dtype=float).ravel() for v in np.broadcast_arrays(E, H, rho))
    if np.any(~((rho >= 1.0) & np.isfinite(rho))):
        raise CoatHertzError("rho = Rx/Ry must be finite and >= 1 (Rx the larger relative radius)")
    return np.vstack([np.log10(H), np.log10(E), np.log10(rho)])


def prefactor(E, H, rho) -> np.ndarray:
    """``log10(rho) log10(E) w(H)``: the factor that makes the correction vanish in the limits."""
    E, H, rho = (np.asarray(v, dtype=float).ravel() for v in np.broadcast_arrays(E, H, rho))
    return np.log10(rho) * np.log10(E) * weight(H)


def log_correction(surfaces: dict[str, Surface], q: str, E, H, rho) -> np.ndarray:
    """``ln(q / q_base)`` of the correction (flattened broadcast shape)."""
    if q not in QUANTITIES:
        raise CoatHertzError(f"quantity must be one of {QUANTITIES}; got {q!r}")
    return prefactor(E, H, rho) * surfaces[q](variables(E, H, rho))
