"""What designers read from a stress field: the maxima, with their locations, of the stresses
that decide where a coating yields, cracks or delaminates.

Method-independent: works on any field sampled on ``(z, component, y, x)`` in the Voigt order
``xx, yy, zz, yz, xz, xy`` [Pa], positions in m. Tension is positive.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from coathertz.materials import Body

#: The stress components in the order of a field's component axis (Voigt order).
COMPONENTS = ("xx", "yy", "zz", "yz", "xz", "xy")


def von_mises(sig: np.ndarray, axis: int = 1) -> np.ndarray:
    """Von Mises stress of a field with the six components (:data:`COMPONENTS` order) on
    ``axis``."""
    xx, yy, zz, yz, xz, xy = np.moveaxis(sig, axis, 0)
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (yz**2 + xz**2 + xy**2))


def first_principal(sig: np.ndarray) -> np.ndarray:
    """Largest principal stress (tension positive) of a ``(nz, 6, ny, nx)`` field: the
    trigonometric root of the characteristic cubic of the symmetric 3 x 3 tensor (closed form,
    vectorised; the largest root is well conditioned also where two roots coincide, as on the
    axis of a circular contact)."""
    xx, yy, zz, yz, xz, xy = (sig[:, j] for j in range(6))
    q = (xx + yy + zz) / 3.0
    off = xy**2 + xz**2 + yz**2
    p = np.sqrt(((xx - q) ** 2 + (yy - q) ** 2 + (zz - q) ** 2 + 2.0 * off) / 6.0)
    ps = np.where(p > 0, p, 1.0)
    bx, by, bz = (xx - q) / ps, (yy - q) / ps, (zz - q) / ps
    bxy, bxz, byz = xy / ps, xz / ps, yz / ps
    det = bx * (by * bz - byz**2) - bxy * (bxy * bz - byz * bxz) + bxz * (bxy * byz - by * bxz)
    phi = np.arccos(np.clip(0.5 * det, -1.0, 1.0)) / 3.0
    return q + 2.0 * p * np.cos(phi)


def _entry(values: np.ndarray, mask: np.ndarray, x, y, z, p0: float) -> dict | None:
    if not np.any(mask):
        return None
    v = np.where(mask, values, -np.inf)
    k, j, i = np.unravel_index(np.argmax(v), v.shape)
    val = float(v[k, j, i])
    return {"value": val, "over_p0": val / p0, "at": [float(x[i]), float(y[j]), float(z[k])]}


def summarise(body: Body, x, y, z, sigma: np.ndarray, p0: float,
              interface_sigma: np.ndarray | None = None,
              interfaces: Sequence[tuple[float, np.ndarray]] | None = None) -> dict:
    """The designer's maxima, each ``{value [Pa], over_p0, at: [x, y, z] m}``.

    ``interface_sigma`` (``(6, ny, nx)``): the coating side of the interface ``z = h``, for
    the interface shear ``sqrt(sigma_xz^2 + sigma_yz^2)`` and normal (tension) stress; or
    ``interfaces``: ``(depth, sigma (6, ny, nx))`` for each interface of a layer stack (the
    maxima over all of them). "Coating" is everything above the substrate (all layers of a
    stack). Entries that do not apply (no coating) are ``None``.
    """
    z = np.asarray(z, dtype=float)
    vm = von_mises(sigma)
    s1 = first_principal(sigma)
    shape = vm.shape
    depth = np.broadcast_to(z[:, None, None], shape)
    h = sum(L.h for L in body.stack) if body.stack else None
    in_coating = depth <= h if h is not None else np.zeros(shape, bool)
    everywhere = np.ones(shape, bool)
    out = {
        "vm_max": _entry(vm, everywhere, x, y, z, p0),
        "vm_max_coating": _entry(vm, in_coating, x, y, z, p0),
        "vm_max_substrate": _entry(vm, ~in_coating, x, y, z, p0),
        "tensile_max_surface": _entry(s1, depth == 0, x, y, z, p0),
        "tensile_max": _entry(s1, in_coating if h is not None else everywhere, x, y, z, p0),
        "interface_shear_max": None,
        "interface_normal_max": None,
    }
    if interfaces is None and h is not None and interface_sigma is not None:
        interfaces = ((h, interface_sigma),)
    if h is not None and interfaces:
        zi = np.array([d for d, _ in interfaces], dtype=float)
        sig = np.stack([s for _, s in interfaces])  # (n_int, 6, ny, nx)
        shear = np.hypot(sig[:, 3], sig[:, 4])
        ones = np.ones(shear.shape, bool)
        out["interface_shear_max"] = _entry(shear, ones, x, y, zi, p0)
        out["interface_normal_max"] = _entry(sig[:, 2], ones, x, y, zi, p0)
    return out
