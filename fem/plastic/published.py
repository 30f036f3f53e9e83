r"""Published fits of elastic-plastic spherical contact: Kogut & Etsion (2002), Jackson & Green (2005).

Both are FE fits for a *deformable sphere on a rigid flat* (elastic-perfectly-plastic, no
hardening); the FE model here is a rigid sphere on a plastic half-space, so they are a reference
of the same regime, not of the identical problem (the difference is largest where the contact is
deep, a/R > ~0.05).

Kogut & Etsion (2002), J. Appl. Mech. 69, 657-662
    ``K = 0.454 + 0.41 nu``, hardness ``H = 2.8 Y``, critical interference
    ``delta_c = (pi K H / (2 E*))^2 R``, ``P_c = (4/3) (R / E*)^2 (pi K H / 2)^3``,
    ``A_c = pi R delta_c``; with ``x = delta / delta_c``:
    ``P / P_c = 1.03 x^1.425``, ``A / A_c = 0.93 x^1.136`` for ``1 <= x <= 6`` and
    ``P / P_c = 1.40 x^1.263``, ``A / A_c = 0.94 x^1.146`` for ``6 <= x <= 110``.
    Hence ``p_mean = P / A = (2/3) K H (c_P / c_A) x^(e_P - e_A)``.
Jackson & Green (2005), J. Tribol. 127, 343-354 (eqs 9, 10, 17, 18, 21 as numbered there)
    ``C = 1.295 exp(0.736 nu)``, ``delta_c = (pi C Y / (2 E*))^2 R``,
    ``P_c = (4/3) (R / E*)^2 (C pi Y / 2)^3``; for ``x >= 1.9``:
    ``A = pi R delta (x / 1.9)^B``, ``B = 0.14 exp(23 Y / E*)``;
    ``H_G / Y = 2.84 [1 - exp(-0.82 (a / R)^(-0.7))]`` with ``a = sqrt(A / pi)``;
    ``P / P_c = exp(-x^(5/12) / 4) x^(3/2) + (4 H_G / (C Y)) [1 - exp(-x^(5/9) / 25)] x``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coathertz.errors import CoatHertzError


@dataclass(frozen=True)
class SphereFit:
    """Load, contact radius and mean pressure of a fit at one interference."""

    P: float  # load [N]
    a: float  # contact radius [m]
    p_mean: float  # P / (pi a^2) [Pa]
    delta_c: float  # the fit's critical interference [m]


def _check(E_star: float, Y: float, nu: float, R: float, delta: float) -> None:
    for name, v in (("E_star", E_star), ("Y", Y), ("R", R), ("delta", delta)):
        if not (math.isfinite(v) and v > 0):
            raise CoatHertzError(f"published fit: {name} must be > 0, got {v!r}")
    if not 0.0 <= nu < 0.5:
        raise CoatHertzError(f"published fit: nu must be in [0, 0.5), got {nu!r}")


def kogut_etsion_critical(E_star: float, Y: float, nu: float, R: float) -> tuple[float, float]:
    """Kogut & Etsion's critical interference ``delta_c`` [m] and load ``P_c`` [N]."""
    _check(E_star, Y, nu, R, 1.0)
    K, H = 0.454 + 0.41 * nu, 2.8 * Y
    delta_c = (math.pi * K * H / (2.0 * E_star)) ** 2 * R
    P_c = 4.0 / 3.0 * (R / E_star) ** 2 * (math.pi * K * H / 2.0) ** 3
    return delta_c, P_c


def kogut_etsion(delta: float, E_star: float, Y: float, nu: float, R: float) -> SphereFit:
    """Kogut & Etsion (2002) at interference ``delta`` [m] (valid for ``1 <= delta / delta_c <= 110``;
    outside, :class:`~coathertz.errors.CoatHertzError`)."""
    _check(E_star, Y, nu, R, delta)
    dc, Pc = kogut_etsion_critical(E_star, Y, nu, R)
    x = delta / dc
    if not 1.0 <= x <= 110.0:
        raise CoatHertzError(f"Kogut & Etsion (2002): delta/delta_c must be in [1, 110], got {x:.4g}")
    cP, eP, cA, eA = (1.03, 1.425, 0.93, 1.136) if x <= 6.0 else (1.40, 1.263, 0.94, 1.146)
    P = cP * x**eP * Pc
    A = cA * x**eA * math.pi * R * dc
    return SphereFit(P, math.sqrt(A / math.pi), P / A, dc)


def jackson_green(delta: float, E_star: float, Y: float, nu: float, R: float) -> SphereFit:
    """Jackson & Green (2005) at interference ``delta`` [m] (area fit valid for
    ``delta / delta_c >= 1.9``; below, :class:`~coathertz.errors.CoatHertzError`)."""
    _check(E_star, Y, nu, R, delta)
    C = 1.295 * math.exp(0.736 * nu)
    dc = (math.pi * C * Y / (2.0 * E_star)) ** 2 * R
    Pc = 4.0 / 3.0 * (R / E_star) ** 2 * (C * math.pi * Y / 2.0) ** 3
    x = delta / dc
    if x < 1.9:
        raise CoatHertzError(f"Jackson & Green (2005): delta/delta_c must be >= 1.9, got {x:.4g}")
    B = 0.14 * math.exp(23.0 * Y / E_star)
    A = math.pi * R * delta * (x / 1.9) ** B
    a = math.sqrt(A / math.pi)
    HG = 2.84 * Y * (1.0 - math.exp(-0.82 * (a / R) ** -0.7))
    elastic = math.exp(-0.25 * x ** (5.0 / 12.0)) * x**1.5
    plastic = 4.0 * HG / (C * Y) * (1.0 - math.exp(-(x ** (5.0 / 9.0)) / 25.0)) * x
    P = (elastic + plastic) * Pc
    return SphereFit(P, a, P / A, dc)
