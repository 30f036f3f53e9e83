r"""Stresses inside a layered body from the exact axisymmetric solution (Hankel integrals).

The solved contact (:mod:`coathertz.axisym.solver`) gives the auxiliary function
``g(x) = sum_n c_n P_2n(x)`` and with it the Hankel transform of the surface pressure in closed
form (package docstring, Abel route):

.. math::  P(k) = \int_0^a p(r) J_0(kr)\,r\,dr = \frac{E_{ref}\,a}{\pi}\,\hat g(\xi),\qquad
           \hat g(\xi) = \int_0^1 g(x)\cos\xi x\,dx = \sum_n (-1)^n c_n\,j_{2n}(\xi),\quad \xi = k a .

Plane-strain response of the stack to one wave
-----------------------------------------------
An axisymmetric load is a superposition of plane waves ``P cos(k.x)`` over all directions of
``k``. Under one wave (``k = 1`` in scaled depth ``s = k z``, ``z`` down into the body) each layer
carries the Airy function ``phi = f(s) cos x`` with ``f'''' - 2 f'' + f = 0`` (the definition of
:mod:`coathertz.stack`): ``sigma_kk = f''``, ``sigma_zz = -f``, ``sigma_kz = f' sin x``, plane
strain ``sigma_pp = nu (f'' - f)`` (``p`` normal to ``k``), ``2 G u_k = (1 - nu) f'' + nu f``,
``2 G u_z = -(2 - nu) f' + (1 - nu) f'''``. In a layer of scaled thickness ``t = k h`` (local
depth ``0 <= s <= t``) ``f`` is a combination of the bounded functions
``e^{-s}, s e^{-s}, e^{s-t}, (t-s) e^{s-t}`` (no growing exponential; independent as
``t -> 0``); in an elastic substrate of ``(A + B s) e^{-s}``. The coefficients of all layers
follow from one linear system per ``k`` (size ``4 N + 2``, ``4 N`` on a rigid base):
``sigma_zz = -1, sigma_kz = 0`` at the surface; at a bonded interface ``u_z, u_k, sigma_zz,
sigma_kz`` continuous; at a frictionless one ``u_z, sigma_zz`` continuous and ``sigma_kz = 0`` on
both faces; on a rigid base ``u_z = u_k = 0`` (bonded) or ``u_z = sigma_kz = 0`` (frictionless).
Displacement rows are scaled by the top layer's ``G`` so that all rows are of order one. A
homogeneous half-space gives ``f = (1 + s) e^{-s}``, i.e.
``S_kk = (s - 1) e^{-s}, S_pp = -2 nu e^{-s}, S_zz = -(1 + s) e^{-s}, S_kz = -s e^{-s}``
(Boussinesq's field in Fourier space, Johnson 1985 sec. 3.2).

From waves to the axisymmetric field
------------------------------------
Rotating the wave's field to the point ``(r, 0, z)`` and integrating over the directions of
``k`` (``int cos(n alpha) e^{i x cos alpha} d alpha = 2 pi i^n J_n(x)``) gives, with the
responses ``S(k, z)`` of the body at depth ``z``:

.. math::  \sigma_{zz} &= \int_0^\infty S_{zz} P J_0(kr)\,k\,dk,\qquad
           \sigma_{rz} = \int_0^\infty S_{kz} P J_1(kr)\,k\,dk,\\
           \sigma_{rr} + \sigma_{\theta\theta} &= \int_0^\infty (S_{kk} + S_{pp}) P J_0(kr)\,k\,dk,
           \qquad
           \sigma_{rr} - \sigma_{\theta\theta} = -\int_0^\infty (S_{kk} - S_{pp}) P J_2(kr)\,k\,dk .

Quadrature
----------
In ``xi = k a`` the integrands are ``(E_ref/(pi a)) S(xi/a, z) g^(xi) J_n(xi r/a) xi``: ``g^``
oscillates with period ``2 pi`` and decays like ``xi^-2`` (smooth edge), ``J_n(xi rho)`` with
period ``2 pi/rho``, and ``S`` decays like ``e^{-xi z/a}`` times a polynomial. Composite
Gauss--Legendre (``order`` nodes per panel): geometric panels from ``2^-24`` (the scales
``a/z`` and ``a/h`` of deep points and thick layers) up to the uniform width, then panels of width
``w = min(2, 8/(1 + rho_max))`` (at most 8 radians of the fastest oscillation per 16-node panel)
up to ``X = cut * a / z_min`` (``cut = 32``: ``e^{-32} = 1e-14``). The ``J_n`` and ``g^`` do not
depend on the depth: one pass over the nodes in chunks gives all depths by matrix products.

*The surface* ``z = 0`` (where ``e^{-kz}`` no longer cuts the integrals off) is taken in closed
form: ``sigma_zz = -p(r)``, ``sigma_rz = 0`` (the boundary conditions, exactly), and with the
responses' limit at ``k -> inf`` (the top layer as a half-space: ``S_kk = -1``,
``S_pp = -2 nu_1``) split off, ``int P J_0 k dk = p(r)`` and
``int P J_2 k dk = 2 m(r)/r^2 - p(r)`` (``J_2 = 2 J_1/x - J_0``,
``m(r) = int_0^r p s ds = r int P J_1 dk``) give

.. math::  \sigma_{rr} + \sigma_{\theta\theta} = -(1 + 2\nu_1) p + R_+,\qquad
           \sigma_{rr} - \sigma_{\theta\theta} = (1 - 2\nu_1)\bigl(2 m(r)/r^2 - p\bigr) + R_-,

where the remainders ``R`` integrate ``S(k, 0) - S(inf, 0)``, which decays like
``e^{-2 k h_1}`` (cut at ``cut a / (2 h_1)``; zero on a homogeneous body: there the surface is
Boussinesq's exactly, e.g. ``sigma_rr = (1 - 2 nu) W / (2 pi r^2)`` outside the contact).
``m(r)`` is integrated in ``r = a sin(phi)`` (smooth integrand). Depths ``0 < z`` needing more
than ``MAX_NODES`` nodes are refused (the cost grows like ``a / z``): use
``z = 0`` or a depth at least :meth:`AxisymStresses.min_depth`. The nodes are processed in
chunks (coefficients, ``g^``, responses and Bessel functions per chunk), so memory does not grow
with ``X``, and each depth uses the nodes up to its own cut-off only.

Accuracy (``tests/stresses/test_axisym_stresses.py``): a homogeneous body (and a coating or stack
of the substrate's material) equals Huber's closed form (Johnson eq 3.44--3.46) to 2e-13 p0 at and
below the surface (round-off); at a fixed node density the error falls geometrically with the
nodes per panel (b4c_on_steel: 4.9e-7, 6.1e-11, 1.9e-14 p0 at 4, 6, 8 against 32; the default 16
is at round-off), and ``cut = 20`` already leaves < 1e-10 p0. Interface tractions are continuous to
round-off (~1e-16 p0) and ``int sigma_zz 2 pi r dr = -W`` holds to the radial rule's accuracy.
The panel width scales with ``order`` (``w`` above is for 16 nodes).

On an interface depth the layer above is used (``side="above"``) unless ``side="below"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.polynomial import legendre as npleg
from scipy import special

from coathertz.axisym.bessel import spherical_jn_all
from coathertz.axisym.edge import psi_hat
from coathertz.axisym.kernel import pair_compliance
from coathertz.axisym.solver import RadiusSolution, XiRule, pressure, solve_at_radius
from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import Body, Material
from coathertz.results import ContactResult

#: Components of a field's component axis: ``sigma_rr, sigma_tt (theta), sigma_zz, sigma_rz``.
COMPONENTS = ("rr", "tt", "zz", "rz")
#: The xi integrals stop where ``e^{-xi z / a} = e^{-CUT}`` (measured: 20 leaves < 1e-10 p0).
CUT = 32.0
#: Most xi nodes a field may use: sets the smallest positive depth (:meth:`AxisymStresses.min_depth`,
#: ~4e-4 a for radii to 3a); the cost grows like ``radii x nodes``.
MAX_NODES = 600_000
SIDES = ("above", "below")
#: Fields on at most this many xi nodes keep the nodes' coefficients and ``g^`` for the next field
#: on the same nodes (e.g. the other side of an interface; <= ~10 MB).
CACHE_NODES = 50_000


@dataclass(frozen=True)
class StackPart:
    """One layer of the body: ``material``, thickness ``h`` [m], top depth ``z0`` [m] and how its
    lower face is joined (``bonded`` or ``frictionless``)."""

    material: Material
    h: float
    z0: float
    interface: str


def body_parts(body: Body, interface: str) -> tuple[tuple[StackPart, ...], Material]:
    """Layers of ``body`` (top first; a single coating with the solved ``interface``) and its
    substrate (``RIGID`` allowed)."""
    parts, z0 = [], 0.0
    for L in body.stack:
        itf = L.interface if body.is_stacked else interface
        if L.h > 0:
            parts.append(StackPart(L.material, float(L.h), z0, itf))
            z0 += float(L.h)
    if not parts and body.material.is_rigid:
        raise CoatHertzError("axisym stresses: the body is rigid (it has no stress field)")
    return tuple(parts), body.material


# --- plane-strain response of the stack to one wave ---------------------------------------------


def _derivs(s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``(f, f', f'', f''')`` of the four bounded basis functions at local scaled depth ``s`` in a
    layer of scaled thickness ``t``: shape ``(4 derivs, 4 funcs, n)``."""
    e1, e2, u = np.exp(-s), np.exp(s - t), t - s
    return np.array([
        [e1, s * e1, e2, u * e2],
        [-e1, (1 - s) * e1, e2, -(1 - u) * e2],
        [e1, (s - 2) * e1, e2, (u - 2) * e2],
        [-e1, (3 - s) * e1, e2, -(3 - u) * e2],
    ])


