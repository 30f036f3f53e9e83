"""Frequency response functions (FRF) of the surface normal displacement of a coated body.

The FRF ``u~(w)`` maps the 2-D Fourier transform of a normal surface pressure to that of the
surface normal displacement (positive into the body). ``w = |k|`` is the angular wavenumber,
so that the homogeneous half-space has ``u~ = 2 / (E* w)`` (eq 14), the transform of
``1 / (pi E* r)``. For a layer of thickness ``h`` we write

.. math::  \\tilde u(w) = \\frac{2}{E_c^* w} F(w h),

with the dimensionless *layer factor* ``F(t)``, ``F(0) = Ec*/Es*`` (eq 14) and ``F(inf) = 1``
(eq 15). Two ways of computing ``F`` are provided:

* :func:`layer_factor_eq13` -- eq (13) of the paper (Nogi & Kato 1997), perfectly bonded layer,
  elastic or rigid substrate (``mu = 0``, ``lam = 4 nu_c - 3``, ``kappa = 1/lam``);
* :func:`layer_factor_tm` -- an independent transfer-matrix solution of the layered problem
  (Papkovich--Neuber potentials, plane strain along ``k``) for a **bonded** or a
  **frictionless** (layer resting on its substrate without friction) interface and an elastic
  or rigid substrate. In the bonded case it reproduces eq (13) to rounding (tested).

Transfer-matrix derivation
--------------------------
A normal load ``P cos(k x)`` on a layered half-space gives a plane-strain field in ``(x, z)``,
``z`` the depth. With the Papkovich--Neuber representation
``2 G u = grad(phi + z psi) - 4 (1 - nu) psi e_z`` and harmonic ``phi = f(z) cos kx``,
``psi = g(z) cos kx``::

    2G u_x   = -k (f + z g)                       sin kx
    2G u_z   = (f' + z g' - (3 - 4 nu) g)          cos kx
    sigma_zz = (k^2 f + k^2 z g - 2 (1 - nu) g')   cos kx
    sigma_xz = -k (f' + z g' - (1 - 2 nu) g)       sin kx

In the layer ``f = A e^{-kz} + C e^{-k(h-z)}``, ``g = B e^{-kz} + D e^{-k(h-z)}`` (bounded
exponentials), in the substrate ``f = A2 e^{-k(z-h)}``, ``g = B2 e^{-k(z-h)}`` (decaying).
Conditions: ``sigma_zz = -P``, ``sigma_xz = 0`` at ``z = 0``; at ``z = h`` either continuity of
``u_x, u_z, sigma_zz, sigma_xz`` (bonded) or continuity of ``u_z, sigma_zz`` with
``sigma_xz = 0`` on both sides (frictionless); a rigid substrate gives ``u_x = u_z = 0``
(bonded) or ``u_z = sigma_xz = 0`` (frictionless). With ``k = 1`` and ``h = t`` the 6 x 6 (or
4 x 4) system is solved per ``t`` and ``F(t) = 2 G_c u_z(0) / (2 (1 - nu_c))``. Nothing
divides by ``1 - 2 nu``: ``nu_c = 0.5`` is fine.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coathertz.errors import CoatHertzError
from coathertz.materials import Material, coating_constants

INTERFACES = ("bonded", "frictionless")


@dataclass(frozen=True)
class Layer:
    """A coating of ``coating`` material on ``substrate`` (``RIGID`` allowed) with an interface.

    The thickness is not part of the layer: the layer factor is a function of ``t = w h``.
    """

    coating: Material
    substrate: Material
    interface: str = "bonded"

    def __post_init__(self) -> None:
        if self.interface not in INTERFACES:
            raise CoatHertzError(
                f"interface must be one of {INTERFACES}, got {self.interface!r}"
            )
        if self.coating.is_rigid:
            raise CoatHertzError("coating material must be elastic (0 < E < inf)")

    @property
    def F0(self) -> float:
        """``F(0) = Ec*/Es*`` (eq 14 with the identity below it); 0 on a rigid substrate."""
        if self.substrate.is_rigid:
            return 0.0
        return self.coating.E_star / self.substrate.E_star

    def factor(self, t: np.ndarray) -> np.ndarray:
        """``F(t)``: eq (13) when bonded, the transfer matrix when frictionless."""
        if self.interface == "bonded":
            return layer_factor_eq13(t, self.coating, self.substrate)
        return layer_factor_tm(t, self.coating, self.substrate, "frictionless")


@dataclass(frozen=True)
class StackFRF:
    """A layer stack in the form :class:`Layer` has for the cell coefficients: ``F(t)``
    with ``t = w h_ref`` (``h_ref``: the stack's total thickness) from the shared N-layer kernel
    definition :func:`coathertz.stack.stack_layer_factor` (complex ``t`` allowed), ``F0``, and
    the top material ``coating`` (its ``E*`` normalises ``F``)."""

    layers: tuple
    substrate: Material
    h_ref: float

    @property
    def coating(self) -> Material:
        return self.layers[0].material

    @property
    def top_fraction(self) -> float:
        """The top layer's share of ``h_ref``: ``F(t)`` reaches its large-``t`` limit (the top
        material's half-space) only as ``exp(-2 t top_fraction)``."""
        return self.layers[0].h / self.h_ref

    @property
    def F0(self) -> float:
        """``F(0) = E_top*/Es*``; 0 on a rigid substrate."""
        return 0.0 if self.substrate.is_rigid else self.coating.E_star / self.substrate.E_star

    def factor(self, t: np.ndarray) -> np.ndarray:
        from coathertz.stack import StackLayer, stack_layer_factor

        t = np.asarray(t)
        layers = [StackLayer(L.material, L.h, L.interface) for L in self.layers]
        out = stack_layer_factor(layers, self.substrate, t.ravel() / self.h_ref)
        return out.reshape(t.shape)


def layer_factor_eq13(t, coating: Material, substrate: Material) -> np.ndarray:
    """Layer factor of eq (13): ``u~ = 2/(Ec* w) F(w h)``, bonded interface.

    ``F(t) = (1 + 4 t kappa theta - lam kappa theta^2) /
    (1 - (lam + kappa + 4 kappa t^2) theta + lam kappa theta^2)``, ``theta = exp(-2 t)``.
    Accepts real or complex ``t`` (complex values are used for Taylor coefficients).
    """
    c = coating_constants(coating, substrate)
    t = np.asarray(t)
    th = np.exp(-2.0 * t)
    lk = c.lam * c.kappa
    num = 1.0 + 4.0 * t * c.kappa * th - lk * th**2  # eq (13), numerator
    den = 1.0 - (c.lam + c.kappa + 4.0 * c.kappa * t**2) * th + lk * th**2  # eq (13)
    return num / den


def _columns(t, nu, zrel, kind):
    """Rows (2G u_x, 2G u_z, sigma_zz, sigma_xz) of one basis function at depth z (k = 1).

    ``kind`` 'A'/'B' decay with depth (amplitude ``E = e^{-z}``, or e^{-(z-h)} in the
    substrate), 'C'/'D' grow towards the interface (``E = e^{-(h - z)}``). ``zrel`` is the
    value of that exponential at the evaluation point and ``t`` the absolute depth z.
    """
    z = t
    E = zrel
    if kind == "A":
        return (-E, -E, E, E)
    if kind == "B":
        return (-z * E, (-z - (3 - 4 * nu)) * E, (z + 2 * (1 - nu)) * E, (z + (1 - 2 * nu)) * E)
    if kind == "C":
        return (-E, E, E, -E)
    if kind == "D":
        return (-z * E, (z - (3 - 4 * nu)) * E, (z - 2 * (1 - nu)) * E, (-z + (1 - 2 * nu)) * E)
    raise AssertionError(kind)


def layer_factor_tm(t, coating: Material, substrate: Material, interface: str = "bonded"):
    """Layer factor ``F(t)`` from the transfer-matrix solution (see module docstring).

    Parameters
    ----------
    t
        ``w h`` (real >= 0 or complex), any shape.
    coating, substrate
        Materials; ``substrate`` may be rigid.
    interface
        ``"bonded"`` (perfect bonding, the paper's model) or ``"frictionless"``.
    """
    if interface not in INTERFACES:
        raise CoatHertzError(f"interface must be one of {INTERFACES}, got {interface!r}")
    t = np.asarray(t)
    shape = t.shape
    M, L0, _ = layer_system(t.ravel(), coating, substrate, interface)
    rhs = np.zeros(M.shape[:2], dtype=M.dtype)
    rhs[:, 0] = -1.0  # sigma_zz(0) = -1, sigma_xz(0) = 0
    x = np.linalg.solve(M, rhs[..., None])[..., 0]
    Uz0 = sum(L0[j][1] * x[:, j] for j in range(4))
    return (Uz0 / (2.0 * (1.0 - coating.nu))).reshape(shape)


def layer_system(tt: np.ndarray, coating: Material, substrate: Material, interface: str):
    """The 6 x 6 system of the layer on its substrate at ``tt = w h`` (1-D, real or complex):
    rows 0, 1 the surface tractions ``sigma_zz(0)``, ``sigma_xz(0)`` (the caller's right-hand
    side), rows 2-5 the interface conditions (bonded: ``u_x, u_z, sigma_zz, sigma_xz``
    continuous; frictionless: ``u_z, sigma_zz`` continuous and ``sigma_xz = 0`` on both sides;
    rigid substrate: ``u_x = u_z = 0`` or ``u_z = sigma_xz = 0``). Unknowns: the layer's
    ``A, B, C, D`` and the substrate's decaying ``A, B`` (zero on a rigid one). Returns
    ``(M, L0, Lh)``, the layer basis at ``z = 0`` and ``z = h`` included (the stress responses
    of :mod:`coathertz.fft.stresses` solve the same system)."""
    n = tt.size
    dtype = np.result_type(tt.dtype, np.float64)
    nu_c = coating.nu
    one = np.ones_like(tt, dtype=dtype)
    zero = np.zeros_like(tt, dtype=dtype)
    eh = np.exp(-tt)  # e^{-h} (k = 1)
    # layer basis at z = 0 and z = h
    L0 = [_columns(zero, nu_c, one if k in "AB" else eh, k) for k in "ABCD"]
    Lh = [_columns(tt, nu_c, eh if k in "AB" else one, k) for k in "ABCD"]
    M = np.zeros((n, 6, 6), dtype=dtype)
    for j in range(4):
        M[:, 0, j] = L0[j][2]  # sigma_zz(0)
        M[:, 1, j] = L0[j][3]  # sigma_xz(0)
    if substrate.is_rigid:
        M[:, 4, 4] = 1.0
        M[:, 5, 5] = 1.0
        rows = (0, 1) if interface == "bonded" else (1, 3)  # (u_x, u_z) or (u_z, sigma_xz)
        for r, q in zip((2, 3), rows, strict=True):
            for j in range(4):
                M[:, r, j] = Lh[j][q]
        return M, L0, Lh
    # 2 G_c = 1, 2 G_s = 1/mu: u = U in the layer, u = mu U in the substrate
    mu = coating.G / substrate.G
    S = [_columns(tt, substrate.nu, one, k) for k in "AB"]
    scale = (mu, mu, 1.0, 1.0)
    quantities = (0, 1, 2, 3) if interface == "bonded" else (1, 2)
    r = 2
    for q in quantities:
        for j in range(4):
            M[:, r, j] = Lh[j][q]
        for j in range(2):
            M[:, r, 4 + j] = -scale[q] * S[j][q]
        r += 1
    if interface == "frictionless":
        for j in range(4):
            M[:, 4, j] = Lh[j][3]  # sigma_xz = 0, layer side
        for j in range(2):
            M[:, 5, 4 + j] = S[j][3]  # sigma_xz = 0, substrate side
    return M, L0, Lh


def taylor_coefficients(fun, n: int = 3, radius: float = 0.2, m: int = 64,
                        rtol: float = 1e-8, min_radius: float = 1e-4) -> np.ndarray:
    """First ``n`` Taylor coefficients of an analytic ``fun`` at 0 (trapezoidal Cauchy integral).

    On a circle of radius ``r`` inside the disc of convergence the error decays like
    ``(r / R_conv)^m``. With a pole inside the circle the integral returns the coefficients of
    ``fun`` without the pole's part, and a fixed radius can be silently wrong: the layer factor
    of a stiff coating has a pole on the negative axis near 0 (``t = -0.13`` for
    Ec*/Es* = 4, ``-0.05`` for 10, nu = 0.3), and a radius of 0.1 gave ``F(0) = 9.18``
    instead of 10 (and a remainder of the split in :mod:`coathertz.fft.influence` that did not
    vanish at 0: delta off by 0.15 %). So ``m/2`` coefficients are computed and their series
    is checked against ``fun`` on the circle of radius ``r/4`` (truncation ``4^(-m/2)``; a
    pole inside misses there by its own part); the radius is halved from ``radius`` until it
    matches to ``rtol`` of ``max |fun|`` on the circle. Raises :class:`~coathertz.errors.CoatHertzError` if no
    radius down to ``min_radius`` passes.
    """
    th = 2.0 * np.pi * np.arange(m) / m
    k = np.arange(max(n, m // 2))
    phi = 2.0 * np.pi * (np.arange(16) + 0.5) / 16
    r = float(radius)
    while r >= min_radius:
        vals = np.asarray(fun(r * np.exp(1j * th)), dtype=complex)
        c = (np.exp(-1j * np.outer(k, th)) @ vals) / m / r**k
        zc = 0.25 * r * np.exp(1j * phi)
        series = (zc[:, None] ** k) @ c
        miss = np.max(np.abs(np.asarray(fun(zc)) - series))
        if miss <= rtol * np.max(np.abs(vals)):
            return c[:n].real
        r /= 2
    raise CoatHertzError(
        f"Taylor coefficients of the layer factor did not converge down to a radius of "
        f"{min_radius:g} (a singularity at the origin?)"
    )
