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

A *stack* of layers (``h`` a sequence of thicknesses, top first) puts a line of element edges at
every interface ``z = -(h_1 + ... + h_i)``; its depth grid equidistributes a target spacing
(:func:`stack_depths`) built from the same rules: at least ``n_coat`` elements through every
layer, ``min(s0, edge h_i / n_a)`` in a layer that starts inside the fine zone, ``s0`` in the
fine zone, each relaxing by ``growth - 1`` per unit of distance. The radial contact-edge band
follows the top layer's thickness. One layer (``h`` a number) is the single-coating mesh above,
point for point.

``a_ref`` is the predicted contact radius; :func:`coathertz.fem.method.FEMMethod.solve`
rebuilds the mesh around the computed radius if that falls outside the fine zone.
Elements are 4-node quadrilaterals (``MeshQuad``) to be used with the 9-node Q2 element.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
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


def thicknesses(h: float | Sequence[float]) -> tuple[float, ...]:
    """Layer thicknesses, top first: ``h`` a number (one coating; ``0``: none) or a sequence."""
    if isinstance(h, int | float | np.integer | np.floating):
        return (float(h),) if h > 0 else ()
    return tuple(float(x) for x in h)


@dataclass(frozen=True)
class LayeredMesh:
    """The mesh with its geometry: regions, fine zone and outer boundary.

    Attributes
    ----------
    mesh
        The scikit-fem quadrilateral mesh, coordinates ``(r, z)``.
    coating, substrate
        Element indices of the two regions (``coating`` empty for an uncoated body; for a stack,
        all its layers).
    a_ref, h, L, D
        Reference contact radius, coating (stack) thickness, domain radius and depth [m].
    r_fine
        Radius of the fine zone [m]: contact candidates live at ``r <= r_fine``.
    rigid_base
        True if the bottom ``z = -D = -h`` rests on a rigid substrate.
    interface
        ``bonded`` or ``frictionless`` coating/substrate interface. Frictionless with an elastic
        substrate: the two regions have their own nodes on ``z = -h`` (tied in ``u_z`` by
        :class:`coathertz.fem.model.FEModel`); on a rigid base only ``u_z = 0`` is imposed there.
        For a stack: ``frictionless`` if any of its interfaces is (see ``interfaces``).
    layers
        Element indices of each layer, top first (one entry for a single coating).
    depths
        Depth of each layer's lower face [m], top first (``depths[-1] == h``).
    interfaces
        How each layer's lower face is joined (``bonded`` or ``frictionless``), top first. Every
        frictionless interface over an elastic body has two node sets, as above.
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
    layers: tuple[np.ndarray, ...] = ()
    depths: tuple[float, ...] = ()
    interfaces: tuple[str, ...] = ()

    @property
    def n_elements(self) -> int:
        return int(self.mesh.t.shape[1])

    @property
    def bottom_interface(self) -> str:
        """How the lowest layer rests on the substrate (``bonded`` for an uncoated body)."""
        return self.interfaces[-1] if self.interfaces else self.interface

    def split_depths(self) -> tuple[float, ...]:
        """Depths of the frictionless interfaces with two node sets (not one on a rigid base)."""
        n = len(self.depths)
        return tuple(d for i, (d, f) in enumerate(zip(self.depths, self.interfaces, strict=True))
                     if f == "frictionless" and not (self.rigid_base and i == n - 1))


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


def _check_inputs(a_ref: float, h: float | Sequence[float], rigid_base: bool) -> None:
    if not (a_ref > 0 and math.isfinite(a_ref)):
        raise CoatHertzError(f"a_ref must be a finite length > 0, got {a_ref!r}")
    if isinstance(h, int | float | np.integer | np.floating):
        if not (h >= 0 and math.isfinite(h)):
            raise CoatHertzError(f"h must be a finite length >= 0, got {h!r}")
    else:
        hs = list(h)
        if not hs:
            raise CoatHertzError("h: a layer stack needs at least one layer thickness, got none")
        for i, hi in enumerate(hs, 1):
            if not (hi > 0 and math.isfinite(hi)):
                raise CoatHertzError(f"h: layer {i} thickness must be a finite length > 0 [m], got {hi!r}")
    if rigid_base and not thicknesses(h):
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
    n_t_layers: tuple[int, ...] = ()  # elements through each layer of a stack (top first)

    @property
    def elements(self) -> int:
        return self.n_r * self.n_t

    @property
    def displacement_dofs(self) -> int:
        """Q2 vector dofs: two per node of the ``(2 n_r + 1) x (2 n_t + 1)`` node grid."""
        return 2 * (2 * self.n_r + 1) * (2 * self.n_t + 1)

    def pressure_dofs(self, coating_mixed: bool | Sequence[bool], substrate_mixed: bool) -> int:
        """Q1 pressure dofs of the mixed regions (one node set per region); ``coating_mixed``
        one flag per layer of a stack (top first) or one for the coating."""
        n = 0
        if not isinstance(coating_mixed, bool | np.bool_):
            for mixed, n_t in zip(coating_mixed, self.n_t_layers, strict=True):
                n += (self.n_r + 1) * (n_t + 1) if mixed else 0
        elif coating_mixed:
            n += (self.n_r + 1) * (self.n_t_coating + 1)
        if substrate_mixed:
            n += (self.n_r + 1) * (self.n_t - self.n_t_coating + 1)
        return n


def mesh_size(a_ref: float, h: float | Sequence[float], spec: MeshSpec, rigid_base: bool = False) -> MeshSize:
    """Element counts of :func:`build_mesh` without building the mesh (and without building the
    grids when the edge band alone exceeds :data:`BAND_CAP`): the input of the memory guard."""
    _check_inputs(a_ref, h, rigid_base)
    hs = thicknesses(h)
    _, _, n_band = _band(a_ref, hs[0] if hs else 0.0, spec)
    if n_band > BAND_CAP:
        n = len(hs)
        return MeshSize(n_band, spec.n_coat * max(n, 1), spec.n_coat * n, exact=False,
                        n_t_layers=(spec.n_coat,) * n)
    r, t = grids(a_ref, h, spec, rigid_base)
    depths = np.cumsum(hs)
    below = [int(np.sum(t[1:] <= d * (1 + 1e-12))) for d in depths]
    per_layer = tuple(int(x) for x in np.diff([0, *below]))
    return MeshSize(len(r) - 1, len(t) - 1, below[-1] if below else 0, n_t_layers=per_layer)


def _radial_grid(a_ref: float, h_edge: float, L: float, spec: MeshSpec) -> np.ndarray:
    """The radial grid: the fine zone (with the contact-edge band of a top layer ``h_edge``
    thick), then geometric growth to ``L``."""
    s0 = a_ref / spec.n_a
    q = spec.growth
    r_f = spec.r_fine * a_ref
    s_e, w, n_band = _band(a_ref, h_edge, spec)
    if n_band > BAND_CAP:
        raise CoatHertzError(
            f"mesh generator: the contact-edge band of a coating with h/a_ref = {h_edge / a_ref:.3g} would"
            f" need {n_band} elements across (> {BAND_CAP}); check the size first with mesh_size()"
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
    return _join(r_fine, graded(r_f, L, (r_fine[-1] - r_fine[-2]) * q, q))


def _equidistribute(u: float, v: float, size, size_at, m: int = 16) -> np.ndarray:
    """Points from ``u`` to ``v`` (both included) equidistributing the target spacing ``size(t)``
    (``size_at``: the same for one float): ``n = ceil(int_u^v dt / size)`` intervals of equal
    ``int dt / size``, so every spacing is at most ``size``; the integral by the trapezoidal rule
    on ``m`` sub-steps per target spacing."""
    x = [u]
    while x[-1] < v:
        x.append(min(v, x[-1] + size_at(x[-1]) / m))
    x = np.array(x)
    f = 1.0 / size(x)
    F = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(x))])
    n = max(1, math.ceil(F[-1] * (1.0 - 1e-9)))
    t = np.interp(np.linspace(0.0, F[-1], n + 1), F, x)
    t[0], t[-1] = u, v
    return t


def stack_depths(a_ref: float, hs: Sequence[float], spec: MeshSpec, rigid_base: bool = False) -> np.ndarray:
    """Depth grid ``t = -z`` of a stack of layers ``hs`` (top first, two or more): every interface
    is a grid point, and each segment between them equidistributes the target spacing

    ``S(t) = min over rules of (c + (growth - 1) * distance(t, where the rule holds))``:
    ``c = s0`` on the fine zone ``t <= t_fine a_ref``; ``c = h_i / n_coat`` through layer ``i``;
    ``c = min(s0, edge h_i / n_a)`` on the part of layer ``i`` inside the fine zone (the single
    coating's rules, :func:`grids`). The ``growth - 1`` slope is geometric growth by ``growth``
    per element, as in :func:`graded`."""
    s0 = a_ref / spec.n_a
    q = spec.growth
    t_f = spec.t_fine * a_ref
    d = np.concatenate([[0.0], np.cumsum(hs)])
    D = d[-1] if rigid_base else spec.L * max(a_ref, d[-1])
    rules = [(0.0, t_f, s0)]  # (top, bottom, c): spacing c on [top, bottom], relaxing outside
    for i, h_i in enumerate(hs):
        rules.append((d[i], d[i + 1], h_i / spec.n_coat))
        if d[i] < t_f:
            rules.append((d[i], min(d[i + 1], t_f), min(s0, spec.edge * h_i / spec.n_a)))

    def size(t: np.ndarray) -> np.ndarray:
        out = np.full(t.shape, np.inf)
        for lo, hi, c in rules:
            out = np.minimum(out, c + (q - 1.0) * np.maximum(0.0, np.maximum(lo - t, t - hi)))
        return out

    def size_at(t: float) -> float:
        return min(c + (q - 1.0) * max(0.0, lo - t, t - hi) for lo, hi, c in rules)

    breaks = [*d, D] if D > d[-1] else list(d)
    return _join(*(_equidistribute(u, v, size, size_at) for u, v in itertools.pairwise(breaks)))


def grids(
    a_ref: float, h: float | Sequence[float], spec: MeshSpec, rigid_base: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """The radial grid ``r`` and the depth grid ``t = -z`` of :func:`build_mesh` (see module
    docstring); ``h`` a coating thickness or a stack's layer thicknesses (top first)."""
    _check_inputs(a_ref, h, rigid_base)
    hs = thicknesses(h)
    if len(hs) > 1:
        r = _radial_grid(a_ref, hs[0], spec.L * max(a_ref, sum(hs)), spec)
        t = stack_depths(a_ref, hs, spec, rigid_base)
        check_spacing(r, "r")
        check_spacing(t, "depth")
        return r, t
    h = hs[0] if hs else 0.0
    s0 = a_ref / spec.n_a
    q = spec.growth
    L = spec.L * max(a_ref, h)
    r = _radial_grid(a_ref, h, L, spec)

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
    a_ref: float,
    h: float | Sequence[float],
    spec: MeshSpec,
    rigid_base: bool = False,
    interface: str | Sequence[str] = "bonded",
) -> LayeredMesh:
    """Graded tensor-product mesh for a contact of radius about ``a_ref`` on a coating of
    thickness ``h`` (0: homogeneous body), or on a stack of layers ``h = (h_1, ..., h_N)`` (top
    first), over an elastic (or, ``rigid_base``, rigid) substrate. ``interface``: one for the
    coating, or one per layer (its lower face); ``frictionless`` gives the two sides of that
    interface their own nodes (not on a rigid base, where only ``u_z = 0`` holds)."""
    _check_inputs(a_ref, h, rigid_base)
    hs = thicknesses(h)
    ifs = (interface,) * len(hs) if isinstance(interface, str) else tuple(interface)
    if len(ifs) != len(hs):
        raise CoatHertzError(f"interface: one per layer expected ({len(hs)}), got {len(ifs)}")
    for i, f in enumerate(ifs, 1):
        if f not in ("bonded", "frictionless"):
            where = "interface" if isinstance(interface, str) else f"layer {i} interface"
            raise CoatHertzError(f"{where} must be 'bonded' or 'frictionless', got {f!r}")
    if isinstance(interface, str) and interface not in ("bonded", "frictionless"):
        raise CoatHertzError(f"interface must be 'bonded' or 'frictionless', got {interface!r}")
    r, t = grids(a_ref, hs if len(hs) > 1 else (hs[0] if hs else 0.0), spec, rigid_base)
    h_tot = float(sum(hs))
    depths = tuple(float(x) for x in np.cumsum(hs))
    if len(hs) == 1:
        depths = (h_tot,)
    L = spec.L * max(a_ref, h_tot)
    D = h_tot if rigid_base else L
    r_f = spec.r_fine * a_ref
    # blocks of the depth grid between frictionless interfaces (each its own node set)
    cuts = [int(np.argmin(np.abs(t - d))) for i, (d, f) in enumerate(zip(depths, ifs, strict=True))
            if f == "frictionless" and not (rigid_base and i == len(hs) - 1)]
    if cuts:
        bounds = [0, *cuts, len(t) - 1]
        blocks = [MeshQuad.init_tensor(r, -t[k0 : k1 + 1][::-1])
                  for k0, k1 in itertools.pairwise(bounds)]
        offsets = np.cumsum([0] + [b.p.shape[1] for b in blocks[:-1]])
        mesh = MeshQuad(np.hstack([b.p for b in blocks]),
                        np.hstack([b.t + o for b, o in zip(blocks, offsets, strict=True)]))
    else:
        mesh = MeshQuad.init_tensor(r, -t[::-1])
    zc = mesh.p[1, mesh.t].mean(axis=0)
    tops = (0.0, *depths[:-1]) if depths else ()
    layers = tuple(np.nonzero((zc < -top) & (zc > -bot))[0] for top, bot in zip(tops, depths, strict=True))
    coating = np.nonzero(zc > -h_tot)[0] if hs else np.array([], dtype=np.int64)
    substrate = np.nonzero(zc <= -h_tot)[0] if not rigid_base else np.array([], dtype=np.int64)
    single = interface if isinstance(interface, str) else "bonded"
    summary = "frictionless" if "frictionless" in ifs else (ifs[0] if ifs else single)
    return LayeredMesh(mesh, coating, substrate, a_ref, h_tot, L, D, r_f, rigid_base, spec, summary,
                       layers, depths, ifs)


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
