"""Surface compliance of the contacting pair in Hankel space and its decaying correction ``M``.

For a homogeneous half-space the surface normal displacement due to an axisymmetric pressure
with Hankel transform ``P(k) = int_0^inf p(r) J0(k r) r dr`` is
``u(r) = int_0^inf C(k) P(k) J0(k r) k dk`` with ``C(k) = 2 / (E* k)`` (eq 14). A coated body
(coating of thickness ``h`` on a substrate) has

.. math::  C(k) = \\frac{2}{E_c^* k} F(k h),   F(0) = E_c^*/E_s^*,   F(\\infty) = 1,

the *layer factor* ``F`` of eq (13) (Nogi & Kato 1997) for a bonded coating. The two bodies'
compliances add, so the pair has

.. math::  C(k) = \\frac{2}{E_{ref} k} \\bigl(1 + M(k)\\bigr),\\qquad
           \\frac{1}{E_{ref}} = \\sum_i \\frac{1 - \\nu_i^2}{E_i}\\ (\\text{top material of body } i),
           \\qquad M(k) = E_{ref} \\sum_i \\frac{1-\\nu_i^2}{E_i} \\bigl(F_i(k h_i) - 1\\bigr),

with ``E_ref`` the ``E*`` of eq (2) with every coating taken as a half-space. ``M`` is bounded
(``M(0) = E_ref/E_s - 1`` finite, ``-1`` on a rigid substrate) and decays like
``(k h)^2 exp(-2 k h)``: the homogeneous part ``2/(E_ref k)`` is handled exactly by the Abel
route (:mod:`coathertz.axisym.solver`) and only ``M`` is integrated numerically.

Layer factors (``t = k h``, ``theta = exp(-2 t)``, ``eps = 3 - 4 nu_c``):

* bonded, elastic substrate: eq (13),
  ``F = (1 + 4 t kappa theta - lam kappa theta^2) / (1 - (lam + kappa + 4 kappa t^2) theta
  + lam kappa theta^2)``;
* bonded, rigid substrate (eq 13 with ``mu = 0``, ``lam = -eps``, ``kappa = -1/eps``, multiplied
  through by ``eps e^{2t}``): ``F = (2 eps sinh 2t - 4 t) / (2 eps cosh 2t + 1 + eps^2 + 4 t^2)``;
  thin layer ``F ~ (1 - 2 nu_c) t / (2 (1 - nu_c)^2)`` (the constrained-modulus Winkler layer,
  ``u = p h (1 - 2 nu) / (2 G (1 - nu))``), and for ``nu_c = 0.5`` ``F ~ (2/3) t^3`` (the
  incompressible layer): nothing divides by ``1 - 2 nu``;
* frictionless, rigid substrate: ``F = (cosh 2t - 1) / (sinh 2t + 2 t)``, independent of ``nu_c``;
  thin layer ``F ~ t/2``, i.e. ``u = p h / E_c*`` (laterally free layer);
* frictionless, elastic substrate: see :func:`layer_factor_frictionless`.

All forms are evaluated with ``exp(-2t)`` only (no overflow for large ``t``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as npcheb

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import Body, Material

INTERFACES = ("bonded", "frictionless")

LayerFactor = Callable[[np.ndarray], np.ndarray]


def _dundurs(coating: Material, substrate: Material) -> tuple[float, float]:
    """``lam`` and ``kappa`` of eq (13) for an elastic substrate."""
    nu_c, nu_s = coating.nu, substrate.nu
    mu = coating.E * (1.0 + nu_s) / (substrate.E * (1.0 + nu_c))  # eq (13): Gc/Gs
    lam = 1.0 - 4.0 * (1.0 - nu_c) / (1.0 + mu * (3.0 - 4.0 * nu_s))  # eq (13)
    kappa = (mu - 1.0) / (mu + 3.0 - 4.0 * nu_c)  # eq (13)
    return lam, kappa


def layer_factor_bonded(coating: Material, substrate: Material) -> LayerFactor:
    """``F(t)`` of a coating perfectly bonded to ``substrate`` (rigid allowed), eq (13)."""
    if substrate.is_rigid:
        eps = 3.0 - 4.0 * coating.nu

        def F_rigid(t: np.ndarray) -> np.ndarray:
            th = np.exp(-2.0 * t)
            # (2 eps sinh 2t - 4t) e^{-2t} / ((2 eps cosh 2t + 1 + eps^2 + 4t^2) e^{-2t})
            num = eps * (1.0 - th * th) - 4.0 * t * th
            den = eps * (1.0 + th * th) + (1.0 + eps * eps + 4.0 * t * t) * th
            # thin layers: the numerator cancels (eps - 1 = 2 (1 - 2 nu)); series for t < 0.1
            small = t < 0.1
            if np.any(small):
                ts = t[small]
                # 2 eps sinh 2t - 4t = 4 (eps - 1) t + sum_{j>=1} 2 eps (2t)^(2j+1)/(2j+1)!
                x = 2.0 * ts
                ser = 4.0 * (eps - 1.0) * ts
                term = x
                for j in range(1, 9):
                    term = term * x * x / ((2 * j) * (2 * j + 1))
                    ser = ser + 2.0 * eps * term
                num = num.copy()
                num[small] = ser * th[small]
            return num / den

        return F_rigid

    lam, kappa = _dundurs(coating, substrate)
    lk = lam * kappa

    def F_elastic(t: np.ndarray) -> np.ndarray:
        th = np.exp(-2.0 * t)
        num = 1.0 + 4.0 * t * kappa * th - lk * th * th  # eq (13), numerator
        den = 1.0 - (lam + kappa + 4.0 * kappa * t * t) * th + lk * th * th  # eq (13)
        return num / den

    return F_elastic


def layer_factor_frictionless(coating: Material, substrate: Material) -> LayerFactor:
    r"""``F(t)`` of a coating resting on ``substrate`` without friction (rigid allowed).

    Derivation (plane strain along ``k``, ``k = 1``, Papkovich--Neuber potentials
    ``phi = (A e^{-z} + C e^{z}) cos x``, ``psi = (B e^{-z} + D e^{z}) cos x`` in the layer): with
    both faces free of shear and normal pressures ``P`` (top) and ``q`` (interface), the layer's
    surface displacements in units of ``2/E_c*`` are ``u(0) = a11 P + a12 q``,
    ``u(t) = -a12 P - a11 q`` with ``a11 = (s c + t)/(s^2 - t^2)``,
    ``|a12| = (t c + s)/(s^2 - t^2)``, ``s = sinh t``, ``c = cosh t`` (a free plate: both blow up
    like ``6/t^3`` as ``t -> 0``). The substrate gives ``u(t) = r q`` with
    ``r = E_c*/E_s*`` (``0``: rigid). Eliminating ``q`` and using
    ``a11^2 - a12^2 = s^2/(s^2 - t^2)``:

    .. math::  F(t) = \frac{r (s c + t) + s^2}{r (s^2 - t^2) + s c + t},

    ``F(0) = r`` (eq 14), ``F(inf) = 1`` (eq 15); ``r = 0`` gives ``(cosh 2t - 1)/(sinh 2t + 2t)``.
    ``nu_c`` and ``nu_s`` enter only through ``E_c*`` and ``E_s*``. Evaluated as
    ``[r (1 - th^2 + 4 t th) + (1 - th)^2] / [r ((1 - th)^2 - 4 t^2 th) + 1 - th^2 + 4 t th]``
    with ``th = exp(-2t)`` (numerator and denominator times ``4 e^{-2t}``).
    """
    r = 0.0 if substrate.is_rigid else coating.E_star / substrate.E_star

    def F(t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        th = np.exp(-2.0 * t)
        sc = 1.0 - th * th + 4.0 * t * th  # 4 e^{-2t} (sinh t cosh t + t)
        s2 = (1.0 - th) ** 2  # 4 e^{-2t} sinh^2 t
        with np.errstate(invalid="ignore", divide="ignore"):
            out = (r * sc + s2) / (r * (s2 - 4.0 * t * t * th) + sc)
        return np.where(t > 1e-12, out, r)

    return F


#: Interpolation table of a stack's ``F``: Chebyshev panels of this width in ``log t``, this many
#: nodes each, from ``t = STACK_T_MIN h_min / h_total`` (``k h_total = STACK_T_MIN``); accepted
#: only if it matches direct evaluation to ``STACK_TABLE_TOL`` of ``max(|F|, 1)`` at the panel
#: midpoints and below its start (otherwise ``F`` is evaluated directly).
STACK_PANEL, STACK_NODES, STACK_T_MIN, STACK_TABLE_TOL = 0.5, 16, 1e-8, 1e-13


class _StackTable:
    """Piecewise-Chebyshev interpolant of ``F(t)`` in ``log t`` (``F`` is smooth there): a few
    hundred evaluations once per body instead of one per xi node and radius. Below ``t_min``
    (``k h_total <= 1e-8``: ``F`` is analytic in ``k h_total`` there) the chord from the exact
    long-wave limit ``F0`` (:func:`stack_factor`) to ``F(t_min)``, off by ``~F'' t_min^2 / 8``
    (~1e-17); above ``t_max`` (all layers 40 decay lengths deep: ``F = 1`` to 1e-30) exactly 1."""

    def __init__(self, F_direct, t_min: float, t_max: float, F0: float) -> None:
        self.F_direct = F_direct
        self.s0, self.s1 = math.log(t_min), math.log(t_max)
        self.t_min, self.F0 = t_min, F0
        self.n_pan = max(1, math.ceil((self.s1 - self.s0) / STACK_PANEL))
        self.w = (self.s1 - self.s0) / self.n_pan
        x = np.cos(np.pi * (np.arange(STACK_NODES) + 0.5) / STACK_NODES)  # Chebyshev points
        s = self.s0 + self.w * (np.arange(self.n_pan)[:, None] + 0.5 * (x[None, :] + 1.0))
        # the nodes, the panels' check points and the chord's end and check points in one call
        mid = self.s0 + self.w * (np.arange(self.n_pan) + 0.37)
        below = t_min * np.array([1.0, 0.3, 1e-3])
        vals = F_direct(np.concatenate([np.exp(s.ravel()), np.exp(mid), below]))
        n = s.size
        # interpolation at the Chebyshev points: one solve for all panels (was chebfit per panel)
        V = npcheb.chebvander(x, STACK_NODES - 1)
        self.coef = np.linalg.solve(V, vals[:n].reshape(s.shape).T).T
        self.coef_t = np.ascontiguousarray(self.coef.T)  # (nodes, panels): rows gathered per call
        self.F_lo = float(vals[-3])
        # relative to max(|F|, 1): F reaches E_1*/E_s* (~70 for a stiff top on a soft stack), where
        # round-off alone is 1e-13 absolute
        ref = vals[n:]
        got = np.concatenate([self._interp(np.exp(mid)), [self.F_lo], self._chord(below[1:])])
        self.err = float(np.max(np.abs(got - ref) / np.maximum(np.abs(ref), 1.0)))
        self.ok = self.err < STACK_TABLE_TOL

    def _chord(self, t: np.ndarray) -> np.ndarray:
        return self.F0 + (self.F_lo - self.F0) * (t / self.t_min)

    def _interp(self, t: np.ndarray) -> np.ndarray:
        s = np.log(t)
        i = np.clip(((s - self.s0) / self.w).astype(int), 0, self.n_pan - 1)
        x = 2.0 * (s - self.s0 - i * self.w) / self.w - 1.0
        c = self.coef_t[:, i]  # (nodes, n): each row contiguous
        # Clenshaw, vectorised over points with their own coefficients
        x2 = 2.0 * x
        b1 = c[STACK_NODES - 1].copy()
        b2 = np.zeros_like(x)
        for j in range(STACK_NODES - 2, 0, -1):
            b1, b2 = x2 * b1 - b2 + c[j], b1
        return x * b1 - b2 + c[0]

    def __call__(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        flat = t.ravel()
        if not self.ok:
            return self.F_direct(flat).reshape(t.shape)
        out = np.ones_like(flat)
        lo = flat < self.t_min
        mid = ~lo & (flat <= math.exp(self.s1))
        if np.any(lo):
            out[lo] = self._chord(flat[lo])
        if np.any(mid):
            out[mid] = self._interp(flat[mid])
        return out.reshape(t.shape)


def stack_factor(body: Body, table: bool = True) -> tuple[LayerFactor, float]:
    """``F`` of a body with a layer stack (:mod:`coathertz.stack`) as a function of
    ``t = k h_min`` and ``h_min``, the thinnest layer [m] (it sets the decay of ``M``);
    ``table``: through ``_StackTable`` (checked against direct evaluation), whose long-wave end
    is the exact limit ``F(0) = E_1^*/E_s^*`` (0 on a rigid substrate: the substrate under a
    stack much thinner than the wave)."""
    from coathertz.stack import StackLayer, stack_layer_factor

    layers = [StackLayer(L.material, L.h, L.interface) for L in body.layers]
    h_min = min(L.h for L in body.layers)

    def F(t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return stack_layer_factor(layers, body.material, t.ravel() / h_min).reshape(t.shape)

    if not table:
        return F, h_min
    ratio = sum(L.h for L in body.layers) / h_min
    F0 = 0.0 if body.material.is_rigid else body.layers[0].material.E_star / body.material.E_star
    return _StackTable(F, STACK_T_MIN / ratio, 40.0 * ratio, F0), h_min


def body_layer_factor(body: Body, interface: str) -> LayerFactor | None:
    """The layer factor of a coated ``body``, ``None`` if it is homogeneous (``F = 1``)."""
    if body.is_stacked:
        return stack_factor(body)[0]
    if not body.is_coated:
        return None
    coat = body.coating.material
    if interface == "bonded":
        return layer_factor_bonded(coat, body.material)
    if interface == "frictionless":
        return layer_factor_frictionless(coat, body.material)
    raise CoatHertzError(f"interface must be one of {INTERFACES}, got {interface!r}")


def top_compliance(body: Body) -> float:
    """``(1 - nu^2)/E`` of the material at the body's surface (coating or top layer), 0 if rigid."""
    if body.is_stacked:
        return body.layers[0].material.compliance
    return body.coating.material.compliance if body.is_coated else body.material.compliance


