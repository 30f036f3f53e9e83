r"""Layer factor ``F(kh)`` of an ordered stack of layers on a substrate.

A body with layers ``i = 1..N`` (top first; material ``E_i, nu_i``, thickness ``h_i``; each
interface bonded or frictionless) on an elastic or rigid substrate has, for a normal surface
pressure ``P cos kx`` (plane strain along ``k``; axisymmetric loads superpose such waves), the
surface displacement ``u_z = 2 F(k) P / (E_1^* k)``: ``F`` generalises eq (13) (``F -> 1`` for
``k -> inf``, ``F -> E_1^*/E_s^*`` for ``k -> 0``, ``0`` on a rigid substrate).

Method (Airy stress function ``phi = f(z) cos x`` with ``k = 1``, ``z`` down into the body;
``f'''' - 2 f'' + f = 0``): ``sigma_zz = -f``, ``sigma_xz = f'``, ``u_x = ((1-nu) f'' + nu f)/(2G)``,
``u_z = (-(2-nu) f' + (1-nu) f''')/(2G)`` (amplitudes of ``cos x``, ``sin x``; ``u_z`` is fixed by
the compatibility ``f''' + int f = 2 f'``): ``state = S (f, f', f'', f''')``. The admissible
states ``(u_z, u_x, sigma_zz, sigma_xz)`` at the top of what lies below form a plane (a
two-dimensional subspace of C^4), carried as its Plücker coordinates: the antisymmetric 4x4 matrix
``X = b_1 b_2^T - b_2 b_1^T`` of any two states spanning it (the compound-matrix method: no null
spaces, no pivoting; linear in ``X`` and polynomial in ``e^{-t}`` and ``t``, so complex ``k``
continues analytically). Half-space: ``(A + Bz) e^{-z}``; rigid bonded: ``u = 0``; a frictionless
interface keeps the member ``v`` of the plane with ``sigma_xz = 0`` and frees ``u_x``. Through a
layer of ``t = kh`` (``X`` scaled to ``max |X_ij| = 1`` after each):

* ``|t| < 1``: ``X -> T X T^T``, ``T = e^{-t} S e^{-tC} S^{-1}``, the transfer matrix from the
  layer's bottom to its top (``e^{-tC}`` from ``cosh``, ``sinh``, ``z cosh``, ``z sinh``): bounded,
  ``-> I`` as ``t -> 0`` with absolute errors ~1e-16 in its ``O(t)`` entries, so a thin layer on a
  rigid base (``F ~ t``; ``F ~ t^3`` when incompressible) keeps its digits;
* ``|t| >= 1``: in the bounded basis ``e^{-z}, z e^{-z}, e^{z-t}, (t-z) e^{z-t}``
  (``M(z) = S Psi(z)``; no growing exponential, and the four stay independent), the top states
  ``M(0) c`` of the solutions whose bottom states ``M(t) c`` lie in the plane:
  ``X -> M(0) *(M(t)^T (*X) M(t)) M(0)^T``, ``*`` the Hodge dual (the plane's annihilator). Here
  ``T`` would not do: its entries grow like ``t`` and its 2x2 minors cancel ``t^2`` of them;
* ``Re t >= 25``: the layer's own half-space (what lies below enters as ``t^2 e^{-2t} < 1e-19``).

At the surface ``sigma_zz = -1``, ``sigma_xz = 0`` give ``u_z = -X_03 / X_23``. Accuracy:
``|dF| <= 5.3e-15`` against the one-layer closed forms of :mod:`coathertz.axisym.kernel` for
``kh = 1e-8 .. 300``; 400 random stacks agree with the former null-space (QR) form to 2.5e-13 of
``max(|F|, 1)``, real and complex ``k``. All of it is batched over ``k``.

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


def _S(mat: Material, G_ref: float) -> np.ndarray:
    """``S`` with ``(u_z, u_x, sigma_zz, sigma_xz) = S (f, f', f'', f''')`` (displacements in
    units of ``1/G_ref``, so that all four rows are of order one)."""
    G2 = mat.E / (1.0 + mat.nu) / G_ref  # 2 G / G_ref
    nu = mat.nu
    return np.array([[0.0, -(2.0 - nu) / G2, 0.0, (1.0 - nu) / G2],
                     [nu / G2, 0.0, (1.0 - nu) / G2, 0.0],
                     [-1.0, 0.0, 0.0, 0.0],
                     [0.0, 1.0, 0.0, 0.0]])


#: ``f, f', f'', f'''`` at ``z = 0`` of ``cosh z, sinh z, z cosh z, z sinh z`` (columns).
_PHI0 = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 1.0, 0.0], [1.0, 0.0, 0.0, 2.0], [0.0, 1.0, 3.0, 0.0]])
_PHI0_INV = np.linalg.inv(_PHI0)
#: ``f, f', f'', f'''`` at ``z = 0`` of the half-space modes ``e^{-z}``, ``z e^{-z}`` (columns).
_DECAYING0 = np.array([[1.0, 0.0], [-1.0, 1.0], [1.0, -2.0], [-1.0, 3.0]])

#: The transfer matrix serves ``|t| < T_THIN``, the bounded basis ``|t| >= T_THIN``; a layer with
#: ``Re t >= T_DEEP`` is its own half-space to ``t^2 e^{-2t} < 1e-19`` (module docstring).
T_THIN, T_DEEP = 1.0, 25.0


def _const_congruence(A: np.ndarray, X: np.ndarray) -> np.ndarray:
    """``A X A^T`` for one ``(4, 4)`` matrix ``A`` and a batch ``X`` ``(n, 4, 4)`` (two BLAS
    products on the stacked rows instead of ``n`` small ones)."""
    n = X.shape[0]
    A = A.astype(X.dtype)
    Y = (X.reshape(4 * n, 4) @ A.T).reshape(n, 4, 4)  # X A^T
    return (np.swapaxes(Y, 1, 2).reshape(4 * n, 4) @ A.T).reshape(n, 4, 4).swapaxes(1, 2)


def _plucker(B: np.ndarray) -> np.ndarray:
    """``b_1 b_2^T - b_2 b_1^T`` of the columns of ``B`` (``(..., 4, 2)``): the span's Plücker
    coordinates as an antisymmetric ``(..., 4, 4)`` matrix."""
    b1, b2 = B[..., :, 0], B[..., :, 1]
    return b1[..., :, None] * b2[..., None, :] - b2[..., :, None] * b1[..., None, :]


def _star(X: np.ndarray) -> np.ndarray:
    """Hodge dual ``(*X)_ij = eps_ijkl X_kl / 2``: the Plücker coordinates of the annihilator
    (the two linear forms that vanish on the plane; no complex conjugation)."""
    Y = np.zeros_like(X)
    Y[..., 0, 1], Y[..., 0, 2], Y[..., 0, 3] = X[..., 2, 3], -X[..., 1, 3], X[..., 1, 2]
    Y[..., 1, 2], Y[..., 1, 3], Y[..., 2, 3] = X[..., 0, 3], -X[..., 0, 2], X[..., 0, 1]
    return Y - np.swapaxes(Y, -1, -2)


def _frictionless(X: np.ndarray) -> np.ndarray:
    """The plane above a frictionless interface: ``v``, the member of the plane ``X`` with
    ``sigma_xz = 0`` (``v_i = X_i3``), and the free ``u_x`` (``e_1``): ``v e_1^T - e_1 v^T``."""
    Y = np.zeros_like(X)
    Y[..., 0, 1], Y[..., 1, 0] = X[..., 0, 3], -X[..., 0, 3]
    Y[..., 2, 1], Y[..., 1, 2] = X[..., 2, 3], -X[..., 2, 3]
    return Y


def _through_thin(X: np.ndarray, t: np.ndarray, S: np.ndarray) -> np.ndarray:
    """``T X T^T`` with ``T = e^{-t} S e^{-tC} S^{-1}`` (``|t| < T_THIN``): the states at the top
    of the layer from those at its bottom, ``e^{-tC} = Phi(-t) Phi(0)^{-1}`` with ``Phi`` the
    derivatives of ``cosh z, sinh z, z cosh z, z sinh z`` (columns)."""
    E = np.exp(-2.0 * t)
    c = 0.5 * (1.0 + E)  # e^{-t} cosh(-t)
    s = 0.5 * np.expm1(-2.0 * t)  # e^{-t} sinh(-t)
    z = -t
    zc, zs = z * c, z * s
    P = np.empty((t.size, 4, 4), dtype=t.dtype)
    P[:, 0, 0] = P[:, 2, 0] = P[:, 1, 1] = P[:, 3, 1] = c
    P[:, 1, 0] = P[:, 3, 0] = P[:, 0, 1] = P[:, 2, 1] = s
    P[:, 0, 2], P[:, 1, 2], P[:, 2, 2], P[:, 3, 2] = zc, c + zs, 2.0 * s + zc, 3.0 * c + zs
    P[:, 0, 3], P[:, 1, 3], P[:, 2, 3], P[:, 3, 3] = zs, s + zc, 2.0 * c + zs, 3.0 * s + zc
    Y = _const_congruence(_PHI0_INV @ np.linalg.inv(S), X)
    return _const_congruence(S, P @ Y @ np.swapaxes(P, 1, 2))


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


def _through_thick(X: np.ndarray, t: np.ndarray, S: np.ndarray) -> np.ndarray:
    """``M(0) * (M(t)^T (*X) M(t)) M(0)^T`` (``|t| >= T_THIN``) in the bounded basis
    ``e^{-z}, z e^{-z}, e^{z-t}, (t-z) e^{z-t}`` (state matrix ``M(z) = S Psi(z)``, ``Psi`` from
    :func:`_basis`): the plane of the top states ``M(0) c`` of the solutions whose bottom states
    ``M(t) c`` lie in ``X``."""
    Pt = np.moveaxis(_basis(t, t), -1, 0)  # Psi(t), (n, 4 derivs, 4 funcs)
    P0 = np.moveaxis(_basis(np.zeros_like(t), t), -1, 0)  # Psi(0)
    Q = _const_congruence(S.T, _star(X))  # S^T (*X) S
    Q = _star(np.swapaxes(Pt, 1, 2) @ Q @ Pt)
    return _const_congruence(S, P0 @ Q @ np.swapaxes(P0, 1, 2))


def stack_layer_factor(layers: Sequence[StackLayer], substrate: Material, k: np.ndarray) -> np.ndarray:
    """``F(k)`` of ``layers`` (top first) on ``substrate`` (``RIGID`` allowed), ``k`` in 1/m
    (complex ``k`` gives the analytic continuation: every step is a polynomial in the entries,
    and the scalings cancel in the ratio that gives ``F``).

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
    k = k.astype(complex if np.iscomplexobj(k) else float).ravel()
    n = k.size
    top = layers[0].material
    G_ref = top.E / (2.0 * (1.0 + top.nu))
    X = np.zeros((n, 4, 4), dtype=k.dtype)
    if substrate.is_rigid:
        X[:, 2, 3], X[:, 3, 2] = 1.0, -1.0  # u = 0, any traction: span(e_2, e_3)
    else:
        X[:] = _plucker(_S(substrate, G_ref) @ _DECAYING0)  # (A + B z) e^{-z} at z = 0
    if layers[-1].interface == "frictionless":
        X = _frictionless(X)
    for j in range(len(layers) - 1, -1, -1):
        L = layers[j]
        S = _S(L.material, G_ref)
        t = k * L.h
        thin = np.abs(t) < T_THIN
        deep = ~thin & (t.real >= T_DEEP) & (np.abs(t.imag) <= t.real)
        mid = ~thin & ~deep
        Xn = np.empty_like(X)
        if np.any(thin):
            Xn[thin] = _through_thin(X[thin], t[thin], S)
        if np.any(mid):
            Xn[mid] = _through_thick(X[mid], t[mid], S)
        if np.any(deep):
            Xn[deep] = _plucker(S @ _DECAYING0)  # the layer's own half-space
        # only the plane counts: scale its coordinates to at most 1 (no overflow through the stack)
        X = Xn / np.abs(Xn).max(axis=(1, 2), keepdims=True)
        if j > 0 and layers[j - 1].interface == "frictionless":
            X = _frictionless(X)
    # surface: sigma_zz = -1, sigma_xz = 0: u_z = -X_03 / X_23 (Cramer's rule on the two columns)
    uz = -X[:, 0, 3] / X[:, 2, 3]
    return 0.5 * top.E_star * uz / G_ref