def _derivs_half(s: np.ndarray) -> np.ndarray:
    """``(f, ..., f''')`` of ``e^{-s}, s e^{-s}`` (elastic substrate): ``(4, 2, n)``."""
    e1 = np.exp(-s)
    return np.array([[e1, s * e1], [-e1, (1 - s) * e1], [e1, (s - 2) * e1], [-e1, (3 - s) * e1]])


def _state(d: np.ndarray, mat: Material, G_ref: float) -> np.ndarray:
    """Rows ``(u_z, u_k, sigma_zz, sigma_kz)`` (displacements times ``2 G_ref``) of basis
    derivatives ``d`` (``(4, m, n)``): ``(4, m, n)``."""
    g = mat.G / G_ref
    nu = mat.nu
    f0, f1, f2, f3 = d
    return np.array([(-(2 - nu) * f1 + (1 - nu) * f3) / g, ((1 - nu) * f2 + nu * f0) / g, -f0, f1])


def _stress_rows(d: np.ndarray, nu: float) -> np.ndarray:
    """Rows ``(S_kk, S_pp, S_zz, S_kz)`` of basis derivatives ``d``: ``(4, m, n)``."""
    f0, f1, f2 = d[0], d[1], d[2]
    return np.array([f2, nu * (f2 - f0), -f0, f1])


