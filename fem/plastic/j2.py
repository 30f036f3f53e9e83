r"""J2 (von Mises) elastic-plastic law with isotropic hardening: radial return, consistent tangent.

Small strain, additive split :math:`\varepsilon = \varepsilon^e + \varepsilon^p`, isotropic
elasticity (bulk modulus ``K``, shear modulus ``G``), yield function

.. math:: f = q - Y(\bar\varepsilon^p), \qquad q = \sqrt{\tfrac32\, s : s},

associated flow :math:`\dot\varepsilon^p = \dot\gamma\, \tfrac32\, s / q` and
:math:`\dot{\bar\varepsilon}{}^p = \dot\gamma`. The backward-Euler return mapping is the radial
return (Wilkins 1964; Simo & Hughes, *Computational Inelasticity*, 1998, Box 3.2; de Souza Neto,
Peric & Owen, *Computational Methods for Plasticity*, 2008, Box 7.3): with the elastic trial
stress :math:`\sigma^{tr}`, if :math:`f^{tr} > 0` solve

.. math:: q^{tr} - 3 G\, \Delta\gamma - Y(\bar\varepsilon^p_n + \Delta\gamma) = 0

(closed form for linear hardening, safeguarded scalar Newton otherwise) and scale the deviator,
:math:`s = (1 - 3 G \Delta\gamma / q^{tr})\, s^{tr}`. The consistent (algorithmic) tangent is
de Souza Neto et al. eq (7.120):

.. math:: D = 2G\Big(1 - \frac{3G\Delta\gamma}{q^{tr}}\Big) I_d
          + 6G^2\Big(\frac{\Delta\gamma}{q^{tr}} - \frac{1}{3G + H'}\Big)\, \bar N \otimes \bar N
          + K\, 1 \otimes 1,
          \qquad \bar N = s^{tr}/\lVert s^{tr}\rVert ,

``H' = dY/d\bar\varepsilon^p`` at the end of the step. Axisymmetric Voigt order as in
:mod:`coathertz.fem.material`: strain ``(e_rr, e_zz, e_tt, gamma_rz)`` with engineering shear,
stress ``(s_rr, s_zz, s_tt, s_rz)``; the history is the plastic strain (same Voigt order,
engineering shear) and the equivalent plastic strain ``ep`` at every quadrature point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.material import State, lame_parameters
from coathertz.materials import Plasticity

#: ``m``: the identity in Voigt form; dot products of tensors in Voigt form use :data:`_W`
#: (the shear entry counts twice).
_M = np.array([1.0, 1.0, 1.0, 0.0])
_W = np.array([1.0, 1.0, 1.0, 2.0])
#: Relative tolerance of the yield check (a reloaded point lands on the surface up to round-off).
YIELD_TOL = 1e-12


def deviator(sig: np.ndarray) -> np.ndarray:
    """Deviatoric part of a Voigt stress ``sig[4, ...]``."""
    p = (sig[0] + sig[1] + sig[2]) / 3.0
    return sig - p * _M.reshape(4, *([1] * (sig.ndim - 1)))


def equivalent_stress(sig: np.ndarray) -> np.ndarray:
    """Von Mises stress ``q = sqrt(3/2 s:s)`` of ``sig[4, ...]``."""
    s = deviator(sig)
    return np.sqrt(1.5 * np.einsum("i,i...->...", _W, s * s))


@dataclass(frozen=True)
class J2Plastic:
    """Isotropic elasticity with J2 plasticity (see module docstring).

    Parameters
    ----------
    E, nu
        Young's modulus [Pa] and Poisson's ratio (``-1 < nu < 0.5``).
    plasticity
        Yield stress and hardening (:class:`coathertz.materials.Plasticity`).
    """

    E: float
    nu: float
    plasticity: Plasticity
    is_linear: bool = False

    def __post_init__(self) -> None:
        if not (0 < self.E < math.inf):
            raise CoatHertzError(f"E must satisfy 0 < E < inf [Pa] for a J2 law, got {self.E!r}")
        if not (-1.0 < self.nu < 0.5):
            raise CoatHertzError(f"nu must satisfy -1 < nu < 0.5 for a J2 law (displacement/B-bar form), "
                                 f"got {self.nu!r}")
        if not isinstance(self.plasticity, Plasticity):
            raise CoatHertzError(f"plasticity must be a Plasticity, got {self.plasticity!r}")

    @property
    def lame(self) -> tuple[float, float]:
        return lame_parameters(self.E, self.nu)

    @property
    def bulk(self) -> float:
        return self.E / (3.0 * (1.0 - 2.0 * self.nu))

    @property
    def shear(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    def elastic_matrix(self) -> np.ndarray:
        lam, mu = self.lame
        D = np.zeros((4, 4))
        D[:3, :3] = lam
        D[[0, 1, 2], [0, 1, 2]] += 2.0 * mu
        D[3, 3] = mu
        return D

    def initial_state(self, shape: tuple[int, ...]) -> State:
        return {"eps_p": np.zeros((4, *shape)), "ep": np.zeros(shape)}

    def _solve_dgamma(self, q_tr: np.ndarray, ep: np.ndarray) -> np.ndarray:
        """``dgamma`` with ``q_tr - 3 G dgamma - Y(ep + dgamma) = 0`` (vector, q_tr > Y(ep))."""
        G, pl = self.shear, self.plasticity
        if pl.hardening in ("perfect", "linear"):
            return (q_tr - pl.flow_stress(ep)[0]) / (3.0 * G + (pl.H if pl.hardening == "linear" else 0.0))
        lo, hi = np.zeros_like(q_tr), q_tr / (3.0 * G)  # g(lo) > 0 >= g(hi) for Y > 0
        x = np.zeros_like(q_tr)
        for _ in range(100):
            Y, dY = pl.flow_stress(ep + x)
            g = q_tr - 3.0 * G * x - Y
            if np.all(np.abs(g) <= 1e-14 * pl.Y):
                return x
            lo = np.where(g > 0, x, lo)
            hi = np.where(g <= 0, x, hi)
            xn = x + g / (3.0 * G + dY)
            x = np.where((xn > lo) & (xn < hi), xn, 0.5 * (lo + hi))
        raise ConvergenceError("J2 return mapping: the scalar Newton/bisection did not converge in 100 steps")

    def _trial(self, strain: np.ndarray, eps_p: np.ndarray, ep: np.ndarray):
        """Elastic trial state: volumetric strain, deviatoric stress, von Mises stress and the
        points beyond the yield surface (``q_tr - Y > YIELD_TOL Y``: round-off on the surface stays
        elastic)."""
        e = strain - eps_p
        tr = e[0] + e[1] + e[2]
        ee = e.copy()
        ee[3] = 0.5 * e[3]  # tensor shear component
        s_tr = 2.0 * self.shear * deviator(ee)
        q_tr = np.sqrt(1.5 * np.einsum("i,i...->...", _W, s_tr * s_tr))
        Y0 = self.plasticity.flow_stress(ep)[0]
        return tr, s_tr, q_tr, q_tr - Y0 > YIELD_TOL * Y0

    def inelastic_points(self, strain: np.ndarray, state: State) -> np.ndarray:
        """Points whose stress and tangent are not the elastic law's from zero strain: a plastic
        strain in their history or a trial state beyond the yield surface (the same test as
        :meth:`stress`). At the others ``sigma = D_el strain``, ``D = D_el`` and the state is
        unchanged, so the assembly (:class:`~coathertz.fem.plastic.assembly.BBarAssembler`) can
        leave them to the elastic stiffness."""
        return self._trial(strain, state["eps_p"], state["ep"])[3] | np.any(state["eps_p"] != 0.0, axis=0)

    def stress(self, strain: np.ndarray, state: State) -> tuple[np.ndarray, np.ndarray, State]:
        """Return ``(sigma, D, new_state)`` for total strain ``strain[4, ...]`` (module docstring)."""
        shape = strain.shape[1:]
        eps_p = state["eps_p"] if state else np.zeros_like(strain)
        ep = state["ep"] if state else np.zeros(shape)
        K, G = self.bulk, self.shear
        tr, s_tr, q_tr, plastic = self._trial(strain, eps_p, ep)
        dgam = np.zeros(shape)
        if plastic.any():
            dgam[plastic] = self._solve_dgamma(q_tr[plastic], ep[plastic])
        q_safe = np.where(plastic, q_tr, 1.0)
        theta = 1.0 - 3.0 * G * dgam / q_safe
        s = s_tr * theta
        sig = s + K * tr * _M.reshape(4, *([1] * len(shape)))
        # plastic strain increment 3/2 dgamma s/q (engineering shear: twice the tensor component)
        n_q = 1.5 * s_tr / q_safe
        deps_p = dgam * n_q * _W.reshape(4, *([1] * len(shape)))
        new = {"eps_p": eps_p + deps_p, "ep": ep + dgam}
        # consistent tangent, de Souza Neto et al. eq (7.120), in Voigt form (engineering shear)
        D = np.empty((4, 4, *shape))
        Id = np.eye(4) - np.outer(_M, _M) / 3.0
        Id[3, 3] = 0.5
        base = np.outer(_M, _M) * K
        D[...] = (base + 2.0 * G * Id).reshape(4, 4, *([1] * len(shape)))
        if plastic.any():
            Hp = self.plasticity.flow_stress(ep + dgam)[1]
            norm_s = np.sqrt(np.einsum("i,i...->...", _W, s_tr * s_tr))
            N = s_tr / np.where(plastic, norm_s, 1.0)
            c = np.where(plastic, 6.0 * G**2 * (dgam / q_safe - 1.0 / (3.0 * G + Hp)), 0.0)
            D += 2.0 * G * (theta - 1.0) * Id.reshape(4, 4, *([1] * len(shape)))
            D += c * np.einsum("i...,j...->ij...", N, N)
        return sig, D, new