# --- The layer states in the bounded basis (:func:`_basis`, the one definition that F above also
# uses), for fields *inside* the layers (the FFT stresses of a stack,
# :mod:`coathertz.fft.stack_stresses`, sweep spanning states with these; F uses the Plücker form).


def _state(f: np.ndarray, G: float, nu: float) -> np.ndarray:
    """``(u_z, u_x, sigma_zz, sigma_xz)`` from ``f, f', f'', f'''`` (shape ``(4, ...)``)."""
    f0, f1, f2, f3 = f
    return np.stack([(-(2.0 - nu) * f1 + (1.0 - nu) * f3) / (2.0 * G),
                     ((1.0 - nu) * f2 + nu * f0) / (2.0 * G), -f0, f1])


def state_matrix(z: np.ndarray, t: np.ndarray, mat: Material, G_ref: float) -> np.ndarray:
    """State matrix ``(..., 4 states, 4 funcs)`` of a layer at depth ``z`` (displacements in units
    of ``1/G_ref``, so that all four rows are of order one)."""
    G = mat.E / (2.0 * (1.0 + mat.nu)) / G_ref
    st = _state(_basis(z, t), G, mat.nu)  # (4 states, 4 funcs, ...)
    return np.moveaxis(st, (0, 1), (-2, -1))


