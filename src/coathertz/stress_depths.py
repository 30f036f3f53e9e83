"""The default depths at which a body's stresses are evaluated (every stress method: the FFT,
the exact axisymmetric method and the FE read the same points, so their fields can be compared
point by point). A definition on the case model, like the materials; no solver code."""

from __future__ import annotations

import numpy as np

from coathertz.materials import Body


def default_depths(body: Body, a: float) -> np.ndarray:
    """Depths [m] below the surface of ``body`` for a contact of radius ``a`` [m].

    Homogeneous: 0 to ``a`` in 40 steps, ``a`` to ``3a`` in 20. Coated or stacked (total
    thickness ``H``): 16 steps through each layer, each interface depth (the layer above) and
    ``1e-9`` of it deeper (the layer below), then 32 geometric steps from ``H (1 + 1e-9)`` to
    ``max(3a, 2H)`` (none on a rigid substrate, whose depths end at ``H``).
    """
    parts = [L for L in body.stack if L.h > 0]
    if not parts:
        return np.concatenate([np.linspace(0, a, 41), np.linspace(a, 3 * a, 21)[1:]])
    zs, z0 = [np.zeros(1)], 0.0
    for i, L in enumerate(parts):
        if i:  # the lower side of the interface above
            zs.append(np.array([z0 * (1 + 1e-9)]))
        zs.append(z0 + np.linspace(0, L.h, 17)[1:])
        z0 += L.h
    if not body.material.is_rigid:
        zs.append(np.geomspace(z0 * (1 + 1e-9), max(3 * a, 2 * z0), 32))
    return np.concatenate(zs)
