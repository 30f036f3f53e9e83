"""Stresses inside a (coated) half-space under a normal surface pressure, by FFT per depth plane.

Transfer solution per wavenumber
--------------------------------
A pressure ``P cos(k x)`` (``sigma_zz(0) = -P``, ``sigma_xz(0) = 0``) gives a plane-strain
field in ``(x, z)``. With the Papkovich--Neuber potentials of :mod:`coathertz.fft.frf`,
``2 G u = grad(phi + z psi) - 4 (1 - nu) psi e_z``, ``phi = f(z) cos kx``,
``psi = g(z) cos kx``, the divergence is ``2 G div u = -2 (1 - 2 nu) g'`` so that
``lambda div u = -2 nu g'`` and (k = 1)::

    sigma_xx = (-(f + z g) - 2 nu g')            cos kx
    sigma_yy = -2 nu g'                          cos kx     (plane strain, y normal to k)
    sigma_zz = (f + z g - 2 (1 - nu) g')         cos kx
    sigma_xz = -(f' + z g' - (1 - 2 nu) g)       sin kx

With the bounded exponentials of :func:`coathertz.fft.frf.layer_factor_tm`
(``f = A e^{-z} + C e^{-(h-z)}``, ``g = B e^{-z} + D e^{-(h-z)}`` in the coating,
``A2 e^{-(z-h)}``, ``B2 e^{-(z-h)}`` in the substrate) every basis value is a product of a
polynomial in ``z`` and an exponential ``<= 1``: no growing exponential appears. The six (or
four, rigid substrate) coefficients depend on ``t = w h`` only and are solved once per
wavenumber ``w = |k|``; the stresses at depth ``z`` are the basis rows at ``w z`` times them.
Homogeneous half-space (no coating): ``A = 1 - 2 nu``, ``B = -1``, i.e. with ``s = w z``::

    S_kk = (s - 1) e^{-s},  S_pp = -2 nu e^{-s},  S_zz = -(1 + s) e^{-s},  S_kz = -s e^{-s}

(the transform of Boussinesq's field, Johnson 1985 sec. 3.2).

3-D field and FFT
-----------------
For a wave vector ``k = w (cos th, sin th)`` the field is the plane-strain one along
``k``, rotated: ``sigma_xx = c^2 S_kk + s^2 S_pp``, ``sigma_yy = s^2 S_kk + c^2 S_pp``,
``sigma_xy = c s (S_kk - S_pp)``, ``sigma_xz = -i c S_kz``, ``sigma_yz = -i s S_kz``,
``sigma_zz = S_zz`` (``sin kx = Re(-i e^{ikx})``). The cell pressures (piecewise constant,
transform ``sinc(kx dx/2) sinc(ky dy/2)``) are zero padded to ``pad`` times the domain in each
direction and multiplied by these responses per depth plane. The responses are bounded at
``w = 0``; their direction-dependent limit there (``S_kk -> -1``, ``S_pp -> -2 nu`` on the
homogeneous body) is replaced by its angular mean, which is what a circular truncation of the
spectrum sees. Periodic images of the kernel lie ``pad - 1`` domain widths away; the
``1/r^2`` part of the lateral stresses has a ``cos 2 th`` angular dependence whose images
cancel at the centre on a square period, but the trace ``sigma_xx + sigma_yy`` decays like
``z / r^3`` and its images shift the lateral stresses uniformly by about
``-(1 + nu) W z 9.03 / (2 pi P^3)`` (``P`` the period, 9.03 the lattice sum of ``|n|^-3``):
0.75 % of p0 at z = a with ``pad = 2`` on a 4a domain, 0.1 % with the default ``pad = 4``
(measured in the tests against Huber's closed form). This shift is removed: the
trace response ``S_kk + S_pp = T0 + T1(z) w + O(w^2)`` has a term linear in ``|k|`` whose
plane transform is the far field ``-W T1 / (2 pi r^3)`` (Boussinesq: ``T1 = 2 (1 + nu) z``),
so the images add ``-W T1 L3 / (4 pi)`` to each of ``sigma_xx, sigma_yy`` with
``L3 = sum' |(i Px, j Py)|^-3`` the lattice sum; :func:`stresses_surface` subtracts it
(``T1`` by a second-order difference of the responses at ``w = eps, 2 eps, 3 eps``, ``eps`` above
the layered responses' floor ``10 T_MIN / h``). Measured on the FFT
solution of a rigid sphere on steel (n = 128, domain 2.5a, pad 4) against Huber's field: the
error at z = 2a falls from 0.75 % to 0.04 % of p0 (with pad 2 it is still 1.4 %: the
expansion needs ``z << P``). The ``cos 2 th / r^2`` part cancels exactly only on a square period.
The ``w = 0`` term and
``T1`` are the ``w -> 0`` limits, i.e. the field at scales far beyond the coating: right
while ``h`` is small against the period ``P``; for a coating thicker than ``P`` they carry
the substrate's (or rigid base's) far field into a field that has not felt it yet (measured:
0.3 to 0.5 % of p0 for h = 100a on a rigid base, P = 16a).

Layer stacks
------------
A body with ``layers`` (any number, bonded or frictionless interfaces, elastic or rigid
substrate) takes its responses from :class:`coathertz.fft.stack_stresses.StackStressFRF` (Airy
functions in the stack kernel's bounded basis, every layer's coefficients from the kernel's own
sweep run back down; derivation there); one coating keeps :class:`CoatedStressFRF`. Both have the
same rows, so everything above applies; a stack counts with its total thickness in
:func:`image_pad`. Against the exact method (``tests/stresses/test_fft_stack_stresses.py``,
128^2): 2.7e-3 p0 at 2.4 cells below the surface of a TiN/Ti bilayer, <= 5e-4 p0 elsewhere,
second order in the cell size near the surface. A stack on a *frictionless* rigid base is not
quite the exponentially decaying case :func:`image_pad` assumes: its layers carry the Poisson
expansion as a membrane whose field decays like ``1/r^2``; its images leave 3e-4 p0 with the
default period 4 (9e-5 with 8).

Cost
----
The responses depend on ``|k|`` only and are evaluated once per distinct ``|k|`` (22 090 of
131 584 half-spectrum points at 128^2, pad 4) and gathered; the angle factors are folded into
the load spectra once (:func:`stresses_surface`, Notes), so a depth costs a few products per
component and its two transforms. A depth's spectrum is cut where every response is below
:data:`BAND_TOL` of the unit load (``e^{-w z}``: deep planes keep a small block of wavenumbers).
``precision="single"`` runs the per-depth products and transforms in complex64 (round-off
about 2e-7 of p0, measured against double). Depths are computed one at a time into the
result array: the working memory beyond it is one depth's spectra plus the load spectra.
``tests/benchmarks/bench_fft_stresses.py`` times it.

Accuracy near the surface
-------------------------
The responses times ``sinc sinc`` are the exact field of a pressure uniform over each cell
(piecewise-constant patches), so the consistent cell value is the cell mean of a continuous
pressure (what the DC-FFT contact solver delivers), not its sample at the cell centre. With
centre samples of Hertz's pressure the staircase at the contact edge is misplaced by up to
half a cell: max error against Huber's field 2.5 % / 1.6 % / 0.75 % / 0.26 % of p0 at
z = 0.025 / 0.05 / 0.1 / 0.2 a on 128^2 (domain 4a), about first order. With cell means:
1.2 % / 0.52 % / 0.19 % / 0.06 % on 128^2 and 0.39 % / 0.14 % / 0.05 % / 0.01 % on 256^2;
at z = 0.1 a 0.67 % / 0.19 % / 0.05 % on 64^2 / 128^2 / 256^2, observed order about 1.9
(tests/stresses/test_fft_stresses.py). Within about 1.5 cells of the surface the error is
the cell size itself (the field varies on the scale z). On the surface (Johnson eq. 3.41)
the error is 0.29 % / 0.17 % / 0.11 % of p0 beyond 1.5 cells from the contact edge on
64^2 / 128^2 / 256^2; in the edge cells a cell mean cannot equal the value at the centre
of a square-root edge: 9.3 % / 6.6 % / 4.7 % (order 1/2), and the peak radial tension
(1 - 2 nu)/3 p0 at r = a is reached only as dx -> 0 (0.124 p0 at 128^2 instead of 0.133).

"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy import fft as sfft

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError, ModelValidityWarning
from coathertz.fft.frf import Layer, layer_system
from coathertz.fft.grid import Grid
from coathertz.fft.stack_stresses import StackStressFRF
from coathertz.fft.stress_rows import StressRows
from coathertz.materials import Body
from coathertz.results import ContactResult
from coathertz.stress_depths import default_depths

#: The stress components in the order of a field's component axis (Voigt order).
COMPONENTS = ("xx", "yy", "zz", "yz", "xz", "xy")
T_MIN = 1e-6  # smallest w h solved (the 6 x 6 system degenerates at t = 0; w = 0 only)


@dataclass(frozen=True)
class CoatedStressFRF:
    """Stress responses of a coating of thickness ``h`` [m] on its substrate (``layer``)."""

    layer: Layer
    h: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.h) and self.h > 0):
            raise CoatHertzError(f"coating thickness h must be finite and > 0 [m], got {self.h!r}")

    @property
    def w_floor(self) -> float:
        """Smallest wavenumber [1/m] the responses resolve (:meth:`at` clamps below it)."""
        return T_MIN / self.h

    def coefficients(self, w: np.ndarray) -> CoatedCoefficients:
        """In-plane coefficients ``(A, B, C, D, A2, B2)`` for the normal and the tangential load
        (``x``, shape ``w.shape + (6, 2)``), antiplane ``(alpha, beta, gamma)`` (``xa``,
        ``w.shape + (3,)``) and the rows' polynomial coefficients derived from them."""
        coating, substrate = self.layer.coating, self.layer.substrate
        interface = self.layer.interface
        t = np.maximum(np.asarray(w, dtype=float).ravel() * self.h, T_MIN)
        n = t.size
        M, _, _ = layer_system(t, coating, substrate, interface)
        eh = np.exp(-t)
        rhs = np.zeros((n, 6, 2))
        rhs[:, 0, 0] = -1.0  # normal: sigma_zz(0) = -P
        rhs[:, 1, 1] = 1.0  # tangential: row kz(0) = Q, i.e. sigma_xz(0) = -Q cos kx
        x = np.linalg.solve(M, rhs)
        # antiplane: U = a e^{-kz} + b e^{-k(h-z)} (coating), c e^{-k(z-h)} (substrate);
        # alpha = G_c k a / Q etc.: -alpha + beta e^{-t} = -1 (sigma_pz(0) = -Q), and
        # beta = rho alpha e^{-t}, rho = (1 - r)/(1 + r), r = G_s/G_c (bonded; -1 on a rigid
        # substrate) or rho = 1 (frictionless: sigma_pz(h) = 0); gamma = alpha e^{-t} + beta.
        if interface == "frictionless":
            rho = 1.0
        elif substrate.is_rigid:
            rho = -1.0
        else:
            r_g = substrate.G / coating.G
            rho = (1 - r_g) / (1 + r_g)
        alpha = 1.0 / (1.0 - rho * eh * eh)
        beta = rho * alpha * eh
        gamma = np.zeros_like(t) if interface == "frictionless" else alpha * eh + beta
        xa = np.stack([alpha, beta, gamma], axis=-1)
        shape = np.shape(w)
        # rows (kk, pp, zz, kz) = e_a (a_q + s b_q) + e_c (c_q + s d_q) (the basis rows of the
        # module docstring collected: b = (-B, 0, B, B), d = (-D, 0, D, -D)); in the substrate
        # e (a_q + s b_q) from A2, B2
        nu, nus = coating.nu, substrate.nu
        X = np.ascontiguousarray(np.moveaxis(x, 0, -1))  # (6, 2, n)
        A, B, C, D, A2, B2 = X
        coat = np.stack([-A + 2 * nu * B, 2 * nu * B, A + 2 * (1 - nu) * B, A + (1 - 2 * nu) * B,
                         -C - 2 * nu * D, -2 * nu * D, C - 2 * (1 - nu) * D, -C + (1 - 2 * nu) * D])
        sub = np.stack([-A2 + 2 * nus * B2, 2 * nus * B2, A2 + 2 * (1 - nus) * B2,
                        A2 + (1 - 2 * nus) * B2])
        return CoatedCoefficients(x.reshape((*shape, 6, 2)), xa.reshape((*shape, 3)), coat, B, D,
                                  sub, B2, np.ascontiguousarray(xa.T))

    def at(self, w: np.ndarray, z: float, coef=None) -> StressRows:
        """Response rows at depth ``z`` [m] (``coef``: :meth:`coefficients` of the same ``w``).

        On the interface ``z = h`` the coating's side is returned; a rigid substrate has no
        stresses below ``h`` (raises).
        """
        w = np.maximum(np.asarray(w, dtype=float), T_MIN / self.h)  # as solved
        cf = self.coefficients(w) if coef is None else coef
        if w.ndim != 1:  # the coefficients are stored flat
            r = self.at(w.ravel(), z, cf)
            return StressRows(*(tuple(v.reshape(w.shape) for v in g)
                                for g in (r.normal, r.tangential, r.antiplane)))
        s, sh = w * z, w * self.h
        if z <= self.h:
            ea, ec = np.exp(-s), np.exp(-(sh - s))
            loads = []
            for m in range(2):
                a_kk, a_pp, a_zz, a_kz, c_kk, c_pp, c_zz, c_kz = cf.coat[:, m]
                sB, sD = s * cf.B[m], s * cf.D[m]
                loads.append((ea * (a_kk - sB) + ec * (c_kk - sD), ea * a_pp + ec * c_pp,
                              ea * (a_zz + sB) + ec * (c_zz + sD),
                              ea * (a_kz + sB) + ec * (c_kz - sD)))
            a, b = cf.anti[0], cf.anti[1]
            a1, b2 = a * ea, b * ec
            return StressRows(loads[0], loads[1], (a1 + b2, b2 - a1))
        if self.layer.substrate.is_rigid:
            raise CoatHertzError(
                f"depth z = {z:g} m lies in the rigid substrate "
                f"(z must be in [0, h = {self.h:g}] m)"
            )
        e = np.exp(-(s - sh))
        loads = []
        for m in range(2):
            a_kk, a_pp, a_zz, a_kz = cf.sub[:, m]
            sB = s * cf.B2[m]
            loads.append((e * (a_kk - sB), e * a_pp, e * (a_zz + sB), e * (a_kz + sB)))
        r_g = self.layer.substrate.G / self.layer.coating.G
        g = cf.anti[2] * r_g * e
        return StressRows(loads[0], loads[1], (g, -g))


