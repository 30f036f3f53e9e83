"""Graded axisymmetric mesh of a (coated) half-space, built with scikit-fem alone.

The body occupies ``0 <= r <= L`` and ``-D <= z <= 0`` (``z`` points out of the body, the
surface is ``z = 0``, the axis of symmetry ``r = 0``). The mesh is a tensor product of two
graded 1-D grids, so the coating/substrate interface ``z = -h`` is a line of element edges
and the mesh is conforming:

* in ``r``: uniform spacing ``s0 = a_ref / n_a`` on ``0 <= r <= r_fine * a_ref`` (the contact
  zone and its edge), then geometric growth by ``growth`` per element up to ``L``;
* in ``z`` (depth ``t = -z``): the coating gets ``max(n_coat, ceil(h / s0))`` elements (at least
  ``n_coat`` even for ``H = 0.01``), then the spacing relaxes to ``s0`` down to ``t_fine``,
  then grows geometrically to ``D``.

``a_ref`` is the predicted contact radius; :func:`coathertz.fem.method.FEMMethod.solve`
rebuilds the mesh around the computed radius if that falls outside the fine zone.
Elements are 4-node quadrilaterals (``MeshQuad``) to be used with the 9-node Q2 element.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from skfem import MeshQuad

from coathertz.errors import CoatHertzError


@dataclass(frozen=True)
class MeshSpec:
    """Mesh density knobs (all dimensionless, relative to the reference contact radius).

    Parameters
    ----------
    n_a
        Elements across the contact radius in the fine zone (``s0 = a_ref / n_a``).
    r_fine
        Radial extent of the fine zone in units of ``a_ref``.
    t_fine
        Depth of the fine surface layer in units of ``a_ref``.
    growth
        Geometric growth factor of the element size outside the fine zone.
    L
        Domain size (radius and depth) in units of ``max(a_ref, h)``. The outer boundary carries
        the substrate's point-load field (:mod:`coathertz.fem.farfield`), which ignores the
        coating: a bias in ``delta`` decaying like ``L^-1.7`` (measured against the exact
        axisymmetric solution, default mesh: E = 2, H = 1.3: +6.8e-5, -1.6e-5, -2.1e-5 and
        E = 4, H = 1: +3.2e-4, -0.6e-5, -3.1e-5 at L = 40, 160, 640), hence 160 (16 % more
        unknowns than 40).
    n_coat
        Minimum number of elements through the coating.
    edge
        Thin coatings: element size at the contact edge is ``edge * h / n_a`` if smaller than
        ``a_ref / n_a`` (so ``n_a / edge`` elements per coating thickness there). Measured:
        without it the contact radius of H = 0.03 coatings erred by 0.3-0.5 % at n_a = 40.
    edge_refine
        Every mesh has a band ``|r - a_ref| <= 0.15 a_ref`` of spacing ``s0 / edge_refine`` at
        the contact edge (``1``: none; thin coatings use the finer ``edge`` rule). Measured on
        thin layers bonded to a rigid base (H = h/a0c 0.05-0.5, nu_c 0.4-0.5, n_a = 40) against
        the exact axisymmetric solution, max |error in a|: 0.30 % without, 0.12 % with 2,
        0.054 % with 3 (for 30 % more unknowns than without).
    """

    n_a: int = 40
    r_fine: float = 1.5
    t_fine: float = 0.5
    growth: float = 1.3
    L: float = 160.0
    n_coat: int = 4
    edge: float = 6.0
    edge_refine: float = 3.0

    def __post_init__(self) -> None:
        if not (isinstance(self.n_a, int | np.integer) and 4 <= self.n_a <= 2000):
            raise CoatHertzError(f"n_a (elements across a) must be an integer in [4, 2000], got {self.n_a!r}")
        if not (1.05 <= self.r_fine <= 5.0):
            raise CoatHertzError(f"r_fine must be in [1.05, 5] (units of a), got {self.r_fine!r}")
        if not (0.0 < self.t_fine <= 5.0):
            raise CoatHertzError(f"t_fine must be in (0, 5] (units of a), got {self.t_fine!r}")
        if not (1.0 < self.growth <= 2.0):
            raise CoatHertzError(f"growth must be in (1, 2], got {self.growth!r}")
        if not (5.0 <= self.L <= 1e5):
            raise CoatHertzError(f"L must be in [5, 1e5] (units of max(a, h)), got {self.L!r}")
        if self.L < 2.0 * max(self.r_fine, self.t_fine):
            raise CoatHertzError(
                f"L must be at least 2 max(r_fine, t_fine) = {2.0 * max(self.r_fine, self.t_fine):g}"
                f" (units of a), got {self.L!r}"
            )
        if not (1.0 <= self.edge_refine <= 10.0):
            raise CoatHertzError(f"edge_refine must be in [1, 10], got {self.edge_refine!r}")
        if not (0.5 <= self.edge <= 1e3):
            raise CoatHertzError(f"edge must be in [0.5, 1000], got {self.edge!r}")
        if not (isinstance(self.n_coat, int | np.integer) and 1 <= self.n_coat <= 100):
            raise CoatHertzError(f"n_coat must be an integer in [1, 100], got {self.n_coat!r}")


#: Named mesh levels used by the CLI and the verification studies.
MESH_LEVELS: dict[str, MeshSpec] = {
    "coarse": MeshSpec(n_a=20, growth=1.4),
    "default": MeshSpec(n_a=40, growth=1.3),
    "fine": MeshSpec(n_a=100, growth=1.2),
}


def graded(start: float, stop: float, s_first: float, growth: float, s_max: float = math.inf) -> np.ndarray:
    """Points from ``start`` to ``stop`` (both included) whose spacing starts near ``s_first``
    and grows by ``growth`` per interval, capped at ``s_max``; rescaled to end exactly at ``stop``."""
    if stop <= start:
        return np.array([start])
    pts = [start]
    s = s_first
    while pts[-1] < stop:
        pts.append(pts[-1] + s)
        s = min(s * growth, s_max)
    x = np.array(pts)
    if len(x) > 2 and (x[-1] - stop) > 0.5 * (x[-1] - x[-2]):
        x = x[:-1]  # drop the overshooting point, stretch the rest slightly
    return start + (x - start) * (stop - start) / (x[-1] - start)


def _join(*parts: np.ndarray) -> np.ndarray:
    out = parts[0]
    for p in parts[1:]:
        out = np.concatenate([out, p[1:]])
    return out


@dataclass(frozen=True)
class LayeredMesh:
    """The mesh with its geometry: regions, fine zone and outer boundary.

    Attributes
    ----------
    mesh
        The scikit-fem quadrilateral mesh, coordinates ``(r, z)``.
    coating, substrate
        Element indices of the two regions (``coating`` empty for an uncoated body).
    a_ref, h, L, D
        Reference contact radius, coating thickness, domain radius and depth [m].
    r_fine
        Radius of the fine zone [m]: contact candidates live at ``r <= r_fine``.
    rigid_base
        True if the bottom ``z = -D = -h`` rests on a rigid substrate.
    interface
        ``bonded`` or ``frictionless`` coating/substrate interface. Frictionless with an elastic
        substrate: the two regions have their own nodes on ``z = -h`` (tied in ``u_z`` by
        :class:`coathertz.fem.model.FEModel`); on a rigid base only ``u_z = 0`` is imposed there.
    """

    mesh: MeshQuad
    coating: np.ndarray
    substrate: np.ndarray
    a_ref: float
    h: float
    L: float
    D: float
    r_fine: float
    rigid_base: bool
    spec: MeshSpec
    interface: str = "bonded"

    @property
    def n_elements(self) -> int:
        return int(self.mesh.t.shape[1])


def edge_band(a_ref: float, h: float, spec: MeshSpec) -> tuple[float, float]:
    """Spacing ``s_e`` at the contact edge and the band half-width ``w`` (a band only when ``s_e < s0``).

    Thin coatings (``edge * h / n_a < s0 / edge_refine``): ``s_e = edge * h / n_a`` and
    ``w = min(0.15 a_ref, max(0.05 a_ref, 5 h))``; otherwise ``s_e = s0 / edge_refine`` and
    ``w = 0.15 a_ref`` (no band at ``edge_refine = 1``).
    """
    s0 = a_ref / spec.n_a
    s_thin = spec.edge * h / spec.n_a
    if h > 0 and s_thin < s0 / spec.edge_refine:
        return s_thin, min(0.15 * a_ref, max(0.05 * a_ref, 5.0 * h))
    return s0 / spec.edge_refine, 0.15 * a_ref


#: Largest ratio of adjacent element sizes :func:`build_mesh` may produce (a guard against
#: slivers; measured <= 2.2 over H = 1e-3 ... 1e2 at every mesh level).
MAX_SIZE_RATIO = 4.0


def check_spacing(x: np.ndarray, what: str) -> None:
    """Raise if the 1-D grid ``x`` is not strictly increasing or has adjacent intervals whose
    sizes differ by more than :data:`MAX_SIZE_RATIO` (a degenerate, near-singular element)."""
    d = np.diff(x)
    if not np.all(d > 0):
        raise CoatHertzError(f"mesh generator: {what} grid is not strictly increasing (internal error)")
    worst = float(np.max(np.maximum(d[1:] / d[:-1], d[:-1] / d[1:]))) if len(d) > 1 else 1.0
    if worst > MAX_SIZE_RATIO:
        raise CoatHertzError(
            f"mesh generator: adjacent {what} intervals differ by a factor {worst:.3g} > {MAX_SIZE_RATIO:g}"
            " (a degenerate element; internal error, please report the case)"
        )


def _check_inputs(a_ref: float, h: float, rigid_base: bool) -> None:
    if not (a_ref > 0 and math.isfinite(a_ref)):
        raise CoatHertzError(f"a_ref must be a finite length > 0, got {a_ref!r}")
    if not (h >= 0 and math.isfinite(h)):
        raise CoatHertzError(f"h must be a finite length >= 0, got {h!r}")
    if rigid_base and h <= 0:
        raise CoatHertzError("a rigid substrate needs a coating of thickness h > 0")


def _band(a_ref: float, h: float, spec: MeshSpec) -> tuple[float, float, int]:
    """Edge spacing ``s_e``, band half-width ``w`` and the number of band elements."""
    s_e, w = edge_band(a_ref, h, spec)
    w = min(w, 0.5 * (spec.r_fine - 1.0) * a_ref)  # the band stays inside the fine zone (r_fine >= 1.05)
    n_band = round(2 * w / s_e) if s_e < a_ref / spec.n_a else 0
    return s_e, w, n_band


#: Above this many elements in the edge band :func:`mesh_size` does not build the grids (a
#: lower bound is enough to refuse the mesh; H = 1e-6 asks for 6.7e5 at the default level).
BAND_CAP = 200_000


@dataclass(frozen=True)
class MeshSize:
    """Element counts of the tensor-product mesh (``n_r`` x ``n_t``) and derived dof counts.

    ``exact`` is False when the counts are a lower bound (edge band beyond :data:`BAND_CAP`).
    """

    n_r: int
    n_t: int
    n_t_coating: int
    exact: bool = True

    @property
    def elements(self) -> int:
        return self.n_r * self.n_t

    @property
    def displacement_dofs(self) -> int:
        """Q2 vector dofs: two per node of the ``(2 n_r + 1) x (2 n_t + 1)`` node grid."""
        return 2 * (2 * self.n_r + 1) * (2 * self.n_t + 1)

    def pressure_dofs(self, coating_mixed: bool, substrate_mixed: bool) -> int:
        """Q1 pressure dofs of the mixed regions (one node set per region)."""
        n = 0
        if coating_mixed:
            n += (self.n_r + 1) * (self.n_t_coating + 1)
        if substrate_mixed:
            n += (self.n_r + 1) * (self.n_t - self.n_t_coating + 1)
        return n


def mesh_size(a_ref: float, h: float, spec: MeshSpec, rigid_base: bool = False) -> MeshSize:
    """Element counts of :func:`build_mesh` without building the mesh (and without building the
    grids when the edge band alone exceeds :data:`BAND_CAP`): the input of the memory guard."""
    _check_inputs(a_ref, h, rigid_base)
    _, _, n_band = _band(a_ref, h, spec)
    if n_band > BAND_CAP:
        return MeshSize(n_band, spec.n_coat, spec.n_coat, exact=False)
    r, t = grids(a_ref, h, spec, rigid_base)
    n_tc = int(np.sum(t[1:] <= h * (1 + 1e-12))) if h > 0 else 0
    return MeshSize(len(r) - 1, len(t) - 1, n_tc)


def grids(a_ref: float, h: float, spec: MeshSpec, rigid_base: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The radial grid ``r`` and the depth grid ``t = -z`` of :func:`build_mesh` (see module docstring)."""
    _check_inputs(a_ref, h, rigid_base)
    s0 = a_ref / spec.n_a
    q = spec.growth
    L = spec.L * max(a_ref, h)
    r_f = spec.r_fine * a_ref
    s_e, w, n_band = _band(a_ref, h, spec)
    if n_band > BAND_CAP:
        raise CoatHertzError(
            f"mesh generator: the contact-edge band of a coating with h/a_ref = {h / a_ref:.3g} would need"
            f" {n_band} elements across (> {BAND_CAP}); check the size first with mesh_size()"
        )
    if s_e < s0:
        # thin coating: the pressure edge has a boundary layer of width ~h; resolve it with
        # spacing s_e in the band |r - a_ref| <= w, grading back to s0 on both sides
        left = (a_ref - w) - graded(0.0, a_ref - w, s_e * q, q, s0)[::-1]
        band = np.linspace(a_ref - w, a_ref + w, n_band + 1)
        right = graded(a_ref + w, r_f, s_e * q, q, s0)
        r_fine = _join(left, band, right)
    else:
        r_fine = np.linspace(0.0, r_f, round(r_f / s0) + 1)
    r = _join(r_fine, graded(r_f, L, (r_fine[-1] - r_fine[-2]) * q, q))

    t_f = spec.t_fine * a_ref
    if h > 0:
        if abs(h - t_f) < 2.0 * s0:
            # The bottom of the fine layer is a soft boundary: near the interface it moves onto it.
            # Otherwise a sliver element of thickness |h - t_f| is left between the two (found at H = 0.5:
            # h = t_f (1 + 1e-12), i.e. H = 0.5 at a_ref = a0c, made the system exactly singular).
            t_f = h
        s_c = min(s0, spec.edge * h / spec.n_a)  # depth spacing in the coating (edge_refine: radial only)
        n_c = max(spec.n_coat, math.ceil(min(h, t_f) / s_c - 1e-9))
        if h <= t_f:
            t = np.linspace(0.0, h, n_c + 1)
            below = h
            if not rigid_base:
                t = _join(t, graded(h, t_f, min(h / n_c * q, s0), q, s0))
                below = t_f
        else:
            t = _join(np.linspace(0.0, t_f, round(t_f / s0) + 1), graded(t_f, h, s0 * q, q))
            below = h
        D = h if rigid_base else L
        if D > below:
            s_last = t[-1] - t[-2]
            t = _join(t, graded(below, D, s_last * q, q))
    else:
        D = L
        t = _join(np.linspace(0.0, t_f, round(t_f / s0) + 1), graded(t_f, D, s0 * q, q))
    check_spacing(r, "r")
    check_spacing(t, "depth")
    return r, t


