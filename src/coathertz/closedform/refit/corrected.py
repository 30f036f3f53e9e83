r"""The second closed form: the refit alpha of eqs (17)-(18) times a smooth correction factor.

Where no single alpha reproduces the exact bar (:func:`coathertz.fitalpha.fit.single_alpha_floor`:
e.g. the maximum pressure under soft, nearly incompressible coatings on compressible substrates
around H ~ 0.1), the one-alpha structure cannot reach the target however alpha is fitted. The
corrected form keeps eqs (1), (17), (18) with the refit alpha and multiplies each bar by a
factor that vanishes in the Hertz limits:

.. math::

    \ln \bar q = \ln \bar q_\alpha + v(H)\, C_q(x), \qquad
    v(H) = \begin{cases} w(1 - w),\ w = H/(1 + H) & \text{elastic substrate} \\
                         1/(1 + H) & \text{rigid substrate} \end{cases}

with :math:`C_q` a clamped tensor Chebyshev surface
(:class:`~coathertz.closedform.refit.surface.Surface`) in the variables of the configuration
(:mod:`coathertz.closedform.refit.model`: :math:`(\log_{10} H, \log_{10} E, s)` on an elastic
substrate, :math:`(\log_{10} H, t(\nu_c))` on a rigid one), fitted by linear least squares to
the residual :math:`\ln \bar q_\text{exact} - \ln \bar q_\alpha` of the one-alpha rule.
Limits: on an elastic substrate :math:`v \to 0` as H -> 0 (substrate Hertz) and H -> inf
(coating Hertz); on a rigid substrate as H -> inf (coating Hertz); the thin-layer end H -> 0 is
not a Hertz limit there and the correction is held at its H = 0.001 value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from coathertz.closedform.extended import EXPONENT
from coathertz.closedform.refit import model as M
from coathertz.closedform.refit.surface import Surface, evaluate_shared
from coathertz.errors import CoatHertzError


def weight(H) -> np.ndarray:
    """``w(H) = H/(1 + H)``."""
    H = np.asarray(H, dtype=float)
    return H / (1.0 + H)


def correction_weight(config: str, H) -> np.ndarray:
    """The factor ``v(H)`` of the correction (see the module docstring)."""
    H = np.asarray(H, dtype=float)
    if config == "rigid":
        return 1.0 / (1.0 + H)
    w = weight(H)
    return w * (1.0 - w)


def log_correction(surface: Surface, E, H, nu_c=0.3, nu_s=0.3, config: str = "elastic") -> np.ndarray:
    """``v(H) C_q`` of the corrected form (flattened broadcast shape)."""
    X = M.variables(config, E, H, nu_c, nu_s)
    return correction_weight(config, 10.0 ** X[0]) * surface(X)


#: The axis branch of p0 blends from the global surface to the stiff-coating patch over
#: log10 E in [log10 2, log10 3] (a C^2 smooth step: no jump, no kink).
BLEND_LOG10_E = (math.log10(2.0), math.log10(3.0))


def smoothstep(t) -> np.ndarray:
    """``t^3 (10 - 15 t + 6 t^2)`` on [0, 1], 0 below, 1 above (C^2)."""
    t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
    return t**3 * (10.0 - 15.0 * t + 6.0 * t * t)


def in_ring_box(H, E) -> np.ndarray:
    """Inside the box where the peak pressure may sit on a ring
    (:data:`coathertz.closedform.refit.rule_format.RING_BOX`; E above the box counts as inside)."""
    from coathertz.closedform.refit.rule_format import RING_BOX

    lh, le = np.log10(np.asarray(H, dtype=float)), np.log10(np.asarray(E, dtype=float))
    (h0, h1), (e0, _) = RING_BOX["log10_H"], RING_BOX["log10_E"]
    return (lh >= h0) & (lh <= h1) & (le >= e0)


@dataclass(frozen=True)
class CorrectedForm:
    """The corrected form of one circular configuration (see the module docstring).

    ``base``: the constant alpha of the base per quantity, or None for the one-alpha refit of the
    same data file. Elastic substrate, p0: the axis branch blends the global surface with the
    stiff-coating ``patch`` (in ``xi_H``, :func:`coathertz.closedform.refit.model.xi_H`) over
    :data:`BLEND_LOG10_E`, and inside the ring box p0 is the larger of the axis branch and the
    ``ring`` branch (the largest pressure on 0.2 a <= r <= a): the maximum pressure has a kink
    where the peak leaves the axis, which no smooth surface reproduces.
    """

    config: str
    base: dict
    surfaces: dict
    patch: dict = field(default_factory=dict)
    ring: dict = field(default_factory=dict)

    def base_log_bar(self, q: str, alpha_model: M.AlphaModel | None, E, H, nu_c, nu_s,
                     cache: dict | None = None) -> np.ndarray:
        """``ln`` of the base bar of ``q`` (flattened broadcast shape): the one-alpha refit, or eq
        (17) at the base's constant alpha. Quantities sharing a constant alpha share one eq (17)
        through ``cache`` (``ln bar_q = k_q ln(E1*/E_ref)``, eq 1)."""
        E, H, nu_c, nu_s = (a.ravel() for a in np.broadcast_arrays(
            *(np.asarray(0.3 if v is None else v, dtype=float) for v in (E, H, nu_c, nu_s))))
        a0 = self.base.get(q)
        if a0 is None:
            if alpha_model is None:
                raise CoatHertzError("the corrected form's base is the one-alpha refit: pass its model")
            return np.log(alpha_model.bar(q, E, H, nu_c, nu_s))
        cache = {} if cache is None else cache
        key = float(a0)
        if key not in cache:  # ln(E1*/E_ref) at this alpha
            ratio = M.bar_from_alpha("p", key, E, H, nu_c, nu_s, rigid=self.config == "rigid")
            cache[key] = np.log(ratio) / EXPONENT["p"]
        return EXPONENT[q] * cache[key]

    def log_bar(self, q: str, E, H, nu_c=0.3, nu_s=0.3,
                alpha_model: M.AlphaModel | None = None) -> np.ndarray:
        """``ln bar_q`` (flattened broadcast shape)."""
        return self.log_bars(E, H, nu_c, nu_s, alpha_model, (q,))[q]

    def log_bars(self, E, H, nu_c=0.3, nu_s=0.3, alpha_model: M.AlphaModel | None = None,
                 quantities=M.QUANTITIES) -> dict[str, np.ndarray]:
        """``ln bar_q`` of several quantities at once (the variables and the weights are shared)."""
        E = None if self.config == "rigid" else E
        X = M.variables(self.config, E, H, nu_c, nu_s)
        Hf = 10.0 ** X[0]
        v = correction_weight(self.config, Hf)
        if self.config == "rigid":
            Eb, nu_sb = None, None
            nu_cb = np.broadcast_arrays(np.asarray(H, dtype=float), np.asarray(nu_c, dtype=float))[1].ravel()
        else:
            Eb = 10.0 ** X[1]
            _, _, nu_cb, nu_sb = (a.ravel() for a in np.broadcast_arrays(
                *(np.asarray(x, dtype=float) for x in (E, H, nu_c, nu_s))))
        # every global surface at every point in one shared evaluation (one set of tables, one
        # matrix product); where the patch takes over, the global value is simply not used
        shared = dict(zip(quantities, evaluate_shared([self.surfaces[q] for q in quantities], X),
                          strict=True))
        out = {}
        ratio_cache: dict = {}
        for q in quantities:
            base = self.base_log_bar(q, alpha_model, Eb, Hf, nu_cb, nu_sb, ratio_cache)
            if q in self.patch:
                beta = smoothstep((X[1] - BLEND_LOG10_E[0]) / (BLEND_LOG10_E[1] - BLEND_LOG10_E[0]))
                on = beta > 0.0
                # the global surface where beta < 1 (elementwise: the same values as masked updates)
                val = np.where(beta < 1.0, base + v * shared[q] * (1.0 - beta), base)
                if np.any(on):
                    Xp = np.vstack([M.xi_H(Hf[on]), X[1:, on]])
                    val[on] += v[on] * self.patch[q](Xp) * beta[on]
            else:
                val = base + v * shared[q]
            if q in self.ring:
                inside = in_ring_box(Hf, 10.0 ** X[1])
                if np.any(inside):
                    val[inside] = np.maximum(val[inside], base[inside] + self.ring[q](X[:, inside]))
            out[q] = val
        return out

    def to_dict(self) -> dict:
        return {"base": dict(self.base), "surfaces": {q: s.to_dict() for q, s in self.surfaces.items()},
                "patch": {q: s.to_dict() for q, s in self.patch.items()},
                "ring": {q: s.to_dict() for q, s in self.ring.items()}}

    @classmethod
    def from_dict(cls, config: str, d: Mapping) -> CorrectedForm:
        def surf(key):
            return {q: Surface.from_dict(s) for q, s in d.get(key, {}).items()}

        return cls(config, dict(d.get("base", {})), surf("surfaces"), surf("patch"), surf("ring"))


