r"""The refitted alpha: one smooth closed-form alpha per quantity, used in eqs (1), (17), (18).

The paper's structure is kept: a coated body has the extended modulus :math:`E_1^*` of eq (17)
with one parameter :math:`\alpha_q` per quantity :math:`q \in \{a, \delta, p\}`, and eq (1)
(eq 5 for ellipses) with the eq (18) modulus gives the prediction. Only the rule for alpha
changes: instead of the representative curves of Appendix A and the piecewise eq (19),

.. math::

    \ln \alpha_q = L \tanh(S_q / L), \quad S_q = \sum_k c_{qk} \prod_v T_{i_{kv}}(s_v),
    \quad L = \ln 10^4,

a Chebyshev-product surface (:class:`~coathertz.closedform.refit.surface.Surface`) in

* elastic substrate: the reduced coordinates of :mod:`coathertz.closedform.refit.reduced`,
  :math:`\log_{10} H \in [-3, 1]`, :math:`\log_{10} E \in [-1, 1]` and Dundurs' normalised
  :math:`s \in [0, 1]` (E = Ec*/Es*, H = h/a0s, eq 7a): the bars depend on the materials only
  through :math:`(\lambda, \kappa)`, i.e. through (E, s), so alpha needs three variables, not four;
* rigid substrate: :math:`\log_{10} H \in [-3, 1]`, :math:`t(\nu_c)` with :math:`\nu_c \in [0, 0.5]`
  (H = h/a0c, 7b).

Outside these boxes each variable is clamped, so alpha is held at its boundary value.
Limits: as H -> 0, alpha H -> 0 and eq (17) gives E1* -> Es* (substrate Hertz); as
H -> inf, alpha H -> inf and E1* -> Ec* (coating Hertz). The surface is smooth inside its
box and continuous everywhere (no pieces, no jumps).

Elliptical contacts (:mod:`coathertz.closedform.refit.ellipse`) add one correction factor per quantity.
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.closedform.extended import EXPONENT, E1_over_Ec, constants_from_ratio
from coathertz.closedform.refit.reduced import s_coordinate
from coathertz.closedform.refit.surface import Surface
from coathertz.errors import CoatHertzError

QUANTITIES = ("a", "delta", "p")
CONFIGS = ("elastic", "rigid")
LOG10_H = (-3.0, 1.0)  # H in [0.001, 10]
LOG10_E = (-1.0, 1.0)  # E in [1/10, 10]
NU_EPS = 0.01
#: On a rigid substrate nu_c enters through ``t(nu) = log10(1 + NU_EPS - 2 nu)``: thin layers
#: stiffen like ``1/(1 - 2 nu)`` as nu -> 1/2, and t spreads that end (t = 0.004 at nu = 0, -2 at
#: nu = 0.5). On an elastic substrate nu_c and nu_s enter through Dundurs' s (reduced.py).
T_NU = (math.log10(NU_EPS), math.log10(1.0 + NU_EPS))
NU = (0.0, 0.5)
VARIABLES = {
    "elastic": ("log10_H", "log10_E", "s"),
    "rigid": ("log10_H", "t_nu_c"),
}
BOXES = {
    "elastic": (LOG10_H, LOG10_E, (0.0, 1.0)),
    "rigid": (LOG10_H, T_NU),
}


#: The stretched thickness coordinate ``xi_H = asinh((log10 H - XI_C) / XI_W)`` of the stiff-coating
#: patch of p0 (:mod:`coathertz.closedform.refit.corrected`): nodes uniform in xi_H are dense around
#: H = 10^XI_C, where p0 of stiff coatings rises steeply with H.
XI_C, XI_W = -0.35, 0.25
XI_H = (math.asinh((LOG10_H[0] - XI_C) / XI_W), math.asinh((LOG10_H[1] - XI_C) / XI_W))


def xi_H(H) -> np.ndarray:
    """``asinh((log10 H - XI_C) / XI_W)``."""
    return np.arcsinh((np.log10(np.asarray(H, dtype=float)) - XI_C) / XI_W)


def log10_H_of_xi(xi) -> np.ndarray:
    """The inverse of :func:`xi_H` (in log10 H)."""
    return XI_C + XI_W * np.sinh(np.asarray(xi, dtype=float))


#: ln alpha is soft-capped at +-LN_ALPHA_CAP (alpha in (1e-4, 1e4)): where a bar does not depend on
#: alpha (E near 1, the two Hertz limits) the fit would otherwise let alpha drift to 1e9; the cap is
#: smooth (tanh) and changes alpha by < 1 % for alpha in [0.05, 20].
LN_ALPHA_CAP = math.log(1e4)


def ln_alpha(z):
    """The soft cap ``L tanh(z / L)`` applied to a surface value ``z``."""
    return LN_ALPHA_CAP * np.tanh(np.asarray(z, dtype=float) / LN_ALPHA_CAP)


def check_quantity(q: str, allowed=QUANTITIES) -> str:
    if q not in allowed:
        raise CoatHertzError(f"quantity must be one of {', '.join(allowed)}; got {q!r}")
    return q


def t_nu(nu) -> np.ndarray:
    """The Poisson's-ratio variable ``log10(1 + NU_EPS - 2 nu)`` of the surfaces."""
    return np.log10(1.0 + NU_EPS - 2.0 * np.asarray(nu, dtype=float))


