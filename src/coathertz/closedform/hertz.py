"""Classical Hertz theory: circular (eqs 1a-d) and elliptical (eqs 3-6) point contacts.

Pure, vectorised functions of the load ``W`` [N], the radii [m] and the equivalent
modulus ``E_star`` [Pa] of eq (2). A rigid pair (``E_star = inf``) gives ``a0 = 0``.

Nomenclature
------------
a0, delta0, p0
    Contact radius, approach, maximum pressure of eq (1).
r_a0, r_b0, zeta, e
    Semi-axes (major, minor), their ratio ``zeta = r_b0 / r_a0`` and the eccentricity
    ``e = sqrt(1 - zeta^2)`` of eq (4)-(5).
F0, F1, F2
    Elliptical correction factors of eq (6).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from coathertz.errors import CoatHertzError

ArrayLike = float | np.ndarray


@dataclass(frozen=True)
class HertzCircular:
    """Hertz solution of a circular contact, eq (1)."""

    a0: ArrayLike
    delta0: ArrayLike
    p0: ArrayLike


@dataclass(frozen=True)
class HertzElliptical:
    """Hertz solution of an elliptical contact, eqs (4)-(6)."""

    r_a0: ArrayLike
    r_b0: ArrayLike
    a0: ArrayLike
    delta0: ArrayLike
    p0: ArrayLike
    zeta: ArrayLike
    F0: ArrayLike
    F1: ArrayLike
    F2: ArrayLike


def _check_positive_array(name: str, x: ArrayLike, *, allow_inf: bool = False) -> np.ndarray:
    arr = np.asarray(x, dtype=float)
    bad = ~(arr > 0) | (np.isinf(arr) & (not allow_inf))
    if np.any(bad):
        rng = f"0 < {name} <= inf" if allow_inf else f"0 < {name} < inf"
        raise CoatHertzError(f"{name} must satisfy {rng}, got {arr[bad].ravel()[:3]!r}")
    return arr


def _out(x: np.ndarray) -> ArrayLike:
    return float(x) if np.ndim(x) == 0 else x


_SCALAR_TYPES = (float, int, np.floating, np.integer)


def _scalars_ok(W, R: ArrayLike, E_star) -> bool:
    """True if ``W``, ``R``, ``E_star`` are plain numbers that pass the checks of
    :func:`_check_positive_array` (then the scalar fast paths apply; anything else takes the
    array path, which also words the errors)."""
    if not (type(W) is float and type(R) is float and type(E_star) is float):  # the usual case
        for x in (W, R, E_star):
            if not isinstance(x, _SCALAR_TYPES) or isinstance(x, bool):
                return False
    return 0.0 < W < math.inf and 0.0 < R < math.inf and 0.0 < E_star


def _circular_scalar(W, R, E_star) -> tuple[float, float, float] | None:
    """Eqs (1a)-(1c) for one case, ``(a0, delta0, p0)``, or ``None`` to take the array path.

    The same operations as the array path (``x**2`` of an array is ``x * x`` in numpy, and the
    cube roots are numpy's), so the numbers are the same to the last bit, at a fraction of
    the cost (the studies call this a few thousand times per run).
    """
    if not _scalars_ok(W, R, E_star):
        return None
    W, R, E_star = float(W), float(R), float(E_star)
    try:
        a0 = 3.0 * W * R / (4.0 * E_star)  # eq (1a)
        delta0 = 9.0 * (W * W) / (16.0 * R * (E_star * E_star))  # eq (1b)
        p0 = 6.0 * W * (E_star * E_star) / (math.pi**3 * (R * R))  # eq (1c)
    except ZeroDivisionError:  # an underflowed denominator: the array path gives inf
        return None
    return float(np.cbrt(a0)), float(np.cbrt(delta0)), float(np.cbrt(p0))


def combined_modulus(*compliances: float) -> float:
    """E* of eq (2) from the bodies' compliances (1 - nu_i^2)/E_i (0 for a rigid body)."""
    total = math.fsum(compliances)
    if total < 0:
        raise CoatHertzError(f"compliances must be >= 0, got {compliances!r}")
    return math.inf if total == 0 else 1.0 / total


def hertz_circular(W: ArrayLike, R: ArrayLike, E_star: ArrayLike) -> HertzCircular:
    """Hertz circular point contact, eqs (1a)-(1c).

    Parameters
    ----------
    W
        Normal load [N] (> 0).
    R
        Equivalent radius [m], ``1/R = 1/R1 + 1/R2``.
    E_star
        Equivalent modulus [Pa] of eq (2) (``inf`` for two rigid bodies).
    """
    fast = _circular_scalar(W, R, E_star)
    if fast is not None:
        return HertzCircular(*fast)
    W = _check_positive_array("W", W)
    R = _check_positive_array("R", R)
    E_star = _check_positive_array("E_star", E_star, allow_inf=True)
    with np.errstate(divide="ignore"):
        a0 = np.cbrt(3.0 * W * R / (4.0 * E_star))  # eq (1a)
        delta0 = np.cbrt(9.0 * W**2 / (16.0 * R * E_star**2))  # eq (1b)
        p0 = np.cbrt(6.0 * W * E_star**2 / (math.pi**3 * R**2))  # eq (1c)
    return HertzCircular(_out(a0), _out(delta0), _out(p0))


def pressure_elliptical(x: ArrayLike, y: ArrayLike, r_a0: float, r_b0: float, p0: float) -> np.ndarray:
    """Hertz pressure on an ellipse with semi-axes r_a0 (along x), r_b0 (along y); eq (5e)."""
    s = 1.0 - (np.asarray(x) / r_a0) ** 2 - (np.asarray(y) / r_b0) ** 2
    return p0 * np.sqrt(np.clip(s, 0.0, None))


def relative_radii(
    R1x: float, R1y: float, R2x: float, R2y: float, theta: float = 0.0
) -> tuple[float, float]:
    """Principal relative radii ``(Rx, Ry)`` with ``Rx >= Ry``, eqs (3a)-(3b).

    ``theta`` is the angle between the x axes of the two bodies' principal curvatures.
    A flat surface has infinite radii. Raises if the gap is not positive definite
    (both relative curvatures must be > 0).
    """
    k1x, k1y, k2x, k2y = (0.0 if math.isinf(r) else 1.0 / r for r in (R1x, R1y, R2x, R2y))
    S = k1x + k1y + k2x + k2y  # eq (3a): 1/Rx + 1/Ry
    d1, d2 = k1x - k1y, k2x - k2y
    D2 = d1**2 + d2**2 + 2.0 * d1 * d2 * math.cos(2.0 * theta)  # eq (3b)
    D = math.sqrt(max(D2, 0.0))
    inv_Ry, inv_Rx = 0.5 * (S + D), 0.5 * (S - D)
    if inv_Rx <= 0.0 or inv_Ry <= 0.0:
        raise CoatHertzError(
            "the two surfaces do not form a point contact: the relative curvatures "
            f"1/Rx = {inv_Rx:.4g} 1/m and 1/Ry = {inv_Ry:.4g} 1/m must both be > 0"
        )
    return 1.0 / inv_Rx, 1.0 / inv_Ry


def _carlson(zeta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """K(e) = R_F(0, zeta^2, 1) and R_D(0, zeta^2, 1), free of cancellation at zeta -> 1."""
    z2 = zeta**2
    zero = np.zeros_like(z2)
    one = np.ones_like(z2)
    return special.elliprf(zero, z2, one), special.elliprd(zero, z2, one)


def radius_ratio(zeta: ArrayLike) -> ArrayLike:
    """Rx/Ry as a function of zeta = r_b0/r_a0, eq (4).

    Written with Carlson's integrals, using K - E = (m/3) R_D(0, 1-m, 1), m = e^2,
    so that ``(E/zeta^2 - K)/(K - E) = (3 K / R_D - 1) / zeta^2`` has no 0/0 at zeta = 1.
    """
    zeta = np.asarray(zeta, dtype=float)
    K, RD = _carlson(zeta)
    return _out((3.0 * K / RD - 1.0) / zeta**2)


def solve_zeta(Rx_over_Ry: ArrayLike) -> ArrayLike:
    """Invert eq (4) for zeta in (0, 1] given Rx/Ry >= 1 (vectorised bisection in log zeta).

    Accurate to ~1e-14 relative for Rx/Ry from 1 to 1e8.
    """
    q = np.asarray(Rx_over_Ry, dtype=float)
    if np.any(~(q >= 1.0)) or np.any(np.isinf(q)):
        raise CoatHertzError(f"Rx/Ry must satisfy 1 <= Rx/Ry < inf (Rx major), got {q}")
    if np.all(q == 1.0):  # circular: skip the bisection (studies call this per case)
        return _out(np.ones(q.shape))
    if q.ndim == 0:  # one case at a time (studies, figures): the same few ratios recur
        return _solve_zeta_scalar(float(q))
    return _bisect_zeta(q)


@functools.lru_cache(maxsize=4096)
def _solve_zeta_scalar(q: float) -> float:
    """:func:`solve_zeta` of one ratio, memoised (the result is a pure function of ``q``)."""
    return float(_bisect_zeta(np.asarray(q)))


def _bisect_zeta(q: np.ndarray) -> ArrayLike:
    """The vectorised bisection of :func:`solve_zeta` (80 halvings of [1e-12, 1] in log zeta)."""
    lo = np.full(q.shape, math.log(1e-12))
    hi = np.zeros(q.shape)
    target = np.log(q)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        g = np.log(radius_ratio(np.exp(mid)))  # decreasing in zeta
        above = g > target
        lo = np.where(above, mid, lo)
        hi = np.where(above, hi, mid)
    zeta = np.exp(0.5 * (lo + hi))
    zeta = np.where(q == 1.0, 1.0, zeta)
    return _out(zeta)


def elliptic_factors(zeta: ArrayLike) -> tuple[ArrayLike, ArrayLike, ArrayLike]:
    """F0, F1, F2 of eqs (6a)-(6c) for semi-axis ratio zeta (cancellation-free form)."""
    zeta = np.asarray(zeta, dtype=float)
    K, RD = _carlson(zeta)
    # eq (6a): F0^3 = 4/(pi e^2) sqrt[(E/zeta^2 - K)(K - E)]
    #        = (4/pi) sqrt[(K - R_D/3) R_D / (3 zeta^2)]
    F0 = np.cbrt(4.0 / math.pi * np.sqrt((K - RD / 3.0) * RD / (3.0 * zeta**2)))
    F1 = F0 * np.sqrt(zeta)  # eq (6b)
    F2 = 2.0 / math.pi * np.sqrt(zeta) * K / F1  # eq (6c)
    return _out(F0), _out(F1), _out(F2)


def hertz_elliptical(W: ArrayLike, Rx: ArrayLike, Ry: ArrayLike, E_star: ArrayLike) -> HertzElliptical:
    """Hertz elliptical point contact, eqs (4)-(6), with ``R = sqrt(Rx Ry)``.

    ``Rx`` and ``Ry`` are the principal relative radii; if ``Rx < Ry`` they are swapped
    so that ``r_a0`` is always the major semi-axis (oriented along the larger radius).
    """
    if _scalars_ok(W, 1.0, E_star) and _scalars_ok(Rx, Ry, 1.0) and Rx < math.inf:
        # one case (the studies call this thousands of times): the shape factors of these
        # radii memoised, the load part as in hertz_circular; the same numbers as below
        zeta, F0, F1, F2, R = _shape(float(max(Rx, Ry)), float(min(Rx, Ry)))
        c = _circular_scalar(W, R, E_star)
        if c is not None:
            a0c, delta0c, p0c = c
            r_a0 = F0 * a0c  # eq (5a)
            return HertzElliptical(r_a0, r_a0 * zeta, F1 * a0c, F2 * delta0c, p0c / (F1 * F1),
                                   zeta, F0, F1, F2)
    Rx = _check_positive_array("Rx", Rx)
    Ry = _check_positive_array("Ry", Ry)
    Rmaj, Rmin = np.maximum(Rx, Ry), np.minimum(Rx, Ry)
    zeta = np.asarray(solve_zeta(Rmaj / Rmin))
    F0, F1, F2 = elliptic_factors(zeta)
    R = np.sqrt(Rmaj * Rmin)
    c = hertz_circular(W, R, E_star)
    r_a0 = F0 * np.asarray(c.a0)  # eq (5a)
    r_b0 = r_a0 * zeta  # eq (5a)
    a0 = F1 * np.asarray(c.a0)  # eq (5b)
    delta0 = F2 * np.asarray(c.delta0)  # eq (5c)
    p0 = np.asarray(c.p0) / np.asarray(F1) ** 2  # eq (5d)
    return HertzElliptical(*(_out(np.asarray(v)) for v in (r_a0, r_b0, a0, delta0, p0, zeta, F0, F1, F2)))


@functools.lru_cache(maxsize=4096)
def _shape(Rmaj: float, Rmin: float) -> tuple[float, float, float, float, float]:
    """``(zeta, F0, F1, F2, R)`` of the relative radii ``Rmaj >= Rmin``, eqs (4), (6), as
    :func:`hertz_elliptical`'s array path computes them (memoised: few geometries recur)."""
    zeta = np.asarray(solve_zeta(np.float64(Rmaj) / np.float64(Rmin)))
    F0, F1, F2 = elliptic_factors(zeta)
    R = np.sqrt(np.float64(Rmaj) * np.float64(Rmin))
    return float(zeta), float(F0), float(F1), float(F2), float(R)


def hertz_axis_stresses(z: ArrayLike, a0: float, p0: float, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """Hertz stresses on the axis r = 0 below a circular contact (Johnson 1985, eq 3.45).

    Returns ``(sigma_r, sigma_z)`` [Pa] (``sigma_theta = sigma_r`` on the axis),
    compressive negative, at depths ``z >= 0``.
    """
    z = np.asarray(z, dtype=float)
    zeta = z / a0
    with np.errstate(divide="ignore", invalid="ignore"):
        atan_term = np.where(zeta > 0, zeta * np.arctan2(1.0, zeta), 0.0)
    sigma_z = -p0 / (1.0 + zeta**2)
    sigma_r = p0 * (-(1.0 + nu) * (1.0 - atan_term) + 0.5 / (1.0 + zeta**2))
    return sigma_r, sigma_z
