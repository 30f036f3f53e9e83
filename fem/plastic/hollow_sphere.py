r"""Hill's thick-walled hollow sphere under internal pressure, in the axisymmetric FE model.

A check of the elastic-plastic machinery against a closed form (Hill, *The Mathematical Theory
of Plasticity*, 1950, Section V.3; Chakrabarty, *Theory of Plasticity*, 2006, Section 4.3):
inner radius ``a``, outer radius ``b``, elastic-perfectly-plastic (Tresca = von Mises under
spherical symmetry, yield stress ``Y``). The elastic limit, the plastic front ``c`` and the
collapse pressure are

.. math:: p_e = \tfrac23 Y\Big(1 - \frac{a^3}{b^3}\Big), \qquad
          p(c) = 2Y\ln\frac{c}{a} + \tfrac23 Y\Big(1 - \frac{c^3}{b^3}\Big), \qquad
          p_L = 2Y\ln\frac{b}{a}.

The meridian section of the upper half shell, :math:`a \le \rho \le b`,
:math:`0 \le \theta \le \pi/2` (``r = rho cos(theta)``, ``z = rho sin(theta)``) is meshed with Q2
quadrilaterals (uniform in ``rho`` and ``theta``), ``u_r = 0`` on the axis and ``u_z = 0`` on
the plane ``z = 0``. The pressure acts on ``rho = a`` (consistent nodal forces ``p f_1``);
Newton with the B-bar tangent (:mod:`coathertz.fem.plastic.assembly`). Pressure control up to
just below ``p_L``; beyond it the collapse pressure is measured under displacement control (a
uniform radial displacement ``U`` of the inner surface), ``p = F_int . u_1 / f_1 . u_1`` with
``u_1`` the nodal field of ``U = 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, ElementQuad2, ElementVector, FacetBasis, LinearForm, MeshQuad, MeshQuad2, asm

from coathertz.errors import ConvergenceError
from coathertz.fem.model import INTORDER
from coathertz.fem.plastic.assembly import BBarAssembler
from coathertz.fem.plastic.j2 import J2Plastic
from coathertz.materials import Plasticity


def hill_closed_form(a: float, b: float, Y: float) -> dict:
    """Elastic limit, collapse pressure and ``p(c)`` of Hill's sphere (module docstring)."""
    return {"p_e": 2.0 / 3.0 * Y * (1.0 - (a / b) ** 3), "p_L": 2.0 * Y * math.log(b / a),
            "p_of_c": lambda c: 2.0 * Y * math.log(c / a) + 2.0 / 3.0 * Y * (1.0 - (c / b) ** 3)}


def front_from_pressure(p: float, a: float, b: float, Y: float) -> float:
    """Invert ``p(c)`` for the plastic front ``c`` (``p_e <= p < p_L``)."""
    from scipy.optimize import brentq

    f = hill_closed_form(a, b, Y)["p_of_c"]
    return brentq(lambda c: f(c) - p, a, b, xtol=1e-14 * b)