def half_space_states(k: np.ndarray, mat: Material, G_ref: float) -> np.ndarray:
    """Admissible top states of an elastic half-space: ``f = (A + B z) e^{-z}`` at ``z = 0``."""
    G = mat.E / (2.0 * (1.0 + mat.nu)) / G_ref
    z = np.zeros_like(k)
    b = _basis(z, z)[:, :2]  # (4 derivs, 2 funcs, n)
    return np.moveaxis(_state(b, G, mat.nu), (0, 1), (-2, -1))


def frictionless_span(B: np.ndarray) -> np.ndarray:
    """The subspace above a frictionless interface, as two spanning states (columns of ``B``,
    ``(..., 4, 2)``): the member of ``span(B)`` with ``sigma_xz = 0`` and a free ``u_x`` (the
    spanning-state form of the Plücker ``_frictionless``, for fields inside the layers)."""
    c = np.stack([B[..., 3, 1], -B[..., 3, 0]], axis=-1)  # B c has sigma_xz = 0
    v = np.einsum("...ij,...j->...i", B, c)
    v = v / np.linalg.norm(v, axis=-1, keepdims=True)
    e = np.zeros_like(v)  # same dtype (complex k: analytic continuation for Taylor coefficients)
    e[..., 1] = 1.0
    return np.stack([v, e], axis=-1)
