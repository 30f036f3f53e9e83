"""The parameter alpha of the extended Hertz theory: Appendix A fits and eqs (19), (21).

Appendix A gives representative curves alpha_q(H) for q in {a, delta, p}:

* elastic substrate at modulus ratios E = Ec*/Es* = 3 and 1/3 (figure 5),
* rigid substrate (figure 9, nu_c = 0.3).

Eq (19) maps the E = 1/3 and E = 3 curves to other E for alpha_p (all E) and alpha_delta
(E <= 1). The copy of the paper lacks alpha_a(E) everywhere and alpha_delta(E) for E > 1;
docs/paper-notes.md prescribes the *representative* rule (alpha(E) = alpha(3) for E >= 1 and
alpha(1/3) for E < 1). Both the printed and the assumed parts are collected in an
:class:`AlphaRule`, so a study can swap the assumption (e.g. :data:`EQ21_RULE`, which borrows
eq (21)'s rows for the missing parts) and report its effect.

The pieces are used exactly as printed (first interval closed, others half-open on the
left), including their jumps at breakpoints (:func:`breakpoint_jumps` lists them). Outside
the fitted ranges (H in [0.01, 3], E in [1/4, 4]) alpha is *held at its end value*: linear
extrapolation of the end pieces turns negative (e.g. alpha_a(3) = -0.5 H + 2.8 at H > 5.6),
which eq (17) cannot take. The callers in :mod:`coathertz.closedform.extended` issue a
:class:`~coathertz.errors.FittedRangeWarning` whenever this happens.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from coathertz.errors import CoatHertzError

H_RANGE = (0.01, 3.0)  # fitted range of every Appendix A curve
E_RANGE = (0.25, 4.0)  # modulus ratios covered by eqs (19) and (21)
QUANTITIES = ("a", "delta", "p")

Piece = tuple[float, Callable[[np.ndarray], np.ndarray]]


def _piecewise(H: np.ndarray, breaks: Sequence[float], funcs: Sequence[Callable]) -> np.ndarray:
    """Evaluate pieces: funcs[0] on H <= breaks[0], funcs[k] on breaks[k-1] < H <= breaks[k];
    H is clipped to the fitted range first (alpha held at its end values)."""
    H = np.asarray(H, dtype=float)
    if H.ndim == 0 and H > 0:  # one H (a case of a study): its piece alone, the same numbers
        h = min(max(float(H), H_RANGE[0]), H_RANGE[1])  # np.clip
        return np.array(funcs[bisect.bisect_left(breaks, h)](np.array([h]))[0])
    if np.any(~(H > 0)):
        raise CoatHertzError(f"H must be > 0 to evaluate the alpha curves, got min {np.min(H)!r}")
    H = np.clip(H, *H_RANGE)
    idx = np.searchsorted(np.asarray(breaks), H, side="left")
    out = np.empty_like(H)
    for k, f in enumerate(funcs):
        m = idx == k
        if np.any(m):
            out[m] = f(H[m])
    return out


# --- Appendix A, elastic substrate, E = 3 (figure 5) -----------------------------------
def alpha_a_3(H):
    """alpha_a(3), Appendix A."""
    return _piecewise(H, [0.05, 0.5, 1.5], [
        lambda H: np.full_like(H, 5.51),
        lambda H: -34.22 * H**3 + 43.67 * H**2 - 20.316 * H + 6.331,
        lambda H: 0.157 * H**2 - 1.08 * H + 3.32,
        lambda H: -0.5 * H + 2.8,
    ])


def alpha_delta_3(H):
    """alpha_delta(3), Appendix A."""
    return _piecewise(H, [0.05, 0.25, 0.5, 0.9], [
        lambda H: -0.252 * np.log(H) + 0.389,
        lambda H: -49.446 * H**3 + 28.492 * H**2 - 5.106 * H + 1.330,
        lambda H: -0.683 * H**2 + 0.637 * H + 0.948,
        lambda H: -0.287 * H**2 + 0.211 * H + 1.064,
        lambda H: 0.0466 * H**2 - 0.382 * H + 1.328,
    ])


def alpha_p_3(H):
    """alpha_p(3), Appendix A."""
    return _piecewise(H, [0.05, 0.33, 0.75, 1.2], [
        lambda H: 1.047 * H + 1.654,
        lambda H: 34.734 * H**3 - 8.256 * H**2 - 1.163 * H + 1.776,
        lambda H: 3.661 * H**3 - 10.456 * H**2 + 9.482 * H - 0.410,
        lambda H: -0.648 * H**2 + 0.882 * H + 2.073,
        lambda H: 0.0854 * H**2 - 0.779 * H + 3.02,
    ])


# --- Appendix A, elastic substrate, E = 1/3 (figure 5) ---------------------------------
def alpha_a_third(H):
    """alpha_a(1/3), Appendix A."""
    return _piecewise(H, [0.1, 0.3], [
        lambda H: 197.97 * H**2 - 40.013 * H + 5.624,
        lambda H: 1.853 * H**-0.28,
        lambda H: 1.7 * H**-0.352,
    ])


def alpha_delta_third(H):
    """alpha_delta(1/3), Appendix A."""
    return _piecewise(H, [0.1, 0.3], [
        lambda H: 568.758 * H**3 - 136.497 * H**2 + 11.37 * H + 0.518,
        lambda H: -0.772 * H**2 + 0.242 * H + 0.836,
        lambda H: 0.0175 * H**2 - 0.183 * H + 0.899,
    ])


def alpha_p_third(H):
    """alpha_p(1/3), Appendix A."""
    return _piecewise(H, [0.2, 1.0], [
        lambda H: 0.0122 * H**2 - 0.342 * H + 1.68,
        lambda H: -0.0428 * H**2 - 0.116 * H + 1.637,
        lambda H: 0.0187 * H**2 - 0.279 * H + 1.734,
    ])


# --- Appendix A, rigid substrate (figure 9, nu_c = 0.3) ---------------------------------
def alpha_a_rigid(H):
    """alpha_a, rigid substrate, Appendix A."""
    return _piecewise(H, [0.1, 0.5], [
        lambda H: -1.725 * np.log(H) + 1.21,
        lambda H: 2.371 * H**-0.339,
        lambda H: 2.228 * H**-0.438,
    ])


def alpha_p_rigid(H):
    """alpha_p, rigid substrate, Appendix A."""
    return _piecewise(H, [0.5], [
        lambda H: 2.036 * H**-0.243,
        lambda H: 0.115 * H**2 - 0.836 * H + 2.805,
    ])


def alpha_delta_rigid(H):
    """alpha_delta, rigid substrate, Appendix A."""
    return _piecewise(H, [0.5], [
        lambda H: 1.039 * H**-0.256,
        lambda H: 0.0796 * H**2 - 0.522 * H + 1.503,
    ])


#: Representative curves by (quantity, representative E); "rigid" for the rigid substrate.
CURVES: dict[tuple[str, str], Callable] = {
    ("a", "3"): alpha_a_3,
    ("delta", "3"): alpha_delta_3,
    ("p", "3"): alpha_p_3,
    ("a", "1/3"): alpha_a_third,
    ("delta", "1/3"): alpha_delta_third,
    ("p", "1/3"): alpha_p_third,
    ("a", "rigid"): alpha_a_rigid,
    ("delta", "rigid"): alpha_delta_rigid,
    ("p", "rigid"): alpha_p_rigid,
}

#: Breakpoints of each curve (for the continuity report).
BREAKPOINTS: dict[tuple[str, str], tuple[float, ...]] = {
    ("a", "3"): (0.05, 0.5, 1.5),
    ("delta", "3"): (0.05, 0.25, 0.5, 0.9),
    ("p", "3"): (0.05, 0.33, 0.75, 1.2),
    ("a", "1/3"): (0.1, 0.3),
    ("delta", "1/3"): (0.1, 0.3),
    ("p", "1/3"): (0.2, 1.0),
    ("a", "rigid"): (0.1, 0.5),
    ("delta", "rigid"): (0.5,),
    ("p", "rigid"): (0.5,),
}


def breakpoint_jumps() -> list[dict]:
    """Jumps of the Appendix A curves at their breakpoints: value just right minus value at."""
    rows = []
    for key, bps in BREAKPOINTS.items():
        f = CURVES[key]
        for b in bps:
            left, right = float(f(b)), float(f(b * (1 + 1e-12)))
            rows.append({"quantity": key[0], "curve": key[1], "H": b, "left": left,
                         "right": right, "jump": right - left})
    return rows


# --- eq (21) constants: rows j = 1..4, columns (a, b, delta, p) ------------------------
C21 = {
    "a": (-2.2, 3.5, 0.585, 39.0),
    "b": (0.7, 8.685, 4.685, 2.92),
    "delta": (-64.0, 0.0885, 0.655, None),  # row 4 replaced by the separate alpha_delta line
    "p": (12.0, 2.1, 2.65, 0.926),
}


def eq19_p(E, a13, a3):
    """eq (19a)."""
    return np.select(
        [E <= 1 / 3, E < 1, E <= 3],
        [a13 - (1 / E - 3) / 14, 1.85 + (a13 - 1.85) / (3 * E), 1.72 + E * (a3 - 1.72) / 3],
        a3 - (E - 3) / 25,
    )


def eq19_delta(E, a13):
    """eq (19b), E < 1 only."""
    return np.where(E <= 1 / 3, a13 - (1 / E - 3) / 39, 0.685 + (a13 - 0.685) / (3 * E))


def eq21(q: str, E, a13, a3):
    """eq (21) for quantity q in {a, b, delta, p}."""
    C1, C2, C3, C4 = C21[q]
    high = (0.225 + E * (a3 - 0.225) / 3) if q == "delta" else (a3 + (E - 3) / C4)
    return np.select(
        [E <= 1 / 3, E < 1, E <= 3],
        [a13 + (1 / E - 3) / C1, C2 + (a13 - C2) / (3 * E), C3 + E * (a3 - C3) / 3],
        high,
    )


@dataclass(frozen=True)
class AlphaRule:
    """How alpha(E, H) is obtained from the representative curves.

    Parameters
    ----------
    name
        Label used in reports and the result store.
    missing
        How to fill the parts of eq (19) missing from the copy (alpha_a for all E,
        alpha_delta for E > 1): ``"representative"`` (docs/paper-notes.md: alpha(3) for E >= 1,
        alpha(1/3) for E < 1) or ``"eq21"`` (the a and delta rows of eq 21).
    elliptical
        Use eq (21) for every quantity (Section 5) instead of eq (19).
    """

    name: str = "paper"
    missing: str = "representative"
    elliptical: bool = False

    def __post_init__(self) -> None:
        if self.missing not in ("representative", "eq21"):
            raise CoatHertzError(
                f"AlphaRule.missing must be 'representative' or 'eq21', got {self.missing!r}"
            )

    def alpha(self, quantity: str, E, H) -> np.ndarray:
        """alpha_q(E, H) for an elastic substrate; quantity in {a, b, delta, p}.

        ``b`` (minor semi-axis, eq 21) uses the alpha_a representative curves.
        """
        if quantity not in ("a", "b", "delta", "p"):
            raise CoatHertzError(f"quantity must be one of a, b, delta, p; got {quantity!r}")
        E, H = np.broadcast_arrays(np.asarray(E, dtype=float), np.asarray(H, dtype=float))
        if np.any(~(E > 0)) or np.any(np.isinf(E)):
            raise CoatHertzError("modulus ratio E = Ec*/Es* must satisfy 0 < E < inf")
        E = np.clip(E, *E_RANGE)  # alpha held at its end values outside [1/4, 4]
        base = "a" if quantity == "b" else quantity
        a13 = CURVES[(base, "1/3")](H)
        a3 = CURVES[(base, "3")](H)
        if self.elliptical:
            return eq21(quantity, E, a13, a3)
        if quantity == "p":
            return eq19_p(E, a13, a3)
        if quantity == "delta":
            low = eq19_delta(E, a13)
            high = eq21("delta", E, a13, a3) if self.missing == "eq21" else a3
            return np.where(E < 1, low, high)
        # alpha_a (and b): missing from eq (19) altogether
        if self.missing == "eq21":
            return eq21(quantity, E, a13, a3)
        return np.where(E < 1, a13, a3)


#: Eq (19) with the parts missing from the copy filled by the representative rule
#: (docs/paper-notes.md): the default.
PAPER_RULE = AlphaRule("paper")
#: Eq (19) with the parts missing from the copy (alpha_a, alpha_delta for E > 1) taken from the
#: a and delta rows of eq (21).
EQ21_RULE = AlphaRule("eq21-fill", missing="eq21")
#: Eq (21) for every quantity (Section 5: elliptical contacts).
ELLIPTICAL_RULE = AlphaRule("eq21-elliptical", elliptical=True)


def alpha_rigid(quantity: str, H) -> np.ndarray:
    """alpha_q(H) for a rigid substrate (Appendix A, figure 9); b uses the a curve."""
    base = "a" if quantity == "b" else quantity
    if base not in QUANTITIES:
        raise CoatHertzError(f"quantity must be one of a, b, delta, p; got {quantity!r}")
    return CURVES[(base, "rigid")](np.asarray(H, dtype=float))


#: Largest explicit alpha accepted. The paper's alpha lie between about 0.3 and 10 (figs 4, 5, 9);
#: at alpha H beyond ~350 eq (17) is the coating half-space to the last digit, and alpha H beyond
#: ~1e154 overflows its (alpha H)^2 term.
ALPHA_MAX = 1e3


@dataclass(frozen=True)
class Alphas:
    """Explicit alpha values (e.g. read from the paper's figures, as in Section 6).

    ``b`` defaults to ``a`` (minor semi-axis of an elliptical contact).
    """

    a: float
    delta: float
    p: float
    b: float | None = None

    def __post_init__(self) -> None:
        for name in ("a", "delta", "p", "b"):
            v = getattr(self, name)
            if v is not None and not (np.isfinite(v) and 0 < v <= ALPHA_MAX):
                raise CoatHertzError(f"alpha_{name} must satisfy 0 < alpha <= {ALPHA_MAX:g} (the paper's "
                                     f"alpha are of order 1), got {v!r}")

    def get(self, quantity: str) -> float:
        if quantity == "b":
            return self.a if self.b is None else self.b
        return getattr(self, quantity)

    @classmethod
    def parse(cls, text: str) -> Alphas:
        """Parse ``"a=3.35,p=1.619,delta=1.1"`` (CLI ``--alpha``)."""
        vals: dict[str, float] = {}
        for part in text.split(","):
            if "=" not in part:
                raise CoatHertzError(f"--alpha expects 'a=..,p=..,delta=..', got {text!r}")
            k, v = (s.strip() for s in part.split("=", 1))
            if k not in ("a", "p", "delta", "b"):
                raise CoatHertzError(f"--alpha: unknown key {k!r}; use a, p, delta (and b)")
            try:
                vals[k] = float(v)
            except ValueError as exc:
                raise CoatHertzError(f"--alpha: alpha_{k} = {v!r} is not a number") from exc
        missing = {"a", "p", "delta"} - set(vals)
        if missing:
            raise CoatHertzError(f"--alpha: missing {sorted(missing)}; give a, p and delta")
        try:
            return cls(**vals)
        except CoatHertzError as exc:
            raise CoatHertzError(f"--alpha: {exc}") from None