@dataclass
class HollowSphere:
    """The discrete shell problem (module docstring)."""

    a: float = 1.0
    b: float = 2.0
    E: float = 200e9
    nu: float = 0.3
    Y: float = 1e9
    n_rho: int = 16
    n_theta: int = 8
    bbar: bool = True

    def __post_init__(self) -> None:
        rho = np.linspace(self.a, self.b, self.n_rho + 1)
        th = np.linspace(0.0, 0.5 * math.pi, self.n_theta + 1)
        m = MeshQuad2.from_mesh(MeshQuad.init_tensor(rho, th))
        R, T = m.doflocs
        m = replace(m, doflocs=np.vstack([R * np.cos(T), R * np.sin(T)]))  # isoparametric circle arcs
        self.mesh = m
        self.basis = Basis(m, ElementVector(ElementQuad2()), intorder=INTORDER)
        self.law = J2Plastic(self.E, self.nu, Plasticity(self.Y))
        self.asm = BBarAssembler(self.basis, [(np.arange(m.t.shape[1]), self.law)], bbar=self.bbar)
        x, z = self.basis.doflocs
        comp = np.zeros(self.basis.N, dtype=int)
        for d in (self.basis.nodal_dofs, self.basis.facet_dofs, self.basis.interior_dofs):
            if d.size:
                comp[d[1]] = 1
        tol = 1e-9 * self.b
        rho_d = np.hypot(x, z)
        self.fixed = np.unique(np.concatenate([np.nonzero((x < tol) & (comp == 0))[0],
                                               np.nonzero((z < tol) & (comp == 1))[0]]))
        vr = np.hypot(*m.p)[m.facets]  # radii of both vertices of every facet
        facets = np.nonzero(np.all(np.abs(vr - self.a) < 1e-9 * self.a, axis=0))[0]
        self.inner = np.unique(self.basis.get_dofs(facets).all())
        # unit radial field on the inner surface (nodal values of e_rho)
        self.u1 = np.zeros(self.basis.N)
        e = np.where(comp == 0, x, z) / np.maximum(rho_d, 1e-300)
        self.u1[self.inner] = e[self.inner]
        fb = FacetBasis(m, self.basis.elem, facets=facets, intorder=INTORDER)
        # traction p e_rho = -p n (n the outward normal of the body, pointing into the cavity)
        self.f1 = asm(LinearForm(lambda v, w: -(v[0] * w.n[0] + v[1] * w.n[1]) * 2 * np.pi * w.x[0]), fb)
        self.reset()

    def reset(self) -> None:
        self.u = np.zeros(self.basis.N)
        self.states = [self.law.initial_state(self.asm.w.shape)]

    def _newton(self, fixed, vals, f_ext, rtol=1e-10, max_it=30):
        u = self.u.copy()
        u[fixed] = vals
        F, K, _, trial = self.asm.evaluate(u, self.states)
        free = np.setdiff1d(np.arange(self.basis.N), fixed)
        scale = max(np.linalg.norm(f_ext), np.linalg.norm(F), 1e-300)
        hist = []
        for _ in range(max_it):
            R = (f_ext - F)[free]
            hist.append(float(np.linalg.norm(R) / scale))
            if hist[-1] < rtol:
                self.u, self.states = u, trial
                return F, hist
            Kff = K.tocsc()[free][:, free]
            u[free] += spla.splu(Kff.tocsc(), permc_spec="MMD_AT_PLUS_A",
                                 options={"SymmetricMode": True}).solve(R)
            F, K, _, trial = self.asm.evaluate(u, self.states)
            scale = max(np.linalg.norm(f_ext), np.linalg.norm(F), 1e-300)
        raise ConvergenceError(f"hollow sphere: Newton did not converge in {max_it} iterations: {hist[-3:]}")

    def pressure_step(self, p: float) -> list:
        """Advance to internal pressure ``p`` [Pa]; returns the Newton residual history."""
        return self._newton(self.fixed, np.zeros(len(self.fixed)), p * self.f1)[1]

    def displacement_step(self, U: float) -> float:
        """Advance to inner radial displacement ``U`` [m]; returns the pressure that holds it."""
        fixed = np.unique(np.concatenate([self.fixed, self.inner]))
        vals = U * self.u1[fixed]
        vals[np.isin(fixed, self.fixed)] = 0.0
        F, _ = self._newton(fixed, vals, np.zeros(self.basis.N))
        return float(F @ self.u1 / (self.f1 @ self.u1))

    def ep_profile(self) -> tuple[np.ndarray, np.ndarray]:
        """Equivalent plastic strain against radius (mean over theta at each quadrature radius)."""
        rho = np.hypot(self.asm.rq, self.asm.zq).ravel()
        ep = self.states[0]["ep"].ravel()
        return self._levels(rho, ep)

    def _levels(self, rho: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Means of ``v`` over the quadrature points that share a radius (to 1e-3 element sizes)."""
        key = np.round(rho / (1e-3 * (self.b - self.a) / self.n_rho)).astype(np.int64)
        _, inv = np.unique(key, return_inverse=True)
        cnt = np.bincount(inv)
        return np.bincount(inv, rho) / cnt, np.bincount(inv, v) / cnt

    def _q_rho3(self, mask_elastic: bool) -> float:
        """Volume-weighted mean of ``q rho^3`` over the (elastic) quadrature points. In an elastic
        shell under spherical symmetry (Lame) ``q rho^3`` is constant, equal to ``Y c^3`` at the
        plastic front ``c`` (or ``q(a) a^3`` before yield)."""
        from coathertz.fem.plastic.j2 import equivalent_stress

        sig, _, _ = self.law.stress(self.asm.strain(self.u, np.arange(self.mesh.t.shape[1])), self.states[0])
        q = equivalent_stress(sig)
        rho = np.hypot(self.asm.rq, self.asm.zq)
        sel = self.states[0]["ep"] <= 0.0 if mask_elastic else np.ones_like(q, dtype=bool)
        w = self.asm.w
        return float((q * rho**3 * w)[sel].sum() / w[sel].sum())

    def front(self) -> float:
        """Plastic front ``c = (q rho^3 / Y)^(1/3)`` from the elastic shell (``_q_rho3``); it
        must lie between the outermost plastic and the innermost elastic quadrature radii."""
        if not (self.states[0]["ep"] > 0).any():
            return self.a
        if (self.states[0]["ep"] > 0).all():
            return self.b
        return (self._q_rho3(True) / self.Y) ** (1.0 / 3.0)

    def front_bracket(self) -> tuple[float, float]:
        """Outermost plastic and innermost elastic quadrature radius."""
        rho, ep = self.ep_profile()
        pl = ep > 0
        return float(rho[pl].max()) if pl.any() else self.a, float(rho[~pl].min()) if (~pl).any() else self.b

    def elastic_limit(self) -> float:
        """Pressure at which von Mises reaches Y at the inner surface, from the elastic solution
        (``q(a) = <q rho^3> / a^3``, ``_q_rho3``)."""
        self.reset()
        self.pressure_step(1e-6 * self.Y)
        q_a = self._q_rho3(False) / self.a**3
        self.reset()
        return 1e-6 * self.Y * self.Y / q_a
