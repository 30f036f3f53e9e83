r"""Layer factor ``F(kh)`` of an ordered stack of layers on a substrate.

A body with layers ``i = 1..N`` (top first; material ``E_i, nu_i``, thickness ``h_i``; each
interface bonded or frictionless) on an elastic or rigid substrate has, for a normal surface
pressure ``P cos kx`` (plane strain along ``k``; axisymmetric loads superpose such waves), the
surface displacement ``u_z = 2 F(k) P / (E_1^* k)``: ``F`` generalises eq (13) (``F -> 1`` for
``k -> inf``, ``F -> E_1^*/E_s^*`` for ``k -> 0``, ``0`` on a rigid substrate).

Method (Airy stress function ``phi = f(z) cos x`` with ``k = 1``, ``z`` down into the body;
``f'''' - 2 f'' + f = 0``): ``sigma_zz = -f``, ``sigma_xz = f'``, ``u_x = ((1-nu) f'' + nu f)/(2G)``,
``u_z = (-(2-nu) f' + (1-nu) f''')/(2G)`` (amplitudes of ``cos x``, ``sin x``; ``u_z`` is fixed by
the compatibility ``f''' + int f = 2 f'``). In a layer ``0 <= z <= t`` the solutions are written in
the bounded basis ``e^{-z}, z e^{-z}, e^{z-t}, (t-z) e^{z-t}``: no growing exponential, and the
four stay independent as ``t -> 0``. The admissible states ``(u_z, u_x, sigma_zz, sigma_xz)`` at the
top of what lies below are a two-dimensional subspace (columns of a 4x2 matrix ``B``): half-space
``(A + Bz) e^{-z}``; rigid bonded ``u = 0``; rigid or elastic frictionless ``sigma_xz = 0`` with
``u_x`` free. A bonded interface passes ``B`` unchanged; a frictionless one keeps the member of
``span(B)`` with ``sigma_xz = 0`` and frees ``u_x``. Through a layer the new subspace is
``M(0) C`` with ``[C; D]`` spanning the null space of ``[M(t), -B]`` (complete QR): a bounded, well-scaled
4x6 problem at any ``t`` (for thick layers the columns of the modes decaying from the top vanish
at the bottom and the layer acts as a half-space, as it should). At the surface
``sigma_zz = -P``, ``sigma_xz = 0`` give ``u_z``. All of it is batched over ``k``.

This is the *definition* of the kernel, shared like the case model (hashed with it in
:data:`~coathertz.methods.SHARED_SOURCES`); :mod:`coathertz.axisym` and the FFT each use and test
it on their own.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from coathertz.errors import CoatHertzError
from coathertz.materials import Material

INTERFACES = ("bonded", "frictionless")


@dataclass(frozen=True)
class StackLayer:
    """One layer: ``material``, thickness ``h`` [m] and how its *lower* face is joined to what
    lies below (``bonded`` or ``frictionless``)."""

    material: Material
    h: float
    interface: str = "bonded"


def _state(f: np.ndarray, G: float, nu: float) -> np.ndarray:
    """``(u_z, u_x, sigma_zz, sigma_xz)`` from ``f, f', f'', f'''`` (shape ``(4, ...)``)."""
    f0, f1, f2, f3 = f
    return np.stack([(-(2.0 - nu) * f1 + (1.0 - nu) * f3) / (2.0 * G),
                     ((1.0 - nu) * f2 + nu * f0) / (2.0 * G), -f0, f1])


def _basis(z: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``f, f', f'', f'''`` of the four bounded basis functions at depth ``z`` in a layer of
    thickness ``t`` (``z``, ``t`` arrays of the same shape): shape ``(4 derivs, 4 funcs, ...)``."""
    e1 = np.exp(-z)
    e2 = np.exp(z - t)
    s = t - z
    out = np.empty((4, 4, *np.shape(z)), dtype=np.result_type(z, t, float))
    # e^{-z}
    out[:, 0] = np.stack([e1, -e1, e1, -e1])
    # z e^{-z}
    out[:, 1] = np.stack([z * e1, (1.0 - z) * e1, (z - 2.0) * e1, (3.0 - z) * e1])
    # e^{z - t}
    out[:, 2] = np.stack([e2, e2, e2, e2])
    # (t - z) e^{z - t} = s e^{-s}, d/dz = -d/ds
    out[:, 3] = np.stack([s * e2, -(1.0 - s) * e2, (s - 2.0) * e2, -(3.0 - s) * e2])
    return out


