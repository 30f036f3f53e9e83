r"""Stress responses inside every layer of a stack (N layers on an elastic or rigid substrate).

The FFT stresses (:mod:`coathertz.fft.stresses`) need, per wavenumber ``w = |k|`` and depth
``z``, the plane-strain field along ``k`` under three unit surface loads: a pressure
``P cos kx`` (rows ``normal``), a shear ``Q cos kx`` along ``k`` (``tangential``) and a shear
``Q cos kx`` normal to ``k`` (``antiplane``), in the conventions of
:class:`coathertz.fft.stress_rows.StressRows`.

In-plane loads (Airy function, the kernel definition of :mod:`coathertz.stack`)
--------------------------------------------------------------------------------
With ``k = 1`` (scaled depth ``s = w z``) each layer carries ``phi = f(s) cos x`` (normal load)
or ``f(s) sin x`` (tangential load), ``f'''' - 2 f'' + f = 0``:

    sigma_kk = f'',  sigma_pp = nu (f'' - f) (plane strain),  sigma_zz = -f,
    sigma_kz = f' sin x (normal load) or -f' cos x (tangential load),

so both loads have the rows ``(S_kk, S_pp, S_zz, S_kz) = (f'', nu (f'' - f), -f, f')`` and
differ only in the surface conditions: ``(sigma_zz, sigma_kz) = (-1, 0)``, i.e. ``f(0) = 1,
f'(0) = 0`` (normal) or ``f(0) = 0, f'(0) = 1`` (tangential: ``sigma_kz(0) = -Q cos kx``). In a
layer of scaled thickness ``t = w h`` (local depth ``0 <= s <= t``, ``u = t - s``)
``f = c_1 e^{-s} + c_2 s e^{-s} + c_3 e^{-u} + c_4 u e^{-u}`` (the bounded basis of
:mod:`coathertz.stack`: no growing exponential, independent as ``t -> 0``); in an elastic
substrate ``f = c_1 e^{-s} + c_2 s e^{-s}``.

The coefficients come from a null-space sweep over the stack kernel's own layer states (the
:mod:`coathertz.stack` definitions ``state_matrix``, ``half_space_states``,
``frictionless_span``; the kernel itself carries Plücker coordinates), recorded and run back down:

* *Up.* ``B_j`` (4 x 2, orthonormalised columns) spans the admissible states
  ``(u_z, u_k, sigma_zz, sigma_kz)`` at the top of layer ``j`` and everything below it. Start
  from the substrate (half-space or rigid); through layer ``j`` the null space ``N_j`` (6 x 2)
  of ``[M_j(t), -B'_{j+1}]`` (complete QR) gives ``B_j = M_j(0) N_j[:4] / n_j`` (``n_j`` the
  column norms), where ``B'`` is ``B`` itself below a bonded face and, below a frictionless one,
  ``[v, e_k]`` with ``v = B c_0 / |B c_0|``, ``c_0 = (B_{kz,2}, -B_{kz,1})`` (the member with
  ``sigma_kz = 0``) and ``e_k`` a free tangential slip.
* *Surface.* ``B_1[rows zz, kz] c_1 = (-1, 0)`` or ``(0, 1)`` (both loads in one solve).
* *Down.* Layer ``j``'s coefficients are ``N_j[:4] (c_j / n_j)``; the state below it is
  ``B'_{j+1} d``, ``d = N_j[4:] (c_j / n_j)``: ``c_{j+1} = d`` through a bonded face and
  ``c_{j+1} = c_0 d_1 / |B_{j+1} c_0|`` through a frictionless one (``d_2`` is the slip). The
  substrate's coefficients are the ``c`` below the last layer (its ``B`` is not normalised).

Every step is a bounded, well-scaled small system at any ``t``; ``nu = 0.5`` is allowed
(nothing divides by ``1 - 2 nu``).

Antiplane load (shear normal to ``k``)
--------------------------------------
The displacement ``u_p = U(s) cos x`` solves ``U'' = U``; with ``V = G w U`` (a stress)
``sigma_pz = dV/ds cos x`` and ``sigma_kp = -V sin x``: rows ``(kp, pz) = (V, V')``. In layer
``j`` ``V = alpha e^{-s} + beta e^{-u}``. What lies below a layer acts on its lower face as
``sigma_pz = -K w U`` with an effective modulus ``K`` (half-space ``G_s``; rigid bonded
``inf``; frictionless face or rigid frictionless base ``0``); with ``r = K / G_j`` the lower face
gives ``beta = rho alpha e^{-t}``, ``rho = (1 - r)/(1 + r)`` in ``[-1, 1]``, and the layer passes
up ``K_top = G_j (1 - rho e^{-2t})/(1 + rho e^{-2t})`` (bottom up). At the surface
``sigma_pz(0) = -1``: ``alpha_1 = 1 / (1 - rho_1 e^{-2 t_1})``. Down through a bonded face ``U``
and ``sigma_pz`` are continuous; ``alpha_{j+1}`` is taken from ``V_{top} = (G_{j+1}/G_j) V_{bottom}``
(``alpha (1 + rho e^{-2t}) = V_top``) where ``rho >= 0`` and from ``sigma_pz`` (``-alpha
(1 - rho e^{-2t}) = sigma_bottom``) where ``rho < 0``, so the divisor is never below 1 - e^{-2t}
of the larger kind; a frictionless face unloads everything below (``alpha = 0``). Substrate:
``V = (G_s / G_N) V_{N,bottom} e^{-s}``.

A single layer reproduces :class:`coathertz.fft.stresses.CoatedStressFRF` (Papkovich--Neuber,
one 6 x 6 solve) to round-off (``tests/stresses/test_fft_stack_stresses.py``).

Depths on an interface belong to the layer above (its lower face); the layer below is reached
by any depth beyond it (e.g. ``z (1 + 1e-9)``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from coathertz.errors import CoatHertzError
from coathertz.fft.stress_rows import StressRows
from coathertz.materials import Material
from coathertz.stack import StackLayer, frictionless_span, half_space_states, state_matrix

#: Smallest ``w H`` solved (``H`` the stack's thickness); ``w = 0`` is evaluated there.
T_MIN = 1e-6


@dataclass(frozen=True)
class StackCoefficients:
    """Basis coefficients per wavenumber (last axis): ``layers[j]`` ``(4, 2, n)`` (basis function,
    load normal/tangential), ``sub`` ``(2, 2, n)`` (``None`` on a rigid base), ``anti[j]``
    ``(2, n)`` (``alpha, beta``), ``anti_sub`` ``(n,)``."""

    layers: list
    sub: np.ndarray | None
    anti: list
    anti_sub: np.ndarray | None


@dataclass(frozen=True)
class StackStressFRF:
    """Stress responses of ``layers`` (top first, :class:`~coathertz.stack.StackLayer`: material,
    thickness [m], interface of the lower face) on ``substrate`` (``RIGID`` allowed).

    Same interface as :class:`~coathertz.fft.stresses.CoatedStressFRF`: :meth:`coefficients`
    once per set of wavenumbers, :meth:`at` per depth.
    """

    layers: tuple
    substrate: Material

    def __post_init__(self) -> None:
        layers = tuple(self.layers)
        if not layers:
            raise CoatHertzError("fft stresses: the layer stack is empty (give at least one layer)")
        for i, L in enumerate(layers, 1):
            if not (np.isfinite(L.h) and L.h > 0):
                raise CoatHertzError(f"fft stresses: layer {i} thickness h must satisfy 0 < h < inf "
                                     f"[m], got {L.h!r}")
            if L.interface not in ("bonded", "frictionless"):
                raise CoatHertzError(f"fft stresses: layer {i} interface must be 'bonded' or "
                                     f"'frictionless', got {L.interface!r}")
            if L.material.is_rigid:
                raise CoatHertzError(f"fft stresses: layer {i} must be elastic (0 < E < inf)")
        object.__setattr__(self, "layers", layers)

    @classmethod
    def of(cls, layers: Sequence, substrate: Material) -> StackStressFRF:
        """From any layers with ``material``, ``h``, ``interface``
        (e.g. :class:`coathertz.materials.Layer`)."""
        return cls(tuple(StackLayer(L.material, float(L.h), L.interface) for L in layers), substrate)

    @property
    def depth(self) -> float:
        """Total thickness of the layers [m]."""
        return float(sum(L.h for L in self.layers))

    @property
    def tops(self) -> np.ndarray:
        """Depth of each layer's top face [m] (and, last, of the substrate's)."""
        return np.concatenate([[0.0], np.cumsum([L.h for L in self.layers])])

    @property
    def w_floor(self) -> float:
        """Smallest wavenumber [1/m] the responses resolve (clamped below it)."""
        return T_MIN / self.depth

    def _w(self, w) -> np.ndarray:
        return np.maximum(np.asarray(w, dtype=float), T_MIN / self.depth)

    def coefficients(self, w) -> StackCoefficients:
        """:class:`StackCoefficients` of each layer and the substrate per wavenumber ``w`` [1/m]
        (1-D)."""
        w = self._w(w).ravel()
        n = w.size
        top = self.layers[0].material
        G_ref = top.G
        # --- in-plane: up ---
        if self.substrate.is_rigid:
            B = np.zeros((n, 4, 2))
            B[:, 2, 0] = B[:, 3, 1] = 1.0
        else:
            B = half_space_states(w, self.substrate, G_ref)
        below = B  # the lower region's own basis (its states are B c)
        ups = []
        for j in range(len(self.layers) - 1, -1, -1):
            L = self.layers[j]
            fric = None
            if L.interface == "frictionless":
                c0 = np.stack([below[..., 3, 1], -below[..., 3, 0]], axis=-1)
                nv = np.linalg.norm(np.einsum("nij,nj->ni", below, c0), axis=-1)
                fric = (c0, nv)
                B_used = frictionless_span(below)
            else:
                B_used = below
            t = w * L.h
            Mt = state_matrix(t, t, L.material, G_ref)
            M0 = state_matrix(np.zeros_like(t), t, L.material, G_ref)
            A = np.concatenate([Mt, -B_used], axis=-1)
            Q, _ = np.linalg.qr(np.swapaxes(A, -1, -2), mode="complete")
            Nj = Q[:, :, 4:]
            Bt = M0 @ Nj[:, :4, :]
            nrm = np.linalg.norm(Bt, axis=-2)  # (n, 2)
            ups.append((Nj, nrm, fric))
            below = Bt / nrm[:, None, :]
        ups.reverse()
        rhs = np.broadcast_to(np.array([[-1.0, 0.0], [0.0, 1.0]]), (n, 2, 2))
        c = np.linalg.solve(below[:, 2:, :], rhs)  # (n, 2 combos, 2 loads)
        # --- in-plane: down ---
        layer_coef = []
        for Nj, nrm, fric in ups:
            cs = c / nrm[:, :, None]
            layer_coef.append(Nj[:, :4, :] @ cs)
            d = Nj[:, 4:, :] @ cs
            if fric is not None:
                c0, nv = fric
                d = c0[:, :, None] * (d[:, 0:1, :] / nv[:, None, None])
            c = d
        sub_coef = None if self.substrate.is_rigid else c
        # --- antiplane ---
        K = np.full(n, np.inf if self.substrate.is_rigid else self.substrate.G)
        rhos = []
        for j in range(len(self.layers) - 1, -1, -1):
            L = self.layers[j]
            G = L.material.G
            if L.interface == "frictionless":
                rho = np.ones(n)  # no shear on the lower face
            elif np.isinf(K).all():
                rho = -np.ones(n)  # bonded to a rigid base: U = 0
            else:
                r = K / G
                rho = (1.0 - r) / (1.0 + r)
            e2 = np.exp(-2.0 * w * L.h)
            rhos.append(rho)
            K = G * (1.0 - rho * e2) / (1.0 + rho * e2)
        rhos.reverse()
        anti = []
        alpha = None
        for j, L in enumerate(self.layers):
            e = np.exp(-w * L.h)
            rho = rhos[j]
            if j == 0:
                alpha = 1.0 / (1.0 - rho * e * e)
            else:
                prev = self.layers[j - 1]
                if prev.interface == "frictionless":
                    alpha = np.zeros(n)
                else:
                    V_bot, S_bot = _passed_down(anti[-1], prev, L.material.G, w)
                    alpha = np.where(rho >= 0, V_bot / (1.0 + rho * e * e),
                                     -S_bot / (1.0 - rho * e * e))
            anti.append(np.stack([alpha, rho * alpha * e], axis=-1))
        anti_sub = None
        if not self.substrate.is_rigid:
            last = self.layers[-1]
            if last.interface == "frictionless":
                anti_sub = np.zeros(n)
            else:
                anti_sub = _passed_down(anti[-1], last, self.substrate.G, w)[0]
        def cont(a):  # (n, ...) -> (..., n), contiguous along w
            return None if a is None else np.ascontiguousarray(np.moveaxis(a, 0, -1))

        return StackCoefficients([cont(c) for c in layer_coef], cont(sub_coef),
                                 [cont(a) for a in anti], anti_sub)

    def layer_index(self, z: float) -> int:
        """Index of the layer holding depth ``z`` [m] (an interface depth: the layer above;
        ``len(layers)``: the substrate)."""
        return int(np.sum(self.tops[1:] * (1.0 + 1e-12) < z))

    def at(self, w, z: float, coef=None):
        """Response rows (:class:`~coathertz.fft.stress_rows.StressRows`) at depth ``z`` [m] per
        ``w`` (1-D); a depth in a rigid substrate raises."""

        w = self._w(w)
        if coef is None:
            coef = self.coefficients(w)
        j = self.layer_index(z)
        if j < len(self.layers):
            L = self.layers[j]
            s = w * (z - self.tops[j])
            u = w * L.h - s
            e1, e2 = np.exp(-s), np.exp(-u)
            nu = L.material.nu
            cf = coef.layers[j]  # (4, 2, n)
            out = []
            for m in range(2):
                c1, c2, c3, c4 = cf[:, m]
                # f = (c1 + c2 s) e1 + (c3 + c4 u) e2; f' = c2 e1 - g + h - c4 e2;
                # f'' = f - 2 (c2 e1 + c4 e2)
                g, h = (c1 + c2 * s) * e1, (c3 + c4 * u) * e2
                m1, m2 = c2 * e1, c4 * e2
                f0 = g + h
                f1 = (m1 - m2) + (h - g)
                msum = m1 + m2
                out.append((f0 - 2.0 * msum, (-2.0 * nu) * msum, -f0, f1))
            al, be = coef.anti[j]
            a1, b2 = al * e1, be * e2
            return StressRows(out[0], out[1], (a1 + b2, b2 - a1))
        if self.substrate.is_rigid:
            raise CoatHertzError(
                f"fft stresses: depth z = {z:g} m lies in the rigid substrate "
                f"(valid: 0 to {self.depth:g} m)")
        s = w * (z - self.depth)
        e1 = np.exp(-s)
        nu = self.substrate.nu
        out = []
        for m in range(2):
            c1, c2 = coef.sub[:, m]
            f0 = (c1 + c2 * s) * e1
            m1 = c2 * e1
            out.append((f0 - 2.0 * m1, (-2.0 * nu) * m1, -f0, m1 - f0))
        V = coef.anti_sub * e1
        return StressRows(out[0], out[1], (V, -V))


def _passed_down(anti_above: np.ndarray, above, G_below: float,
                 w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Antiplane state handed across the bonded lower face of the layer ``above`` (coefficients
    ``anti_above[:, 0]``, ``anti_above[:, 1]`` of its decaying and growing parts): the displacement
    scaled to the next medium's shear modulus ``G_below`` (continuity of displacement in the
    ``G``-normalised amplitudes) and the shear it carries."""
    a0, b0 = anti_above[:, 0], anti_above[:, 1]
    e0 = np.exp(-w * above.h)
    return (a0 * e0 + b0) * (G_below / above.material.G), -a0 * e0 + b0