@dataclass(frozen=True)
class StackResponse:
    """Plane-strain responses ``S(k, z)`` of layers on a substrate to ``P cos kx`` (``P = 1``)."""

    parts: tuple[StackPart, ...]
    substrate: Material

    @property
    def depth(self) -> float:
        """Total thickness of the layers [m]."""
        return sum(p.h for p in self.parts)

    @property
    def n_unknowns(self) -> int:
        return 4 * len(self.parts) + (0 if self.substrate.is_rigid else 2)

    def coefficients(self, k: np.ndarray) -> np.ndarray:
        """Basis coefficients of every layer (4 each, top first) and the substrate (2), per
        ``k`` [1/m]: shape ``(k.size, n_unknowns)``."""
        k = np.asarray(k, dtype=float)
        n, N = k.size, self.n_unknowns
        top = self.parts[0].material if self.parts else self.substrate
        G_ref = top.G
        A = np.zeros((n, N, N))
        b = np.zeros((n, N))
        zero = np.zeros(n)
        row = 0

        def put(rows: np.ndarray, col: int) -> None:  # rows: (nrows, m, n) -> A[:, row.., col..]
            nr, m = rows.shape[:2]
            A[:, row:row + nr, col:col + m] += np.moveaxis(rows, 2, 0)

        if not self.parts:  # homogeneous half-space
            st = _state(_derivs_half(zero), self.substrate, G_ref)
            put(st[2:], 0)
            b[:, 0] = -1.0
            return np.linalg.solve(A, b[..., None])[..., 0]
        # surface: sigma_zz = -1, sigma_kz = 0
        t0 = k * self.parts[0].h
        put(_state(_derivs(zero, t0), self.parts[0].material, G_ref)[2:], 0)
        b[:, 0] = -1.0
        row = 2
        for i, L in enumerate(self.parts):
            t = k * L.h
            bottom = _state(_derivs(t, t), L.material, G_ref)  # (4, 4, n)
            last = i == len(self.parts) - 1
            col = 4 * i
            if last and self.substrate.is_rigid:
                keep = [0, 1] if L.interface == "bonded" else [0, 3]
                put(bottom[keep], col)
                row += 2
                continue
            if last:
                below = _state(_derivs_half(zero), self.substrate, G_ref)  # (4, 2, n)
            else:
                nxt = self.parts[i + 1]
                below = _state(_derivs(zero, k * nxt.h), nxt.material, G_ref)
            if L.interface == "bonded":
                put(bottom, col)
                put(-below, col + 4)
                row += 4
            else:  # u_z, sigma_zz continuous; no shear on either face
                put(bottom[[0, 2]], col)
                put(-below[[0, 2]], col + 4)
                row += 2
                put(bottom[[3]], col)
                row += 1
                put(below[[3]], col + 4)
                row += 1
        return np.linalg.solve(A, b[..., None])[..., 0]

    def part_index(self, z: float, side: str = "above") -> int:
        """Layer index of depth ``z`` [m] (``len(parts)``: the substrate)."""
        tops = [p.z0 + p.h for p in self.parts]
        return sum(1 for zb in tops if (zb < z if side == "above" else zb <= z))

    def rows(self, k: np.ndarray, coef: np.ndarray, z: float, side: str = "above") -> np.ndarray:
        """``(S_kk, S_pp, S_zz, S_kz)`` at depth ``z`` [m] per ``k``: shape ``(4, k.size)``."""
        i = self.part_index(z, side)
        if i < len(self.parts):
            L = self.parts[i]
            s = k * (z - L.z0)
            d = _derivs(s, k * L.h)
            c = coef[:, 4 * i:4 * i + 4].T  # (4, n)
            nu = L.material.nu
        else:
            if self.substrate.is_rigid:
                raise CoatHertzError(
                    f"axisym stresses: depth z = {z:g} m lies in the rigid substrate "
                    f"(valid: 0 to {self.depth:g} m)")
            d = _derivs_half(k * (z - self.depth))
            c = coef[:, -2:].T
            nu = self.substrate.nu
        return np.einsum("qjn,jn->qn", _stress_rows(d, nu), c)


