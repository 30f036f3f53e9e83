"""The paper's standard configuration and the case builders the studies share."""

from __future__ import annotations

import numpy as np

from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.materials import RIGID, Body, Coating, Material

__all__ = ["E_SUBSTRATE", "NU", "R_SPHERE", "W_LOAD", "elastic_case", "fig3_ratios", "h_grid", "nearest",
           "rigid_substrate_case"]

R_SPHERE = 10e-3  # [m]
W_LOAD = 1.0  # [N]
E_SUBSTRATE = 200e9  # [Pa]
NU = 0.3


def h_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """``n`` values of H, geometric from ``lo`` to ``hi`` (the paper does not state its spacing;
    geometric spacing resolves the thin-coating end, where the curves change fastest)."""
    return np.round(np.geomspace(lo, hi, n), 6)


def nearest(values, targets) -> set[float]:
    """The members of ``values`` nearest (in log) to each target, rounded to 9 digits: expensive
    methods run on grid points, so the grids keep the paper's sizes."""
    v = np.asarray(values, dtype=float)
    return {round(float(v[np.argmin(np.abs(np.log(v / t)))]), 9) for t in targets}


def fig3_ratios() -> list[float]:
    """The 25 modulus ratios of figure 3: 1/E = 4 - (i-1)/4, i = 1..12; E = 1 + i/4, i = 0..12."""
    return [1.0 / (4.0 - (i - 1) / 4.0) for i in range(1, 13)] + [1.0 + i / 4.0 for i in range(13)]


def elastic_case(E: float, H: float, nu_c: float = NU, nu_s: float = NU, label: str = "") -> ContactCase:
    """Rigid sphere on a coated elastic half-space with ``Ec*/Es* = E`` and ``h = H a0s``."""
    sub = Material(E_SUBSTRATE, nu_s)
    Ec = E * sub.E_star * (1.0 - nu_c**2)
    coat = Material(Ec, nu_c)
    a0s = float(hertz_circular(W_LOAD, R_SPHERE, sub.E_star).a0)  # eq (1a), rigid sphere
    return ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, coat, H * a0s, sub, label=label)


def rigid_substrate_case(Ec: float, H: float, nu_c: float = NU, label: str = "") -> ContactCase:
    """Rigid sphere on a coating of modulus ``Ec`` bonded to a rigid substrate, ``h = H a0c``."""
    coat = Material(Ec, nu_c)
    h = H * float(hertz_circular(W_LOAD, R_SPHERE, coat.E_star).a0)  # a0c, eq (1a)
    return ContactCase(Body.rigid_sphere(R_SPHERE), Body.half_space(RIGID, Coating(coat, h)), W_LOAD,
                       label=label)