@dataclass(frozen=True)
class CoatedCoefficients:
    """:meth:`CoatedStressFRF.coefficients`: ``x`` ``(..., 6, 2)`` and ``xa`` ``(..., 3)`` as
    solved, and per load (axis 1) the rows' polynomial coefficients along ``w`` (last axis):
    ``coat`` ``(8, 2, n)``, ``B``, ``D``, ``sub`` ``(4, 2, n)``, ``B2``, ``anti`` ``(3, n)``."""

    x: np.ndarray
    xa: np.ndarray
    coat: np.ndarray
    B: np.ndarray
    D: np.ndarray
    sub: np.ndarray
    B2: np.ndarray
    anti: np.ndarray


@dataclass(frozen=True)
class HomogeneousStressFRF:
    """Stress responses of a homogeneous half-space of Poisson's ratio ``nu`` (closed form).

    Normal load: ``A = 1 - 2 nu, B = -1``; tangential load along ``k``: ``A = 2 (1 - nu),
    B = -1``, rows ``(s - 2, -2 nu, -s, 1 - s) e^{-s}``; antiplane: ``U = Q e^{-kz}/(G k)``.
    """

    nu: float

    def coefficients(self, w: np.ndarray) -> None:
        return None

    def at(self, w: np.ndarray, z: float, coef=None) -> StressRows:
        s = np.asarray(w, dtype=float) * z
        e = np.exp(-s)
        nu_e = -2 * self.nu * e
        return StressRows(((s - 1) * e, nu_e, -(1 + s) * e, -s * e),
                          ((s - 2) * e, nu_e, -s * e, (1 - s) * e),
                          (e, -e))