# --- the field ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class AxisymStressField:
    """Stresses [Pa] on the lattice ``z x r``: ``sigma[iz, component, ir]`` in the order
    :data:`COMPONENTS` (``rr, tt, zz, rz``); ``r, z`` [m], ``z`` the depth below the surface."""

    r: np.ndarray
    z: np.ndarray
    sigma: np.ndarray
    meta: dict = field(default_factory=dict)

    def voigt(self) -> np.ndarray:
        """The field on the half-plane ``y = 0, x = r`` as ``(nz, 6, 1, nr)`` in the Voigt order
        ``xx, yy, zz, yz, xz, xy`` of :mod:`coathertz.stress_summary`."""
        rr, tt, zz, rz = (self.sigma[:, j] for j in range(4))
        zero = np.zeros_like(rr)
        return np.stack([rr, tt, zz, zero, rz, zero], axis=1)[:, :, None, :]


def _xi_nodes(X: float, width: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss--Legendre on ``[0, X]``: geometric panels from ``2^-24`` up to
    ``xi_s = 2^floor(log2 width)`` (no panel wider than ``width``), then of width ``width``
    (module docstring)."""
    top = math.floor(math.log2(width))
    geo = 2.0 ** np.arange(-24, top + 1)
    xs = geo[-1]
    n_uni = max(1, math.ceil((X - xs) / width))
    b = np.concatenate([[0.0], geo, xs + width * np.arange(1, n_uni + 1)])
    zg, wg = npleg.leggauss(order)
    lo, hi = b[:-1, None], b[1:, None]
    return (0.5 * (hi - lo) * zg + 0.5 * (hi + lo)).ravel(), (0.5 * (hi - lo) * wg).ravel()


def _g_hat(sol: RadiusSolution, xi: np.ndarray, chunk: int = 4096) -> np.ndarray:
    """``g^(xi) = int_0^1 g(x) cos(xi x) dx = sum_n (-1)^n c_n j_{2n}(xi) + sum_j e_j Psi_j(xi)``
    [m] (the second sum: the edge functions of a thin layer, :func:`coathertz.axisym.edge.psi_hat`)."""
    c = sol.c
    d = c * (-1.0) ** np.arange(c.size)
    out = np.empty_like(xi)
    for i in range(0, xi.size, chunk):
        out[i:i + chunk] = d @ spherical_jn_all(2 * c.size - 2, xi[i:i + chunk])[::2]
        if sol.e.size:
            out[i:i + chunk] += sol.e @ psi_hat(sol.beta, xi[i:i + chunk])
    return out


class AxisymStresses:
    """Stresses in one body of an exact axisymmetric solution.

    Parameters
    ----------
    case, result
        The circular case and its :class:`~coathertz.axisym.method.AxisymMethod` result (its
        ``a``, ``meta["n_modes"]``, ``meta["interface"]`` and settings): the Galerkin system is
        solved again at the converged radius to recover ``g`` (milliseconds).
    body
        1 or 2: the body whose field is wanted (elastic, or coated on a rigid base).
    order
        Gauss nodes per xi panel.
    cut
        The xi integrals stop at ``cut * a / z`` (``e^{-cut}`` of the integrand left out).
    """

    def __init__(self, case: ContactCase, result: ContactResult, body: int = 2, order: int = 16,
                 cut: float = CUT) -> None:
        if result.method != "axisym" or "n_modes" not in result.meta:
            raise CoatHertzError("axisym stresses need a result of the axisym method "
                                 f"(got one of {result.method!r})")
        if body not in (1, 2):
            raise CoatHertzError(f"body must be 1 or 2, got {body!r}")
        if not (isinstance(order, int) and 4 <= order <= 64):
            raise CoatHertzError(f"order must be an integer in [4, 64], got {order!r}")
        if not (10.0 <= cut <= 200.0):
            raise CoatHertzError(f"cut must be in [10, 200], got {cut!r}")
        self.case, self.result, self.order, self.cut = case, result, order, float(cut)
        b = case.body1 if body == 1 else case.body2
        self.body_index = body
        interface = result.meta["interface"]
        parts, substrate = body_parts(b, interface)
        self.response = StackResponse(parts, substrate)
        self.pc = pair_compliance(case, interface)
        st = result.meta["settings"]
        rule = XiRule(order=st["order"], panel=float(st["panel"]))
        beta = None
        if result.meta.get("n_edge", 0):  # a thin layer solved with edge functions: the same g
            if "edge_rates" not in result.meta:
                raise CoatHertzError("axisym stresses: the result has edge functions but not their "
                                     "rates (meta['edge_rates']); solve the case again")
            beta = np.asarray(result.meta["edge_rates"], dtype=float)
        self.sol: RadiusSolution = solve_at_radius(
            self.pc, case.R, result.a, result.meta["n_modes"], rule, st["decay"], beta=beta,
            edge_condition=result.meta.get("edge_condition", "point"))
        self.a = result.a
        self.scale = self.pc.E_ref / (math.pi * self.a)  # sigma = scale * int S g^ J xi dxi
        # the layers' coefficients and g^ on the xi nodes of the last field (they depend on the
        # nodes only, not on r, z or side): a second field on the same nodes reuses them
        self._on_nodes: tuple[tuple, dict[int, tuple[np.ndarray, np.ndarray]]] = ((), {})

    # closed-form surface pieces -----------------------------------------------------------------
    def pressure(self, r: np.ndarray) -> np.ndarray:
        """``p(r)`` [Pa] (0 outside the contact)."""
        rho = np.asarray(r, float) / self.a
        out = np.zeros_like(rho)
        inside = rho < 1.0
        out[inside] = pressure(self.pc, self.sol, rho[inside])
        return out

    def load_within(self, r: np.ndarray) -> np.ndarray:
        """``m(r) = int_0^r p(s) s ds`` [N] (the load within ``r`` is ``2 pi m``), by Gauss in
        ``s = a sin(phi)`` (smooth integrand)."""
        rho = np.minimum(np.asarray(r, float) / self.a, 1.0)
        zg, wg = npleg.leggauss(2 * self.sol.c.size + 24)
        phi_max = np.arcsin(rho)[:, None]
        phi = 0.5 * phi_max * (zg[None, :] + 1.0)
        s = np.sin(phi)
        p = pressure(self.pc, self.sol, s.ravel()).reshape(s.shape)
        return self.a**2 * (p * s * np.cos(phi)) @ (0.5 * wg) * phi_max[:, 0]

    # the field --------------------------------------------------------------------------------
    def _width(self, r_max: float) -> float:
        """Uniform xi panel width for radii up to ``r_max`` (module docstring)."""
        rho_max = max(r_max / self.a, 1.0)
        return min(2.0, 8.0 / (1.0 + rho_max)) * (self.order / 16.0)

    def min_depth(self, r_max: float) -> float:
        """Smallest positive depth [m] the quadrature takes for radii up to ``r_max`` [m]
        (``MAX_NODES`` nodes)."""
        n_panels = MAX_NODES / self.order - 26
        return self.cut * self.a / (n_panels * self._width(r_max))

    def field(self, r, z, side: str = "above", chunk: int = 2048) -> AxisymStressField:
        """``sigma_rr, sigma_tt, sigma_zz, sigma_rz`` [Pa] at every ``(r, z)`` of the lattice.

        Parameters
        ----------
        r, z
            Radii ``>= 0`` and depths ``>= 0`` [m] (in the layers only on a rigid base).
        side
            On an interface depth: the layer ``above`` (default) or ``below``.
        """
        r = np.atleast_1d(np.asarray(r, dtype=float))
        z = np.atleast_1d(np.asarray(z, dtype=float))
        if side not in SIDES:
            raise CoatHertzError(f"side must be one of {SIDES}, got {side!r}")
        if np.any(~np.isfinite(r)) or np.any(r < 0):
            raise CoatHertzError("axisym stresses: radii r must be finite and >= 0 [m]")
        bottom = self.response.depth if self.response.substrate.is_rigid else math.inf
        bad = z[~(np.isfinite(z) & (z >= 0) & (z <= bottom))]
        if bad.size:
            raise CoatHertzError(f"axisym stresses: body{self.body_index} depth z = {bad[0]:g} m "
                                 f"outside the body (valid: 0 to {bottom:g} m)")
        a = self.a
        width = self._width(float(r.max()))
        zpos = z[z > 0]
        surface = bool(np.any(z == 0))
        h1 = self.response.parts[0].h if self.response.parts else math.inf
        # each depth needs the nodes up to its own cut-off only (deep points: a few hundred); the
        # surface only for the remainder S(k, 0) - S(inf, 0) ~ e^{-2 k h1}
        z_safe = np.where(z > 0, z, 1.0)
        X_z = np.where(z > 0, self.cut * a / z_safe,
                       self.cut * a / (2.0 * h1) if math.isfinite(h1) else 0.0)
        X = max(40.0, float(X_z.max()))
        n_nodes = self.order * (26 + math.ceil(X / width))
        if n_nodes > MAX_NODES:
            raise CoatHertzError(
                f"axisym stresses: depth z = {float(zpos.min()):g} m is too close to the surface for "
                f"the Hankel quadrature (needs {n_nodes} nodes > {MAX_NODES}); use z = 0 (exact "
                f"surface limit) or z >= {self.min_depth(float(r.max())):g} m")
        xi, w = _xi_nodes(X, width, self.order)
        key = (X, width, chunk)
        if self._on_nodes[0] != key:
            self._on_nodes = (key, {})
        kept = self._on_nodes[1] if xi.size <= CACHE_NODES else {}
        top = self.response.parts[0].material if self.response.parts else self.response.substrate
        nu1 = top.nu
        nz = z.size
        zz_, tr_, dev_, rz_ = (np.zeros((r.size, nz)) for _ in range(4))
        for i in range(0, xi.size, chunk):  # memory bounded by the chunk, whatever X
            act = np.nonzero(X_z >= xi[i])[0]
            if act.size == 0:
                break
            xs = xi[i:i + chunk]
            k = xs / a
            if i not in kept:
                g = _g_hat(self.sol, xs) * xs * w[i:i + chunk] * self.scale
                kept[i] = (self.response.coefficients(k), g)
            coef, base = kept[i]
            V = np.empty((4, xs.size, act.size))  # zz (J0), trace (J0), deviator (J2), rz (J1)
            for col, j in enumerate(act):
                kk, pp, zz, kz = self.response.rows(k, coef, float(z[j]), side)
                if z[j] == 0:  # subtract the k -> inf limit (added in closed form below)
                    kk, pp, zz, kz = kk + 1.0, pp + 2.0 * nu1, zz * 0.0, kz * 0.0
                V[0, :, col] = zz * base
                V[1, :, col] = (kk + pp) * base
                V[2, :, col] = -(kk - pp) * base
                V[3, :, col] = kz * base
            x = np.outer(r / a, xs)
            J0, J1 = special.j0(x), special.j1(x)
            J2 = np.where(x > 0, 2.0 * J1 / np.where(x > 0, x, 1.0) - J0, 0.0)
            zz_[:, act] += J0 @ V[0]
            tr_[:, act] += J0 @ V[1]
            dev_[:, act] += J2 @ V[2]
            rz_[:, act] += J1 @ V[3]
        if surface:
            j0s = np.nonzero(z == 0)[0]
            p = self.pressure(r)
            m = self.load_within(r)
            r2 = np.where(r > 0, r * r, 1.0)
            dev_surf = np.where(r > 0, 2.0 * m / r2 - p, 0.0)
            zz_[:, j0s] = -p[:, None]
            rz_[:, j0s] = 0.0
            tr_[:, j0s] += (-(1.0 + 2.0 * nu1) * p)[:, None]
            dev_[:, j0s] += ((1.0 - 2.0 * nu1) * dev_surf)[:, None]
        sigma = np.stack([0.5 * (tr_ + dev_), 0.5 * (tr_ - dev_), zz_, rz_]).transpose(2, 0, 1)
        meta = {"method": "axisym", "body": self.body_index, "side": side, "n_xi": int(xi.size),
                "xi_max": float(xi[-1]), "order": self.order, "cut": self.cut,
                "interface": self.result.meta["interface"], "n_modes": int(self.sol.c.size)}
        return AxisymStressField(r, z, sigma, meta)

