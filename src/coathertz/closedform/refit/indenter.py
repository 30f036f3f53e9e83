r"""An elastic indenter on a coated elastic half-space: one variable more than the rigid indenter.

For a frictionless contact the normal problem depends on the two bodies only through the sum
of their surface compliances. In Fourier space that is

.. math::

    C(k) = \frac{1}{E_i^*} + \frac{F(kh)}{E_c^*}
         = \frac{1}{E_\text{ref}}\,\bigl[\gamma F(kh) + 1 - \gamma\bigr],
    \qquad \frac{1}{E_\text{ref}} = \frac{1}{E_c^*} + \frac{1}{E_i^*},
    \qquad \gamma = \frac{E_\text{ref}}{E_c^*} = \frac{E_i^*}{E_c^* + E_i^*} \in (0, 1],

with :math:`F` the coated half-space's compliance over the coating's (eq 13; :math:`F \to 1` as
:math:`kh \to \infty`, :math:`F \to E = E_c^*/E_s^*` as :math:`kh \to 0`). So the indenter adds
exactly one variable, :math:`\gamma` (the coating's share of the thick-coating compliance; 1 for
a rigid indenter, 0 for an infinitely compliant one), to :math:`(H, \lambda, \kappa)`; with
:math:`H = h/a_{0s}` and the bars over the Hertz values of the indenter on the bare substrate
(eq 7a) nothing else changes. :math:`\gamma` rather than :math:`E_i^*/E_s^*`: it enters the
kernel linearly, lies in a bounded interval, and both of its ends are exact limits.

The combined kernel :math:`\gamma F + 1 - \gamma` runs from :math:`E' = 1 + \gamma (E - 1)` at
:math:`kh = 0` to 1 at :math:`kh \to \infty`: both Hertz limits are those of a rigid indenter on a
coating with the modulus ratio :math:`E'`. The form

.. math::

    \ln \bar q = \ln \bar q_\text{rigid}(E', H, s') + \gamma (1 - \gamma)\, v(H)\,
    D_q(\log_{10} H, \log_{10} E, s, \gamma),
    \qquad v(H) = w (1 - w),\ w = \frac{H}{1 + H},

takes the rigid indenter's second form (:mod:`coathertz.closedform.refit.corrected`) at the
equivalent modulus ratio :math:`E'` and the Dundurs coordinate :math:`s'` of
:math:`\beta_D' = \gamma \beta_D` (:func:`equivalent_s`; :mod:`coathertz.closedform.refit.reduced`),
and corrects it with a clamped tensor Chebyshev
surface :math:`D_q` fitted to exact solutions (``coathertz fit-alpha``, sweep config
``indenter``). Limits: :math:`\gamma = 1` gives the rigid-indenter rule unchanged,
:math:`\gamma \to 0` Hertz with the indenter's modulus, :math:`H \to 0` and :math:`H \to \infty`
the two Hertz limits (:math:`v \to 0`; the base has the exact limits there).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from coathertz.closedform.refit import model as M
from coathertz.closedform.refit.reduced import dundurs, s_coordinate
from coathertz.closedform.refit.surface import Surface, evaluate_shared
from coathertz.errors import CoatHertzError

VARIABLES = ("log10_H", "log10_E", "s", "gamma")
BOX = (M.LOG10_H, M.LOG10_E, (0.0, 1.0), (0.0, 1.0))


def gamma_of(Ec_star, Ei_star) -> np.ndarray:
    """``gamma = E_ref/Ec* = Ei*/(Ec* + Ei*)`` (1 for a rigid indenter, ``Ei* = inf``)."""
    Ec, Ei = np.asarray(Ec_star, dtype=float), np.asarray(Ei_star, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(np.isinf(Ei), 1.0, Ei / (Ec + Ei))


def equivalent_ratio(E, gamma) -> np.ndarray:
    """``E' = 1 + gamma (E - 1)``: the modulus ratio of the rigid-indenter problem with the same
    two Hertz limits."""
    return 1.0 + np.asarray(gamma, dtype=float) * (np.asarray(E, dtype=float) - 1.0)


def equivalent_s(E, nu_c, nu_s, gamma) -> np.ndarray:
    """Dundurs' coordinate ``s'`` of the equivalent rigid-indenter problem: ``beta' = gamma beta``
    at ``E' = 1 + gamma (E - 1)`` (for small mismatch ``lambda ~ alpha_D + beta_D``,
    ``kappa ~ alpha_D - beta_D``, and the combined kernel's mismatch is gamma times the coating's).
    ``s'`` lies in [0, 1] for every gamma in [0, 1]; gamma = 1 gives s, gamma -> 0 the
    homogeneous point (Hertz)."""
    g = np.asarray(gamma, dtype=float)
    _, beta = dundurs(E, nu_c, nu_s)
    E_eq = equivalent_ratio(E, g)
    al = (E_eq - 1.0) / (E_eq + 1.0)
    return np.clip(0.5 * (4.0 * g * beta - al + 1.0), 0.0, 1.0)


def poisson_at(E_eq, s, nu_s) -> np.ndarray:
    """``nu_c'`` such that ``(E_eq, nu_c', nu_s)`` has Dundurs' coordinate ``s``
    (:func:`coathertz.closedform.refit.reduced.s_coordinate`), in closed form.

    The bars depend on the materials only through ``(lambda, kappa)``, i.e. ``(E, s)``; this pair
    is one parametrisation of the point ``(E_eq, s)`` (nu_c' may leave [0, 1/2]: only the pair
    ``(lambda, kappa)`` it gives is used)."""
    E_eq, s, nu_s = (np.asarray(v, dtype=float) for v in (E_eq, s, nu_s))
    al = (E_eq - 1.0) / (E_eq + 1.0)
    beta = (2.0 * s - 1.0 + al) / 4.0
    u = 1.0 / (2.0 * beta * (E_eq + 1.0) - E_eq * (1.0 - 2.0 * nu_s) / (1.0 - nu_s) + 2.0)  # 1 - nu_c'
    return 1.0 - u


def equivalent_problem(E, nu_c, nu_s, gamma) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(E', nu_c', nu_s)``: a material pair with the equivalent problem's ``E'`` and ``s'``
    (:func:`equivalent_ratio`, :func:`equivalent_s`, :func:`poisson_at`)."""
    E_eq = equivalent_ratio(E, gamma)
    nu_s = np.asarray(nu_s, dtype=float)
    return E_eq, poisson_at(E_eq, equivalent_s(E, nu_c, nu_s, gamma), nu_s), nu_s