def _M(z: np.ndarray, t: np.ndarray, mat: Material, G_ref: float) -> np.ndarray:
    """State matrix ``(..., 4 states, 4 funcs)`` of a layer at depth ``z`` (displacements in units
    of ``1/G_ref``, so that all four rows are of order one)."""
    G = mat.E / (2.0 * (1.0 + mat.nu)) / G_ref
    st = _state(_basis(z, t), G, mat.nu)  # (4 states, 4 funcs, ...)
    return np.moveaxis(st, (0, 1), (-2, -1))


def _half_space(k: np.ndarray, mat: Material, G_ref: float) -> np.ndarray:
    """Admissible top states of an elastic half-space: ``f = (A + B z) e^{-z}`` at ``z = 0``."""
    G = mat.E / (2.0 * (1.0 + mat.nu)) / G_ref
    z = np.zeros_like(k)
    b = _basis(z, z)[:, :2]  # (4 derivs, 2 funcs, n)
    return np.moveaxis(_state(b, G, mat.nu), (0, 1), (-2, -1))


def _frictionless(B: np.ndarray) -> np.ndarray:
    """The subspace above a frictionless interface: the member of ``span(B)`` with
    ``sigma_xz = 0`` and a free ``u_x``."""
    c = np.stack([B[..., 3, 1], -B[..., 3, 0]], axis=-1)  # B c has sigma_xz = 0
    v = np.einsum("...ij,...j->...i", B, c)
    v = v / np.linalg.norm(v, axis=-1, keepdims=True)
    e = np.zeros_like(v)  # same dtype (complex k: analytic continuation for Taylor coefficients)
    e[..., 1] = 1.0
    return np.stack([v, e], axis=-1)


def stack_layer_factor(layers: Sequence[StackLayer], substrate: Material, k: np.ndarray) -> np.ndarray:
    """``F(k)`` of ``layers`` (top first) on ``substrate`` (``RIGID`` allowed), ``k`` in 1/m
    (complex ``k`` gives the analytic continuation: the null space is unique, only its basis
    depends on the factorisation).

    Raises
    ------
    CoatHertzError
        Empty stack, a negative thickness or an unknown interface (the message names the layer).
    """
    if not layers:
        raise CoatHertzError("stack: the layer stack is empty (give at least one layer)")
    for i, L in enumerate(layers, 1):
        if not (np.isfinite(L.h) and L.h >= 0.0):
            raise CoatHertzError(f"stack: layer {i} thickness h must be >= 0 m, got {L.h!r}")
        if L.interface not in INTERFACES:
            raise CoatHertzError(f"stack: layer {i} interface must be one of {INTERFACES}, "
                                 f"got {L.interface!r}")
        if L.material.is_rigid:
            raise CoatHertzError(f"stack: layer {i} must be elastic (a rigid layer hides the stack)")
    k = np.atleast_1d(np.asarray(k))
    k = k.astype(complex if np.iscomplexobj(k) else float)
    n = k.size
    top = layers[0].material
    G_ref = top.E / (2.0 * (1.0 + top.nu))
    if substrate.is_rigid:
        B = np.zeros((n, 4, 2), dtype=k.dtype)
        B[:, 2, 0] = B[:, 3, 1] = 1.0  # u = 0, any traction
        if layers[-1].interface == "frictionless":
            B = _frictionless(B)
    else:
        B = _half_space(k, substrate, G_ref)
        if layers[-1].interface == "frictionless":
            B = _frictionless(B)
    for j in range(len(layers) - 1, -1, -1):
        L = layers[j]
        t = k * L.h
        Mt = _M(t, t, L.material, G_ref)
        M0 = _M(np.zeros_like(t), t, L.material, G_ref)
        A = np.concatenate([Mt, -B], axis=-1)  # (n, 4, 6)
        # null space (A N = 0, (n, 6, 2)): the complement of A's rows, from a complete QR of A^H
        # (A has full rank 4; 2.4x faster than the SVD, the same space)
        Q, _ = np.linalg.qr(np.swapaxes(A, -1, -2).conj(), mode="complete")
        N = Q[:, :, 4:]
        B = M0 @ N[:, :4, :]
        B = B / np.linalg.norm(B, axis=-2, keepdims=True)
        if j > 0 and layers[j - 1].interface == "frictionless":
            B = _frictionless(B)
    # surface: sigma_zz = -1, sigma_xz = 0
    c = np.linalg.solve(B[:, 2:, :], np.broadcast_to(np.array([-1.0, 0.0]), (n, 2))[..., None])
    uz = (B[:, 0:1, :] @ c)[:, 0, 0]
    return 0.5 * top.E_star * uz / G_ref