def stresses_surface(grid: Grid, depths, frf, p: np.ndarray | None = None,
                     qx: np.ndarray | None = None, qy: np.ndarray | None = None,
                     pad: int = 4, out: np.ndarray | None = None,
                     precision: str = "double") -> np.ndarray:
    """Six stress components [Pa] under surface tractions at each depth [m].

    Parameters
    ----------
    grid
        The FFT grid (cell ``(ny//2, nx//2)`` centred on the origin).
    depths
        Depths ``z >= 0`` [m].
    frf
        :class:`HomogeneousStressFRF`, :class:`CoatedStressFRF` or
        :class:`~coathertz.fft.stack_stresses.StackStressFRF`.
    p, qx, qy
        Cell pressure (compressive positive) and tangential tractions applied to the body in
        ``+x``, ``+y`` [Pa] (shape ``grid.shape``; ``None`` for none): ``sigma_zz(0) = -p``,
        ``sigma_xz(0) = -qx``, ``sigma_yz(0) = -qy``.
    pad
        Period of the FFT in domain widths (>= 2: zero padding, non-periodic).
    out
        Optional array of shape ``(len(depths), 6, ny, nx)`` (float64) to write into.
    precision
        ``"double"`` (complex128 spectra and transforms) or ``"single"`` (complex64 spectra and
        transforms, about twice as fast; the responses, the load spectra and the image
        correction are still formed in double: round-off about 1e-7 of the largest stress).

    Returns
    -------
    ndarray
        Shape ``(len(depths), 6, ny, nx)``, components in :data:`COMPONENTS` order, at the
        cell centres.

    Notes
    -----
    The responses depend on ``|k|`` only: they are evaluated once per distinct ``|k|`` of the
    padded half-spectrum (22 090 of 131 584 at 128^2, pad 4) and gathered. With
    ``Sigma = (T_kk + T_pp)/2``, ``Delta = (T_kk - T_pp)/2`` and ``c2 = cos 2 th``,
    ``s2 = sin 2 th`` the in-plane rotation of the module docstring reads
    ``sigma_xx, sigma_yy = Sigma +- (c2 Delta - s2 T_kp)``, ``sigma_xy = s2 Delta + c2 T_kp``; the
    angle factors are folded into the load spectra once, so each depth costs a few real-times-
    complex products per component. The spectra are laid out ``(k_x, k_y)`` so that the complex
    transform along ``y`` runs over contiguous memory, keeps the ``ny`` rows of the body, and the
    complex-to-real transform along ``x`` follows (the same as ``irfft2`` cropped).
    """
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    if np.any(~np.isfinite(depths)) or np.any(depths < 0):
        raise CoatHertzError(f"depths must be finite and >= 0 [m], got {depths!r}")
    if not isinstance(pad, int | np.integer) or pad < 2:
        raise CoatHertzError(f"pad must be an integer >= 2, got {pad!r}")
    ny, nx = grid.shape
    for name, v in (("p", p), ("qx", qx), ("qy", qy)):
        if v is not None and np.shape(v) != (ny, nx):
            raise CoatHertzError(f"{name} shape {np.shape(v)} does not match the grid {(ny, nx)}")
    Ny, Nx = pad * ny, pad * nx
    Nk = Nx // 2 + 1
    if out is None:
        out = np.empty((depths.size, 6, ny, nx))
    elif out.shape != (depths.size, 6, ny, nx):
        raise CoatHertzError(f"out has shape {out.shape}, expected {(depths.size, 6, ny, nx)}")
    if precision not in ("double", "single"):
        raise CoatHertzError(f"precision must be 'double' or 'single', got {precision!r}")
    cdt = np.complex128 if precision == "double" else np.complex64
    # layout (k_x, k_y): rfft along x (k_x >= 0 ascending), full along y in ascending k_y
    # (fftshift order, so that a band |k| <= w_cut is one block; undone by (-1)^j after the
    # transform along y, Ny being even)
    kx_v = 2 * np.pi * sfft.rfftfreq(Nx, grid.dx)
    ky_v = 2 * np.pi * sfft.fftshift(sfft.fftfreq(Ny, grid.dy))
    kx, ky = kx_v[:, None], ky_v[None, :]
    w = np.hypot(kx, ky)
    w_u, inv = np.unique(w, return_inverse=True)
    inv = inv.reshape(w.shape)
    pos = w > 0
    safe = np.where(pos, w, 1.0)
    c = np.where(pos, kx / safe, np.sqrt(0.5))
    s = np.where(pos, ky / safe, np.sqrt(0.5))
    c2 = np.where(pos, c * c - s * s, 0.0)  # angular mean (0) at w = 0
    s2 = np.where(pos, 2 * c * s, 0.0)
    cell = np.sinc(kx * grid.dx / (2 * np.pi)) * np.sinc(ky * grid.dy / (2 * np.pi))
    # Nyquist lines carry odd responses that a real field cannot hold: dropped for all
    if Nx % 2 == 0:
        cell[-1, :] = 0.0
    cell[:, 0] = 0.0  # k_y = -Ny/2 (Ny = pad ny is even)
    sign = np.where(np.arange(ny) % 2 == 0, 1.0, -1.0).astype(cdt)

    def spectrum(v):
        if v is None:
            return None
        return sfft.fftshift(sfft.rfft2(v, s=(Ny, Nx), workers=1).T, axes=1) * cell

    P, Qx, Qy = spectrum(p), spectrum(qx), spectrum(qy)
    tangential = Qx is not None or Qy is not None
    # load-angle spectra, one per term (radial row name, spectrum) of each group
    terms: dict[str, list] = {"S": [], "X": [], "xy": [], "zz": [], "yz": [], "xz": []}
    if P is not None:
        terms["S"].append(("a_n", P))
        terms["X"].append(("d_n", c2 * P))
        terms["xy"].append(("d_n", s2 * P))
        terms["zz"].append(("zz_n", P))
        terms["yz"].append(("kz_n", -1j * s * P))
        terms["xz"].append(("kz_n", -1j * c * P))
    if tangential:
        zero = np.zeros(w.shape)
        Qx_, Qy_ = (zero if Qx is None else Qx), (zero if Qy is None else Qy)
        Qk, Qp = c * Qx_ + s * Qy_, -s * Qx_ + c * Qy_
        oQk = -1j * np.where(pos, 1.0, 0.0) * Qk  # odd responses vanish at w = 0
        iQp = 1j * np.where(pos, 1.0, 0.0) * Qp
        terms["S"].append(("a_t", oQk))
        terms["X"] += [("d_t", c2 * oQk), ("kp", -s2 * iQp)]
        terms["xy"] += [("d_t", s2 * oQk), ("kp", c2 * iQp)]
        terms["zz"].append(("zz_t", oQk))
        terms["yz"] += [("kz_t", -s * Qk), ("pz", c * Qp)]
        terms["xz"] += [("kz_t", -c * Qk), ("pz", -s * Qp)]
    needed = sorted({name for group in terms.values() for name, _ in group})
    terms = {k: [(name, spec.astype(cdt)) for name, spec in group] for k, group in terms.items()}
    coef = frf.coefficients(w_u)
    Px, Py = Nx * grid.dx, Ny * grid.dy
    W = 0.0 if P is None else float(np.real(P[0, Ny // 2])) * grid.dx * grid.dy  # load [N]
    # T1 from responses at eps, 2 eps, 3 eps: above the FRF's floor (a layered FRF clamps
    # w h at T_MIN, which froze a finite difference taken below it: a coating of the
    # substrate's own material, h = 0.01a, kept a uniform -0.0037 p0 z/a in sigma_xx, yy),
    # and second-order accurate (the floor can push eps z to ~1e-3)
    eps = max(1e-4 / max(Px, Py), 10.0 * float(getattr(frf, "w_floor", 0.0)))
    we = np.array([eps, 2 * eps, 3 * eps])
    coef_e = frf.coefficients(we) if W else None
    lattice = _lattice_sum3(Px, Py)
    # work arrays, allocated once (fresh multi-MB arrays per depth cost page faults)
    buf = np.empty((6, Nk, Ny), dtype=cdt)
    tmp_buf = np.empty(Nk * Ny, dtype=cdt)
    tmp2_buf = np.empty(Nk * Ny, dtype=cdt)
    rad_buf = np.empty((len(needed), Nk * Ny), dtype=cdt)
    colsT_buf = np.empty(6 * ny * Nk, dtype=cdt)

    for i, z in enumerate(depths):
        rows = frf.at(w_u, z, coef)
        kk, pp, zz, kz = rows.normal
        rad = {"a_n": 0.5 * (kk + pp), "d_n": 0.5 * (kk - pp), "zz_n": zz, "kz_n": kz}
        if tangential:
            kk, pp, zz, kz = rows.tangential
            rad.update({"a_t": 0.5 * (kk + pp), "d_t": 0.5 * (kk - pp), "zz_t": zz,
                        "kz_t": kz, "kp": rows.antiplane[0], "pz": rows.antiplane[1]})
        # band: the responses decay like e^{-w z}; beyond the last |row| > BAND_TOL (of the
        # unit load) the spectrum is dropped (the field changes by < 1e-16 of the load)
        # (sampled every 8th distinct |k|, the rows being smooth in w; one sample step beyond
        # the last one above)
        amp = np.max(np.abs(np.stack([rad[name][::8] for name in needed])), axis=0)
        big = np.nonzero(amp > BAND_TOL)[0]
        w_cut = w_u[min(w_u.size - 1, 8 * big[-1] + 8)] if big.size else w_u[min(8, w_u.size - 1)]
        Kx = max(1, int(np.searchsorted(kx_v, w_cut, side="right")))
        c0 = int(np.searchsorted(ky_v, -w_cut, side="left"))
        c1 = max(c0 + 1, int(np.searchsorted(ky_v, w_cut, side="right")))
        blk = (slice(0, Kx), slice(c0, c1))
        sub_inv = inv[blk]
        size = Kx * (c1 - c0)
        # complex radial rows: complex x complex products run faster than mixed ones
        radial = {}
        for q, name in enumerate(needed):
            radial[name] = rad_buf[q, :size].reshape(Kx, c1 - c0)
            np.take(rad[name].astype(cdt), sub_inv, mode="clip", out=radial[name])
        tmp = tmp_buf[:size].reshape(Kx, c1 - c0)
        B = buf[:, :Kx, :]
        B[:, :, :c0] = 0.0
        B[:, :, c1:] = 0.0
        Bb = B[:, :, c0:c1]
        X = tmp2_buf[:size].reshape(Kx, c1 - c0)
        _accumulate(Bb[0], terms["S"], radial, blk, tmp)  # Sigma, in xx for now
        _accumulate(X, terms["X"], radial, blk, tmp)  # X = c2 Delta - s2 T_kp
        np.subtract(Bb[0], X, out=Bb[1])  # sigma_yy = Sigma - X
        Bb[0] += X  # sigma_xx = Sigma + X
        for k, group in ((2, "zz"), (3, "yz"), (4, "xz"), (5, "xy")):
            _accumulate(Bb[k], terms[group], radial, blk, tmp)
        # pruned inverse: complex transform along y of the band's k_x rows, keep the ny rows of
        # the body, then complex-to-real along x (zero beyond the band; irfft2 cropped)
        cols = sfft.ifft(B, axis=-1, overwrite_x=True, workers=1)[..., :ny]
        colsT = colsT_buf[:6 * ny * Kx].reshape(6, ny, Kx)
        np.multiply(cols.transpose(0, 2, 1), sign[:, None], out=colsT)
        out[i] = sfft.irfft(colsT, n=Nx, axis=-1, overwrite_x=True, workers=1)[..., :nx]
        if W:
            n_kk, n_pp = frf.at(we, z, coef_e).normal[:2]
            S1, S2, S3 = (n_kk[m] + n_pp[m] for m in range(3))
            T1 = (5.0 * (S2 - S1) - 3.0 * (S3 - S2)) / (2.0 * eps)  # exact for a quadratic
            shift = -W * T1 * lattice / (4 * np.pi)  # images' share of sigma_xx, sigma_yy
            out[i, 0] -= shift
            out[i, 1] -= shift
    return out


def _accumulate(dst: np.ndarray, group: list, radial: dict, blk: tuple, tmp: np.ndarray) -> None:
    """``dst = sum of radial[name] * spec[blk]`` over the ``(name, spec)`` of ``group``."""
    if not group:
        dst[...] = 0.0
        return
    for m, (name, spec) in enumerate(group):
        if m == 0:
            np.multiply(radial[name], spec[blk], out=dst)
        else:
            np.multiply(radial[name], spec[blk], out=tmp)
            dst += tmp


#: Spectral band of a depth: wavenumbers where every response row is below this (of the unit
#: surface load) are dropped.
BAND_TOL = 1e-17


def _lattice_sum3(Px: float, Py: float, m: int = 64) -> float:
    """``sum over (i, j) != 0 of |(i Px, j Py)|^-3``, direct to ``|i|, |j| <= m`` plus the
    integral of the rest (``2 pi / (Px Py R)`` beyond the radius ``R = m min(Px, Py)``)."""
    i = np.arange(-m, m + 1)
    r2 = (i[:, None] * Px) ** 2 + (i[None, :] * Py) ** 2
    r2[m, m] = np.inf
    inner = r2 <= (m * min(Px, Py)) ** 2
    R = m * min(Px, Py)
    return float(np.sum(r2[inner] ** -1.5) + 2 * np.pi / (Px * Py * R))


def stresses_normal(p: np.ndarray, grid: Grid, depths, frf, pad: int = 4) -> np.ndarray:
    """Six stress components [Pa] under the cell pressure ``p`` alone (see
    :func:`stresses_surface`)."""
    return stresses_surface(grid, depths, frf, p=p, pad=pad)


def von_mises(sig: np.ndarray, axis: int = -3) -> np.ndarray:
    """Von Mises equivalent stress of a Voigt-ordered stress array (components on ``axis``)."""
    xx, yy, zz, yz, xz, xy = np.moveaxis(sig, axis, 0)
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (yz**2 + xz**2 + xy**2))


@dataclass(frozen=True)
class StressField:
    """Stresses [Pa] in one body of an FFT contact solution.

    ``sigma`` has shape ``(len(z), 6, len(y), len(x))`` (:data:`COMPONENTS` order); ``x, y``
    [m] are the cell centres, ``z`` [m] the depths below the body's surface.
    """

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    sigma: np.ndarray
    meta: dict


def body_frf(body: Body, interface: str = "bonded"):
    """The stress responses of ``body``: homogeneous, coated (one coating, with ``interface``) or
    a layer stack (each layer's own interface, :class:`~coathertz.fft.stack_stresses.StackStressFRF`)."""
    if body.is_stacked:
        return StackStressFRF.of(body.layers, body.material)
    if body.material.is_rigid and not body.is_coated:
        raise CoatHertzError("the body is rigid: it has no stress field")
    if not body.is_coated:
        return HomogeneousStressFRF(body.material.nu)
    return CoatedStressFRF(Layer(body.coating.material, body.material, interface), body.coating.h)


def layers_depth(body: Body) -> float:
    """Total thickness [m] of the body's coating or layer stack (0 if none)."""
    return float(sum(L.h for L in body.stack))


#: Default period in domain widths, and the largest the automatic rule of :func:`image_pad` takes.
PAD, PAD_MAX = 4, 16
#: Measured uniform error of the lateral stresses from the periodic images of a coating of
#: thickness ``h`` on an elastic substrate, period ``P``: about ``IMAGE_C (h/P)^3 p0`` (against the
#: exact axisymmetric field, E = 4, H = 3, h = 4.75a: 0.115 / 0.014 / 0.0013 p0 at h/P = 0.30 /
#: 0.15 / 0.074; b4c_on_steel 8.6e-4 p0 at h/P = 0.066). The image correction takes the
#: substrate's far field, right only while ``h << P``.
IMAGE_C = 4.3
#: Largest image error the automatic period aims at [p0].
IMAGE_TOL = 0.002


def image_pad(body: Body, grid: Grid, pad: int | None = None) -> tuple[int, float]:
    """The period (in domain widths) for the stresses of ``body``, and its image error estimate
    ``IMAGE_C (h/P)^3`` [p0]: ``pad`` if given, else the smallest of ``PAD .. PAD_MAX`` with an
    estimate under ``IMAGE_TOL`` (or ``PAD_MAX``). Only a coating on an elastic substrate has
    the effect (a rigid base's field decays exponentially beyond it); a stack counts with its
    total thickness."""
    L = max(grid.nx * grid.dx, grid.ny * grid.dy)
    h = layers_depth(body) if not body.material.is_rigid else 0.0

    def estimate(n: int) -> float:
        return IMAGE_C * (h / (n * L)) ** 3

    if pad is None:
        pad = PAD
        while pad < PAD_MAX and estimate(pad) > IMAGE_TOL:
            pad *= 2
    return pad, estimate(pad)


def contact_stresses(case: ContactCase, result: ContactResult, *, body: int = 2,
                     depths=None, mu: float = 0.0, direction: float = 0.0,
                     interface: str = "bonded", pad: int | None = None,
                     Q: float | None = None, precision: str = "double") -> StressField:
    """Stress field in ``body`` (1 or 2) from an FFT solution kept with its fields.

    ``mu`` > 0 adds full sliding friction ``q = mu p`` acting on the body in the direction
    ``direction`` [rad] from x (Coulomb, no normal-tangential coupling in the pressure).
    ``Q`` [N] (``0 <= Q < mu W``) instead applies the partial-slip traction of
    :func:`coathertz.fft.partial_slip.solve_partial_slip` (homogeneous bodies only; Goodman's
    approximation). ``pad``: the FFT period in domain widths; default :func:`image_pad` (4, more
    for a coating thick against the domain, up to 16); the image error estimate is in
    ``meta["image_error_over_p0"]`` and a warning is given where it exceeds 0.5 % of p0.
    A body with a layer stack uses each layer's own interface (``interface`` must stay
    ``"bonded"``, the default). ``precision``: see :func:`stresses_surface`.
    """
    if body not in (1, 2):
        raise CoatHertzError(f"body must be 1 or 2, got {body!r}")
    if not (np.isfinite(mu) and 0 <= mu <= 1):
        raise CoatHertzError(f"friction coefficient mu must be in [0, 1], got {mu!r}")
    if "pressure" not in result.fields:
        raise CoatHertzError("the FFT result has no pressure field (solve with keep_fields=True)")
    b = case.body1 if body == 1 else case.body2
    if b.is_stacked and interface != "bonded":
        raise CoatHertzError(
            f"fft stresses: body{body} has a stack of {len(b.layers)} layers, whose interfaces are "
            f"set per layer (Layer.interface), not by interface={interface!r}")
    interface = case.interface_for(interface)  # a frictionless coating in the case is kept
    frf = body_frf(b, interface)
    x, y, p = result.fields["x"], result.fields["y"], result.fields["pressure"]
    grid = Grid(len(x), len(y), float(x[1] - x[0]), float(y[1] - y[0]))
    z = default_depths(b, result.a) if depths is None else np.asarray(depths, dtype=float)
    H = layers_depth(b)
    if b.material.is_rigid and np.any(z > H * (1 + 1e-12)):
        raise CoatHertzError(
            f"body{body}: depths must be in [0, {H:g}] m (the layers' bottom) on a rigid substrate")
    pad, image_error = image_pad(b, grid, pad)
    if image_error > 0.005:
        warnings.warn(
            f"body{body}: the {'layer stack' if b.is_stacked else 'coating'} (H = {H:g} m) is "
            "thick against the FFT period "
            f"({pad} domain widths): the lateral stresses may be off by about "
            f"{100 * image_error:.2g} % of p0 (from the periodic images of the field)",
            ModelValidityWarning, stacklevel=2)
    q = mu * p if mu > 0 else None
    if Q is not None:
        q = _partial_slip_traction(case, grid, p, Q, mu, direction, interface)
    sig = stresses_surface(grid, z, frf, p=p,
                           qx=None if q is None else np.cos(direction) * q,
                           qy=None if q is None else np.sin(direction) * q, pad=pad,
                           precision=precision)
    meta = {"method": "fft", "body": body, "mu": mu, "direction": direction,
            "interface": "per layer" if b.is_stacked else interface, "pad": pad,
            "precision": precision, "image_error_over_p0": image_error,
            "grid": grid.describe(),
            "coupling": "none (pressure from the frictionless normal solution)",
            "Q": Q, "traction": "sliding" if Q is None else "partial slip"}
    return StressField(x, y, z, sig, meta)


def _partial_slip_traction(case: ContactCase, grid: Grid, p: np.ndarray, Q: float, mu: float,
                           direction: float, interface: str = "bonded") -> np.ndarray:
    """Cattaneo--Mindlin shear traction on the cell pressure (homogeneous or single-coated
    bodies; normal--tangential coupling neglected, see :mod:`coathertz.fft.coupling`)."""
    from coathertz.fft.partial_slip import solve_partial_slip

    if Q >= mu * case.W:  # the case's load (the cell sum differs by the solver's tolerance)
        raise CoatHertzError(
            f"tangential load Q = {Q:g} N >= mu W = {mu * case.W:g} N: the contact slides "
            "(full sliding, q = mu p; partial slip needs Q < mu W)")
    bodies = []
    for i, b in enumerate((case.body1, case.body2), start=1):
        if b.is_stacked:
            raise CoatHertzError(
                f"body{i}: partial slip (Q) takes homogeneous or single-coated bodies; the "
                f"tangential compliance of a stack of {len(b.layers)} layers is not modelled yet")
        if b.is_coated:  # the layered tangential compliance (partial_slip.surface_compliance)
            bodies.append(body_frf(b, interface))
        elif not b.material.is_rigid:
            bodies.append((b.material.G, b.material.nu))
    return solve_partial_slip(p, grid, bodies, Q, mu, direction).q