def weight(H, gamma) -> np.ndarray:
    """``gamma (1 - gamma) w (1 - w)``, ``w = H/(1 + H)``: vanishes in every exact limit."""
    g = np.asarray(gamma, dtype=float)
    w = np.asarray(H, dtype=float) / (1.0 + np.asarray(H, dtype=float))
    return g * (1.0 - g) * w * (1.0 - w)


def variables(E, H, nu_c, nu_s, gamma) -> np.ndarray:
    """Rows ``(4, n)`` of ``(log10 H, log10 E, s, gamma)`` (broadcast, flattened)."""
    E, H, nu_c, nu_s, gamma = (np.asarray(v, dtype=float).ravel() for v in np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (E, H, nu_c, nu_s, gamma))))
    if np.any(~((gamma > 0.0) & (gamma <= 1.0))):
        raise CoatHertzError("indenter compliance share gamma = E_ref/Ec* must lie in (0, 1]")
    X = M.variables("elastic", E, H, nu_c, nu_s)
    return np.vstack([X, gamma])


@dataclass(frozen=True)
class IndenterForm:
    """The correction surfaces ``D_q`` of the elastic indenter (see the module docstring)."""

    surfaces: Mapping[str, Surface]

    def log_bars(self, rigid_bars: Callable, E, H, nu_c, nu_s, gamma, *,
                 logs: bool = False) -> dict[str, np.ndarray]:
        """``ln bar_q`` of an elastic indenter (flattened broadcast shape); ``rigid_bars(E, H,
        nu_c, nu_s)`` are the rigid indenter's bars (the rule's elastic-substrate best form), or
        their logarithms with ``logs`` (no ``exp`` and ``ln`` round trip: the fast path)."""
        E, H, nu_c, nu_s, gamma = (np.asarray(v, dtype=float).ravel() for v in np.broadcast_arrays(
            *(np.asarray(v, dtype=float) for v in (E, H, nu_c, nu_s, gamma))))
        X = variables(E, H, nu_c, nu_s, gamma)
        E_eq, nu_eq, _ = equivalent_problem(E, nu_c, nu_s, gamma)
        base = rigid_bars(E_eq, H, nu_eq, nu_s)
        v = weight(H, gamma)
        vals = evaluate_shared([self.surfaces[q] for q in M.QUANTITIES], X)
        return {q: (base[q] if logs else np.log(base[q])) + v * d
                for q, d in zip(M.QUANTITIES, vals, strict=True)}

    def to_dict(self) -> dict:
        """Full tensor surfaces, stored compactly: the degrees per variable and the coefficients in
        :func:`full_tensor` order (the term list is implied)."""
        first = next(iter(self.surfaces.values()))
        degrees = first.degrees
        coef = {}
        for q, s in self.surfaces.items():
            if s.terms != full_tensor(degrees):
                raise CoatHertzError("IndenterForm: the surfaces must be full tensors of the same degrees")
            coef[q] = list(s.coef)
        return {"variables": list(first.variables), "lo": list(first.lo), "hi": list(first.hi),
                "degrees": list(degrees), "coef": coef}

    @classmethod
    def from_dict(cls, d: Mapping) -> IndenterForm:
        terms = full_tensor(d["degrees"])
        lo, hi = tuple(map(float, d["lo"])), tuple(map(float, d["hi"]))
        return cls({q: Surface(tuple(d["variables"]), lo, hi, terms, tuple(map(float, c)))
                    for q, c in d["coef"].items()})


def full_tensor(degrees) -> tuple[tuple[int, ...], ...]:
    """Every multi-index up to ``degrees`` (a full tensor product), in lexicographic order."""
    return tuple(itertools.product(*(range(int(k) + 1) for k in degrees)))


#: Significant digits of the stored coefficients (the fit rounds to them, so the shipped form is
#: the fitted one; the rounding changes a bar by < 1e-9 relative).
COEF_DIGITS = 10


def s_of(E, nu_c, nu_s) -> np.ndarray:
    """Dundurs' coordinate s of the coating/substrate pair (re-exported for the fit)."""
    return s_coordinate(E, nu_c, nu_s)