@dataclass(frozen=True)
class PairCompliance:
    """``C(k) = 2 (1 + M(k)) / (E_ref k)`` of the two bodies of a case (module docstring).

    Attributes
    ----------
    E_ref
        ``E*`` of eq (2) with the coatings as half-spaces [Pa] (``C`` at large ``k``).
    terms
        ``(weight_i, F_i, h_i)`` per coated body: ``M(k) = sum_i weight_i (F_i(k h_i) - 1)``.
    """

    E_ref: float
    terms: tuple[tuple[float, LayerFactor, float], ...]

    @property
    def h_min(self) -> float:
        """Thinnest coating [m] (``inf`` if none): sets the decay rate of ``M``."""
        return min((h for _, _, h in self.terms), default=np.inf)

    def M(self, k: np.ndarray) -> np.ndarray:
        """The decaying correction ``M(k)`` (dimensionless), ``k`` in 1/m."""
        k = np.asarray(k, dtype=float)
        out = np.zeros_like(k)
        for w, F, h in self.terms:
            out += w * (F(k * h) - 1.0)
        return out


def pair_compliance(case: ContactCase, interface: str = "bonded") -> PairCompliance:
    """The pair compliance of ``case`` (both bodies; a rigid body adds nothing)."""
    if interface not in INTERFACES:
        raise CoatHertzError(f"interface must be one of {INTERFACES}, got {interface!r}")
    comps = [top_compliance(b) for b in (case.body1, case.body2)]
    total = sum(comps)
    if total <= 0:
        raise CoatHertzError("at least one body must be elastic (both are rigid)")
    E_ref = 1.0 / total
    terms = []
    for b, c in zip((case.body1, case.body2), comps, strict=True):
        if b.is_stacked:
            F, h = stack_factor(b)
            terms.append((E_ref * c, F, h))
            continue
        F = body_layer_factor(b, interface)
        if F is not None:
            terms.append((E_ref * c, F, b.coating.h))
    return PairCompliance(E_ref, tuple(terms))
