"""Constitutive laws behind one small interface, evaluated at quadrature points.

A law maps the axisymmetric strain vector (Voigt order, engineering shear)

.. math:: \\varepsilon = (\\varepsilon_{rr}, \\varepsilon_{zz}, \\varepsilon_{\\theta\\theta}, \\gamma_{rz})

and the history variables of the last converged increment to the stress
:math:`\\sigma = (\\sigma_{rr}, \\sigma_{zz}, \\sigma_{\\theta\\theta}, \\sigma_{rz})`, the consistent
tangent :math:`\\partial\\sigma/\\partial\\varepsilon` (4 x 4 at every point) and the updated history.
Arrays carry the quadrature layout ``(..., n_elements, n_points)``. The assembly
(:mod:`coathertz.fem.forms`) and the incremental loop (:mod:`coathertz.fem.loading`) only use
this interface. :class:`LinearElastic` is here; the J2 elastic-plastic law (plastic strain and
equivalent plastic strain as history) is :class:`coathertz.fem.plastic.j2.J2Plastic`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from coathertz.errors import CoatHertzError

State = dict[str, np.ndarray]


@runtime_checkable
class MaterialLaw(Protocol):
    """Stress, tangent and history update at quadrature points."""

    #: True if the tangent is constant (stiffness assembled once, F_int = K u).
    is_linear: bool

    def initial_state(self, shape: tuple[int, ...]) -> State:
        """History variables for quadrature arrays of ``shape``."""
        ...

    def stress(self, strain: np.ndarray, state: State) -> tuple[np.ndarray, np.ndarray, State]:
        """Return ``(sigma[4, ...], tangent[4, 4, ...], new_state)`` for ``strain[4, ...]``."""
        ...


def lame_parameters(E: float, nu: float) -> tuple[float, float]:
    """Lame's ``lam`` and the shear modulus ``mu``; ``lam = inf`` for ``nu = 0.5``."""
    mu = E / (2.0 * (1.0 + nu))
    lam = math.inf if nu >= 0.5 else E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    return lam, mu


@dataclass(frozen=True)
class LinearElastic:
    """Isotropic linear elasticity (no history variables).

    Parameters
    ----------
    E
        Young's modulus [Pa], ``0 < E < inf``.
    nu
        Poisson's ratio, ``-1 < nu < 0.5`` (``nu = 0.5`` only through the mixed u-p form).
    """

    E: float
    nu: float
    is_linear: bool = True

    def __post_init__(self) -> None:
        if not (0 < self.E < math.inf):
            raise CoatHertzError(f"E must satisfy 0 < E < inf [Pa] for an elastic law, got {self.E!r}")
        if not (-1.0 < self.nu <= 0.5):
            raise CoatHertzError(f"nu must satisfy -1 < nu <= 0.5, got {self.nu!r}")

    @property
    def lame(self) -> tuple[float, float]:
        return lame_parameters(self.E, self.nu)

    def matrix(self) -> np.ndarray:
        """The 4 x 4 elasticity matrix in the Voigt order of this module."""
        lam, mu = self.lame
        if math.isinf(lam):
            raise CoatHertzError("nu = 0.5 has no displacement-form elasticity matrix: use the mixed form")
        D = np.full((4, 4), 0.0)
        D[:3, :3] = lam
        D[[0, 1, 2], [0, 1, 2]] += 2.0 * mu
        D[3, 3] = mu
        return D

    def initial_state(self, shape: tuple[int, ...]) -> State:
        return {}

    def stress(self, strain: np.ndarray, state: State) -> tuple[np.ndarray, np.ndarray, State]:
        D = self.matrix()
        sig = np.einsum("ij,j...->i...", D, strain)
        tangent = np.broadcast_to(D.reshape(4, 4, *([1] * (strain.ndim - 1))), (4, 4, *strain.shape[1:]))
        return sig, tangent, state