def variables(config: str, E=None, H=None, nu_c=0.3, nu_s=0.3) -> np.ndarray:
    """Rows ``(d, n)`` of the surface variables of ``config`` (broadcast inputs)."""
    H = np.asarray(H, dtype=float)
    if np.any(~(H > 0)):
        raise CoatHertzError("H must be > 0 to evaluate the refitted alpha (H = 0: no coating)")
    if config == "rigid":
        H, nu_c = np.broadcast_arrays(H, np.asarray(nu_c, dtype=float))
        return np.vstack([np.log10(H).ravel(), t_nu(nu_c).ravel()])
    E = np.asarray(E, dtype=float)
    if np.any(~(E > 0)) or np.any(np.isinf(E)):
        raise CoatHertzError("modulus ratio E = Ec*/Es* must satisfy 0 < E < inf")
    E, H, nu_c, nu_s = np.broadcast_arrays(E, H, np.asarray(nu_c, float), np.asarray(nu_s, float))
    return np.vstack([np.log10(H).ravel(), np.log10(E).ravel(), s_coordinate(E, nu_c, nu_s).ravel()])


def bar_from_alpha(q: str, alpha, E, H, nu_c, nu_s, rigid: bool = False) -> np.ndarray:
    """Bars of eqs (1), (17), (18) for a rigid indenter on a coated half-space.

    Elastic substrate: ``(E1*/Es*)^k``; rigid substrate: ``(E1*/Ec*)^k``, with ``k`` = -1/3 (a),
    -2/3 (delta), 2/3 (p).
    """
    H = np.asarray(H, dtype=float)
    nu_c = np.asarray(nu_c, dtype=float)
    if rigid:
        lam = 4.0 * nu_c - 3.0  # Section 4
        ratio = E1_over_Ec(lam, 1.0 / lam, alpha, H)
    else:
        E = np.asarray(E, dtype=float)
        lam, kappa = constants_from_ratio(E, nu_c, np.asarray(nu_s, dtype=float))
        ratio = E * E1_over_Ec(lam, kappa, alpha, H)
    return np.asarray(ratio, dtype=float) ** EXPONENT[q]


class AlphaModel:
    """The refitted alpha surfaces of one configuration (``elastic`` or ``rigid``)."""

    def __init__(self, config: str, surfaces: dict[str, Surface]) -> None:
        if config not in CONFIGS:
            raise CoatHertzError(f"config must be one of {CONFIGS}, got {config!r}")
        self.config = config
        self.surfaces = dict(surfaces)

    def alpha(self, q: str, E=None, H=None, nu_c=0.3, nu_s=0.3) -> np.ndarray:
        """alpha_q at the (broadcast) inputs, flattened to 1-D."""
        check_quantity(q)
        return np.exp(ln_alpha(self.surfaces[q](variables(self.config, E, H, nu_c, nu_s))))

    def bar(self, q: str, E=None, H=None, nu_c=0.3, nu_s=0.3) -> np.ndarray:
        """Predicted bar of quantity ``q`` (flattened broadcast shape)."""
        X = variables(self.config, E, H, nu_c, nu_s)
        alpha = np.exp(ln_alpha(self.surfaces[check_quantity(q)](X)))
        if self.config == "rigid":
            H, nu_c = (np.broadcast_arrays(np.asarray(H, float), np.asarray(nu_c, float)))
            return bar_from_alpha(q, alpha, None, H.ravel(), nu_c.ravel(), None, rigid=True)
        E, H, nu_c, nu_s = (a.ravel() for a in np.broadcast_arrays(
            *(np.asarray(v, dtype=float) for v in (E, H, nu_c, nu_s))))
        return bar_from_alpha(q, alpha, E, H, nu_c, nu_s)

    def bars(self, E=None, H=None, nu_c=0.3, nu_s=0.3) -> dict[str, np.ndarray]:
        """All three bars at once (shares the variables and eq 13's constants): the fast path."""
        X = variables(self.config, E, H, nu_c, nu_s)
        if self.config == "rigid":
            H, nu_c = (a.ravel() for a in np.broadcast_arrays(np.asarray(H, float), np.asarray(nu_c, float)))
            lam = 4.0 * nu_c - 3.0  # Section 4
            lam, kappa, scale = lam, 1.0 / lam, 1.0
        else:
            E, H, nu_c, nu_s = (a.ravel() for a in np.broadcast_arrays(
                *(np.asarray(v, dtype=float) for v in (E, H, nu_c, nu_s))))
            lam, kappa = constants_from_ratio(E, nu_c, nu_s)
            scale = E
        out = {}
        for q in QUANTITIES:
            alpha = np.exp(ln_alpha(self.surfaces[q](X)))
            out[q] = (scale * E1_over_Ec(lam, kappa, alpha, H)) ** EXPONENT[q]
        return out
