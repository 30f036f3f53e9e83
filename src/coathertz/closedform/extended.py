"""Extended Hertz theory: the equivalent modulus of a coated body, eqs (17)-(18).

Nomenclature
------------
E1_star
    Extended equivalent modulus of a coated body, eq (17) [Pa].
E_star
    Equivalent modulus of the pair, eq (18): ``1/E* = 1/E1*(body 1) + 1/E1*(body 2)``,
    where an uncoated body contributes its ``(1 - nu^2)/E``.
alpha_a, alpha_delta, alpha_p (alpha_b)
    The parameter alpha for contact radius, approach, maximum pressure (and minor semi-axis).
H
    Dimensionless coating thickness, eq (7a)/(7b).
E
    Modulus ratio Ec*/Es*.

The predictions replace E* of eq (2) by the eq (18) modulus of each quantity in eqs (1)
or (5): ``a = a0(E*_a)``, ``delta = delta0(E*_delta)``, ``p = p0(E*_p)`` and, for an
elliptical contact, ``r_a = r_a0(E*_a)``, ``r_b = r_b0(E*_b)``.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from coathertz.case import ContactCase, refuse_stack
from coathertz.closedform.alpha import (
    E_RANGE,
    ELLIPTICAL_RULE,
    H_RANGE,
    PAPER_RULE,
    AlphaRule,
    Alphas,
    alpha_rigid,
)
from coathertz.errors import CoatHertzError, FittedRangeWarning
from coathertz.materials import Body, coating_constants, lam_kappa, lam_kappa_rigid

#: Exponent k of ``bar = (E*_q / E*_ref)^k`` for each quantity (eqs 1 and 5).
EXPONENT = {"a": -1.0 / 3.0, "b": -1.0 / 3.0, "delta": -2.0 / 3.0, "p": 2.0 / 3.0}

#: Poisson's ratios over which the paper fitted or checked alpha (Section 3 and 4).
NU_C_CHECKED = (0.15, 0.30)
NU_S_FITTED = 0.30
NU_C_RIGID_FITTED = 0.30
NU_TOL = 0.02


def E1_over_Ec(lam, kappa, alpha, H):
    """``E1* / Ec*`` of eq (17), vectorised over every argument.

    ``E1* = Ec* [1 - (lam + kappa + 4 kappa alpha^2 H^2) e^{-2 alpha H} + lam kappa e^{-4 alpha H}]
    / [1 + 4 alpha H kappa e^{-2 alpha H} - lam kappa e^{-4 alpha H}]``. Returns ``inf`` for
    H = 0 on a rigid substrate (lam kappa = 1).
    """
    lam, kappa, alpha, H = (np.asarray(v, dtype=float) for v in (lam, kappa, alpha, H))
    x = alpha * H
    t1 = np.exp(-2.0 * x)
    t2 = t1 * t1
    num = 1.0 - (lam + kappa + 4.0 * kappa * x**2) * t1 + lam * kappa * t2  # eq (17)
    den = 1.0 + 4.0 * x * kappa * t1 - lam * kappa * t2  # eq (17)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = num / den
    r = np.where(den == 0.0, np.inf, r)
    return float(r) if r.ndim == 0 else r


def E1_star(Ec_star, lam, kappa, alpha, H):
    """Extended equivalent modulus of a coated body, eq (17) [Pa]."""
    return np.asarray(Ec_star, dtype=float) * E1_over_Ec(lam, kappa, alpha, H)


def mu_from_ratio(E, nu_c, nu_s):
    """Shear-modulus ratio mu = Gc/Gs from E = Ec*/Es*: ``mu = E (1 - nu_c)/(1 - nu_s)``."""
    return np.asarray(E, dtype=float) * (1.0 - np.asarray(nu_c)) / (1.0 - np.asarray(nu_s))


def constants_from_ratio(E, nu_c, nu_s):
    """lam, kappa of eq (13) from the modulus ratio E = Ec*/Es* and the Poisson ratios."""
    return lam_kappa(mu_from_ratio(E, nu_c, nu_s), nu_c, nu_s)  # eq (13)


def _warn_outside(x, bounds: tuple[float, float], label: str, symbol: str, held: str) -> None:
    """Warn once if any of ``x`` lies outside ``bounds`` (a relative slack of 1e-9 at the ends)."""
    x = np.asarray(x, dtype=float)
    n = int(np.count_nonzero((x < bounds[0] * (1 - 1e-9)) | (x > bounds[1] * (1 + 1e-9))))
    if n:
        warnings.warn(
            f"{label} at {n} point(s) ({symbol} from {x.min():.3g} to {x.max():.3g}); {held}",
            FittedRangeWarning,
            stacklevel=4,
        )


def _warn_range(H, E=None, *, what: str = "") -> None:
    _warn_outside(
        H, H_RANGE,
        f"{what}H outside the fitted range [{H_RANGE[0]:g}, {H_RANGE[1]:g}] of the Appendix A alpha curves",
        "H", "alpha is held at its end value there",
    )
    if E is not None:
        _warn_outside(
            E, E_RANGE, f"{what}modulus ratio E = Ec*/Es* outside the fitted range [1/4, 4] of eq (19)/(21)",
            "E", "alpha is held at its value at the end of the range",
        )


def _warn_nu(nu_c: float, nu_s: float | None) -> None:
    if nu_s is None:  # rigid substrate
        if abs(nu_c - NU_C_RIGID_FITTED) > NU_TOL:
            warnings.warn(
                f"nu_c = {nu_c:g}: the rigid-substrate alpha curves were fitted at nu_c = 0.3 only "
                "(paper, Section 4; Poisson's ratio matters strongly there, figure 7)",
                FittedRangeWarning,
                stacklevel=3,
            )
        return
    lo, hi = NU_C_CHECKED
    if not (lo - NU_TOL <= nu_c <= hi + NU_TOL) or abs(nu_s - NU_S_FITTED) > NU_TOL:
        warnings.warn(
            f"nu_c = {nu_c:g}, nu_s = {nu_s:g}: alpha was fitted at nu_c = nu_s = 0.3 and checked "
            f"for nu_c in [{lo}, {hi}] with nu_s = 0.3 (paper, Section 3)",
            FittedRangeWarning,
            stacklevel=3,
        )


@dataclass(frozen=True)
class ExtendedPrediction:
    """Extended-Hertz prediction of one case (SI units).

    ``alpha``, ``E1_star`` (per coated body, in body order) and ``E_star`` are keyed by
    quantity (``a``, ``delta``, ``p`` and, for ellipses, ``b``).
    """

    delta: float
    a: float
    p0: float
    r_a: float
    r_b: float
    H: tuple[float, ...]
    E: tuple[float, ...]
    alpha: dict[str, tuple[float, ...]] = field(default_factory=dict)
    E1_star: dict[str, tuple[float, ...]] = field(default_factory=dict)
    E_star: dict[str, float] = field(default_factory=dict)
    rule: str = ""


def _body_alpha(case: ContactCase, body: Body, q: str, rule: AlphaRule, H: float) -> float:
    if hasattr(rule, "body_alpha"):  # a rule that needs the whole body (coathertz.closedform.refit)
        return float(rule.body_alpha(body, q, H))
    if body.material.is_rigid:
        return _alpha_rigid_of(q, float(H))
    E = float(body.modulus_ratio)
    try:
        return _alpha_of(rule, q, E, float(H))
    except TypeError:  # a rule that cannot be hashed: not memoised
        return float(rule.alpha(q, E, H))


# alpha, E1* of one (rule, quantity, E, H): pure functions of their arguments, asked for again
# and again by the studies (the same H and E recur across cases, quantities and figures);
# memoised, the numbers unchanged


@functools.lru_cache(maxsize=1 << 16)
def _alpha_of(rule: AlphaRule, q: str, E: float, H: float) -> float:
    return float(rule.alpha(q, E, H))


@functools.lru_cache(maxsize=1 << 14)
def _alpha_rigid_of(q: str, H: float) -> float:
    return float(alpha_rigid(q, H))


@functools.lru_cache(maxsize=1 << 16)
def _E1_of(Ec_star: float, lam: float, kappa: float, alpha: float, H: float) -> float:
    return float(E1_star(Ec_star, lam, kappa, alpha, H))


def _body_compliance(body: Body, q: str, alpha: float, H: float) -> tuple[float, float]:
    """(1/E1*_q, E1*_q) of one coated body, eq (17)."""
    c = body.coating
    k = coating_constants(c.material, body.material)
    e1 = _E1_of(float(c.material.E_star), float(k.lam), float(k.kappa), float(alpha), float(H))
    return (0.0 if math.isinf(e1) else 1.0 / e1), e1


def refuse_frictionless(case: ContactCase, interface: str = "bonded") -> None:
    """Raise :class:`~coathertz.errors.CoatHertzError` when ``case`` (or the ``interface`` asked
    for) has a coating resting on its substrate without friction: eq (13) and every alpha curve,
    the paper's and the refitted ones, are for a bonded layer, and the bonded answer differs from
    the exact frictionless one by several per cent (E = 0.2, H = 0.3: delta -6.8 %, a -4.6 %, p0 +11.1 %)."""
    if case.is_coated and case.interface_for(interface) == "frictionless":
        raise CoatHertzError(
            "closed form: the extended Hertz theory (eqs 13-21) and the refitted alpha are for a "
            "coating bonded to its substrate; this case's interface is frictionless, which the closed "
            "form does not model: solve it with `coathertz axisym` (exact, circular) or `coathertz fft` "
            "(any shape), which read the interface from the case file or --interface frictionless")


def predict(
    case: ContactCase,
    alphas: Alphas | None = None,
    rule: AlphaRule | None = None,
    *,
    warn: bool = True,
) -> ExtendedPrediction:
    """Extended-Hertz prediction of ``case``: eqs (1)/(5) with eqs (17)-(18).

    Parameters
    ----------
    case
        The contact case; any body may be coated (eq 17 applied to each, eq 18 sums them),
        the indenter may be elastic, a substrate may be rigid.
    alphas
        Explicit alpha values (as read from the paper's figures in Section 6); if None, alpha
        comes from the Appendix A curves through ``rule`` (elastic substrate) or the
        rigid-substrate curves.
    rule
        Alpha rule for elastic substrates; default eq (19)
        (:data:`~coathertz.closedform.alpha.PAPER_RULE`) for circular contacts and eq (21)
        (:data:`~coathertz.closedform.alpha.ELLIPTICAL_RULE`) for elliptical ones.
    warn
        Issue :class:`~coathertz.errors.FittedRangeWarning` outside the fitted ranges.
    """
    refuse_stack(case, "closed form")  # eqs (17)-(19) know one coating
    refuse_frictionless(case)
    circular = case.is_circular
    if rule is None:
        rule = PAPER_RULE if circular else ELLIPTICAL_RULE
    quantities = ("a", "delta", "p") if circular else ("a", "b", "delta", "p")
    coated = [b for b in (case.body1, case.body2) if b.is_coated]
    Hs = tuple(case.H_of(b) for b in coated)
    Es = tuple(0.0 if b.material.is_rigid else b.modulus_ratio for b in coated)
    if warn and alphas is None:
        for b, H, E in zip(coated, Hs, Es, strict=True):
            if b.material.is_rigid:
                _warn_range(H, what="rigid substrate: ")
                _warn_nu(b.coating.material.nu, None)
                if not circular:
                    warnings.warn(
                        "the rigid-substrate alpha curves were fitted for circular contacts only",
                        FittedRangeWarning,
                        stacklevel=2,
                    )
            else:
                _warn_range(H, E)
                _warn_nu(b.coating.material.nu, b.material.nu)
    alpha: dict[str, tuple[float, ...]] = {}
    e1s: dict[str, tuple[float, ...]] = {}
    e_star: dict[str, float] = {}
    for q in quantities:
        comp = [b.material.compliance for b in (case.body1, case.body2) if not b.is_coated]
        aq, eq = [], []
        for b, H in zip(coated, Hs, strict=True):
            a_val = alphas.get(q) if alphas is not None else _body_alpha(case, b, q, rule, H)
            c_val, e_val = _body_compliance(b, q, a_val, H)
            comp.append(c_val)
            aq.append(a_val)
            eq.append(e_val)
        total = math.fsum(comp)
        e_star[q] = math.inf if total == 0 else 1.0 / total  # eq (18)
        alpha[q], e1s[q] = tuple(aq), tuple(eq)
    h = {q: case.hertz(e_star[q]) for q in quantities}
    r_a = float(h["a"].r_a0)
    r_b = float(h["b"].r_b0) if "b" in h else float(h["a"].r_b0)
    return ExtendedPrediction(
        delta=float(h["delta"].delta0),
        a=math.sqrt(r_a * r_b),
        p0=float(h["p"].p0),
        r_a=r_a,
        r_b=r_b,
        H=Hs,
        E=Es,
        alpha=alpha,
        E1_star=e1s,
        E_star=e_star,
        rule="explicit" if alphas is not None else ("rigid" if case.rigid_substrate else rule.name),
    )


def predict_bar(
    quantity: str,
    E,
    H,
    nu_c=0.3,
    nu_s=0.3,
    *,
    rigid_substrate: bool = False,
    rule: AlphaRule = PAPER_RULE,
    alpha=None,
    warn: bool = True,
):
    """Vectorised prediction of a rigid sphere on a coated half-space, in the paper's bars.

    Elastic substrate: ``a_bar = a/a0s = (Es*/E1*)^(1/3)``, ``delta_bar = (Es*/E1*)^(2/3)``,
    ``p_bar = (E1*/Es*)^(2/3)`` (eqs 1, 17, 18 with a rigid indenter). Rigid substrate: the
    same with ``Ec*`` as reference (eq 7b) and ``E`` ignored.

    Parameters
    ----------
    quantity
        ``a``, ``delta`` or ``p``.
    E, H, nu_c, nu_s
        Modulus ratio Ec*/Es*, dimensionless thickness and Poisson's ratios (broadcast).
    alpha
        Explicit alpha (broadcast); default from ``rule`` / the rigid curves.
    """
    if quantity not in ("a", "delta", "p"):
        raise CoatHertzError(f"quantity must be a, delta or p; got {quantity!r}")
    H = np.asarray(H, dtype=float)
    if np.any(~(H >= 0)):
        raise CoatHertzError("H must satisfy H >= 0")
    nu_c = np.asarray(nu_c, dtype=float)
    if rigid_substrate:
        lam, kappa = lam_kappa_rigid(nu_c)  # Section 4
        if alpha is None:
            if warn:
                _warn_range(H, what="rigid substrate: ")
            alpha = alpha_rigid(quantity, H)
        ratio = E1_over_Ec(lam, kappa, alpha, H)  # E1*/Ec*
    else:
        E = np.asarray(E, dtype=float)
        lam, kappa = constants_from_ratio(E, nu_c, np.asarray(nu_s, dtype=float))
        if alpha is None:
            if warn:
                _warn_range(H, E)
            alpha = rule.alpha(quantity, E, H)
        ratio = E * E1_over_Ec(lam, kappa, alpha, H)  # E1*/Es*
    return np.asarray(ratio) ** EXPONENT[quantity]


def _first_root(f_grid: np.ndarray, x_grid: np.ndarray, f, iters: int = 100) -> np.ndarray:
    """Vectorised: first sign change of f along axis -1 of f_grid, refined by bisection until
    every bracket holds two adjacent floats (at most ``iters`` halvings; about 50 from a scan
    cell, where 100 were run before: further halvings leave such a bracket as it is)."""
    s = np.sign(f_grid)
    change = (s[..., :-1] * s[..., 1:]) <= 0
    has = change.any(axis=-1)
    k = np.argmax(change, axis=-1)
    lo = np.where(has, x_grid[k], np.nan)
    hi = np.where(has, x_grid[np.minimum(k + 1, len(x_grid) - 1)], np.nan)
    f_lo = f(lo)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if np.all((mid == lo) | (mid == hi) | np.isnan(mid)):
            break
        f_mid = f(mid)
        same = np.sign(f_mid) == np.sign(f_lo)
        lo = np.where(same, mid, lo)
        f_lo = np.where(same, f_mid, f_lo)
        hi = np.where(same, hi, mid)
    return 0.5 * (lo + hi)


def invert_alpha(
    quantity: str,
    bar,
    E,
    H,
    nu_c=0.3,
    nu_s=0.3,
    *,
    rigid_substrate: bool = False,
    bounds: tuple[float, float] = (1e-3, 1e3),
    n_scan: int = 400,
):
    """Find the alpha with which eqs (1), (17), (18) reproduce a numerical bar value (fig 4).

    Vectorised over ``bar, E, H`` (broadcast). The predicted bar is scanned on a log grid of
    alpha in ``bounds``; the smallest alpha at which it crosses the target is refined by
    bisection. Returns NaN where no alpha in ``bounds`` reproduces the value (the
    numerical result lies outside what eq (17) can represent).
    """
    if quantity not in ("a", "delta", "p"):
        raise CoatHertzError(f"quantity must be a, delta or p; got {quantity!r}")
    arrays = (np.asarray(v, dtype=float) for v in (bar, E, H, nu_c, nu_s))
    bar, E, H, nu_c, nu_s = np.broadcast_arrays(*arrays)
    if np.any(~(bar > 0)):
        raise CoatHertzError("bar values must be > 0")
    lb = np.log(bar)

    def resid(alpha):
        val = predict_bar(quantity, E[..., None] if alpha.ndim > E.ndim else E,
                          H[..., None] if alpha.ndim > H.ndim else H,
                          nu_c[..., None] if alpha.ndim > nu_c.ndim else nu_c,
                          nu_s[..., None] if alpha.ndim > nu_s.ndim else nu_s,
                          rigid_substrate=rigid_substrate, alpha=alpha, warn=False)
        target = lb[..., None] if alpha.ndim > lb.ndim else lb
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.log(val) - target

    grid = np.geomspace(bounds[0], bounds[1], n_scan)
    f_grid = resid(np.broadcast_to(grid, (*bar.shape, n_scan)))
    out = _first_root(f_grid, grid, resid)
    return float(out) if out.ndim == 0 else out
