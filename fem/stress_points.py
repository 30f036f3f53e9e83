"""The FE stresses at given points ``(r, z)``, for cross-checks with the other methods.

The recovered field is :class:`coathertz.fem.post.StressField` (quadrature-point stresses
L2-projected on continuous Q2 fields, one projection per region, so the lateral stresses keep
their jump at the coating/substrate interface). Here it is sampled on a lattice of radii and
depths, in the conventions of :mod:`coathertz.axisym.stresses`: depth ``z >= 0`` downwards (the
mesh's coordinate is ``-z``), components ``sigma_rr, sigma_tt, sigma_zz, sigma_rz`` with
``sigma_rz`` for the downward ``z`` (the mesh's ``sigma_rz`` changes sign), tension positive.
A depth on the interface is taken on the coating's side (``side="above"``) unless
``side="below"`` (the point is moved ``1e-9 h`` into that region, since the probes search the
whole mesh while each region has its own projection); points on the axis are read at
``r = 1e-9 a_ref`` (the mesh's border: ``O(1e-18)`` relative change).
"""

from __future__ import annotations

import numpy as np

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fem.method import FEMMethod
from coathertz.fem.model import FEModel
from coathertz.fem.post import StressField
from coathertz.results import ContactResult

#: Components of the returned field (those of :data:`coathertz.axisym.stresses.COMPONENTS`).
COMPONENTS = ("rr", "tt", "zz", "rz")
SIDES = ("above", "below")


def sample(model: FEModel, x: np.ndarray, r, z, side: str = "above",
           field: StressField | None = None) -> np.ndarray:
    """Stresses [Pa] at every ``(r, z)`` of the lattice: shape ``(len(z), 4, len(r))``.

    Parameters
    ----------
    model, x
        The FE model and its solution vector (``LoadPath.x`` of
        :meth:`~coathertz.fem.method.FEMMethod.solve_full`).
    r, z
        Radii ``0 <= r <= L`` and depths ``0 <= z <= D`` [m] inside the meshed body.
    side
        On the interface depth: the coating (``above``) or the substrate (``below``).
    field
        A recovered field to reuse (built from ``model, x`` otherwise).
    """
    if side not in SIDES:
        raise CoatHertzError(f"side must be one of {SIDES}, got {side!r}")
    r = np.atleast_1d(np.asarray(r, dtype=float))
    z = np.atleast_1d(np.asarray(z, dtype=float))
    lm = model.lm
    if np.any(r < 0) or np.any(r > lm.L) or np.any(z < 0) or np.any(z > lm.D):
        raise CoatHertzError(f"fem stresses: points must satisfy 0 <= r <= {lm.L:g} m and "
                             f"0 <= z <= {lm.D:g} m (the meshed body)")
    sf = StressField(model, x) if field is None else field
    n_reg = len(model.regions)
    out = np.empty((z.size, 4, r.size))
    for j, zj in enumerate(z):
        if lm.h > 0 and n_reg > 1:
            below = zj > lm.h or (zj == lm.h and side == "below")
            k = 1 if below else 0
        else:
            k = 0
        if lm.h > 0 and n_reg == 1 and zj > lm.h:
            raise CoatHertzError(f"fem stresses: depth {zj:g} m lies in the rigid base (valid: 0 to "
                                 f"{lm.h:g} m)")
        # the probes search the whole mesh: a point on the interface (or on the mesh's bottom)
        # is moved 1e-9 h into the region whose values are read (an O(1e-9 h) shift)
        zq = zj
        if lm.h > 0 and abs(zj - lm.h) <= 1e-12 * lm.h:
            zq = lm.h * (1.0 + 1e-9) if k == 1 else lm.h * (1.0 - 1e-9)
        zq = min(zq, (lm.h if n_reg == 1 and lm.h > 0 else lm.D) * (1.0 - 1e-12))
        rq = np.clip(r, 1e-9 * lm.a_ref, lm.L * (1.0 - 1e-12))  # the axis too lies on the border
        pts = np.vstack([rq, np.full(r.size, -zq)])
        srr, szz, stt, srz = sf.at(k, pts)
        out[j] = np.array([srr, stt, szz, -srz])
    return out


def solve_and_sample(case: ContactCase, r, z, method: FEMMethod | None = None,
                     side: str = "above") -> tuple[ContactResult, np.ndarray]:
    """Solve ``case`` with the FE method (default settings unless ``method``) and sample its
    stresses (:func:`sample`) in the deformable body of the model."""
    m = FEMMethod() if method is None else method
    res, model, path = m.solve_full(case)
    return res, sample(model, path.x, r, z, side)