def build_mesh(
    a_ref: float, h: float, spec: MeshSpec, rigid_base: bool = False, interface: str = "bonded"
) -> LayeredMesh:
    """Graded tensor-product mesh for a contact of radius about ``a_ref`` on a coating of
    thickness ``h`` (0: homogeneous body) over an elastic (or, ``rigid_base``, rigid) substrate;
    ``interface = 'frictionless'``: separate nodes for the two regions on ``z = -h``."""
    if interface not in ("bonded", "frictionless"):
        raise CoatHertzError(f"interface must be 'bonded' or 'frictionless', got {interface!r}")
    r, t = grids(a_ref, h, spec, rigid_base)
    L = spec.L * max(a_ref, h)
    D = h if rigid_base else L
    r_f = spec.r_fine * a_ref
    z = -t[::-1]
    if interface == "frictionless" and h > 0 and not rigid_base:
        k = int(np.argmin(np.abs(t - h)))
        sub = MeshQuad.init_tensor(r, -t[k:][::-1])
        coat = MeshQuad.init_tensor(r, -t[: k + 1][::-1])
        mesh = MeshQuad(np.hstack([coat.p, sub.p]), np.hstack([coat.t, sub.t + coat.p.shape[1]]))
    else:
        mesh = MeshQuad.init_tensor(r, z)
    zc = mesh.p[1, mesh.t].mean(axis=0)
    coating = np.nonzero(zc > -h)[0] if h > 0 else np.array([], dtype=np.int64)
    substrate = np.nonzero(zc <= -h)[0] if not rigid_base else np.array([], dtype=np.int64)
    return LayeredMesh(mesh, coating, substrate, a_ref, h, L, D, r_f, rigid_base, spec, interface)


def build_companion(lm: LayeredMesh) -> LayeredMesh:
    """A homogeneous half-space mesh with the radial grid of ``lm`` (so its surface nodes match
    ``lm``'s) and the depth grid of an uncoated body: the elastic indenter of a two-body contact."""
    r = np.unique(lm.mesh.p[0])
    t = grids(lm.a_ref, 0.0, lm.spec)[1]
    t = t[t <= r[-1] * (1 + 1e-12)] if t[-1] > r[-1] else t
    mesh = MeshQuad.init_tensor(r, -t[::-1])
    n = int(mesh.t.shape[1])
    return LayeredMesh(mesh, np.array([], dtype=np.int64), np.arange(n), lm.a_ref, 0.0, float(r[-1]),
                       float(t[-1]), lm.r_fine, False, lm.spec)
