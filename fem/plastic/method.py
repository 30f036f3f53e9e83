"""Elastic-plastic indentation of a (coated) half-space by a rigid sphere: load path and outputs.

:func:`solve_plastic` builds the axisymmetric model of a case (mesh of
:mod:`coathertz.fem.mesh`, far field and essential conditions of
:class:`coathertz.fem.model.FEModel`), gives every region with ``Material.plasticity`` the J2
law of :mod:`coathertz.fem.plastic.j2` (the others stay linear elastic), and follows a load path
with :class:`coathertz.fem.plastic.contact.IncrementalContact`:

- loading to the load ``W`` (load control) or to the approach ``delta_max`` (approach control) in
  ``n_steps`` equal increments or through explicit ``targets``; on a homogeneous body the first
  increment ends at Hertz's first yield (``_onset_target``) when that lies inside the first
  step, so the first increment is elastic;
- unloading (``unload``) always under load control, in ``n_steps`` equal load steps from the
  largest load reached down to ``W = 0``: it ends where the contact is lost (the ``W = 0`` step is
  solved without contact and gives the residual state), also after approach-controlled loading;
- reloading (``reload``) back to the largest load, under load control.

The mesh is sized for the path's largest contact (its fine zone then spans few elements across
the early contacts of a deep path: at delta/delta_c = 200 on the default mesh 3.6 at the second
increment, 25 at the last), or with ``follow_contact`` the loading runs on meshes that follow the
contact (:mod:`coathertz.fem.plastic.remesh`: each sized for the contact radius predicted at the
next target, the committed state carried over and solved again there; 9-38 elements across
the contacts of that path on the default mesh, the fewest at the sub-increments of a step that
was cut back, which run on the mesh sized for the step's end). Measured at delta/delta_c = 200,
E/Y = 1000, 20 steps: the fixed coarse mesh (12 elements across its reference radius) puts the
load at delta/delta_c = 50 2.8 % below the fixed default mesh's (8.7 elements across a there) and
the first-yield increment's 7.7 % above Hertz's; the following coarse mesh is within 0.14 % and
0.01 % of them; at delta/delta_c = 200 the four (fixed and following, coarse and default) agree
to 0.02 %.

Small strain and the half-space
idealisation are assumed: a/R > 0.1 is warned about and recorded.

Outputs (:class:`PlasticResult`): per increment the load, approach, contact radius (and the number
of elements across it, ``elements_across_a``, counted along the surface from the axis), maximum and
mean pressure, pressure profile, Newton iterations and cutbacks, the largest equivalent plastic
strain and the plastic-zone extent; at the end the residual depth and surface profile, the
residual stresses along the axis and both sides of the interface (:func:`~coathertz.fem.post.stress_report`
with the law's stresses), the equivalent plastic strain per element; ``to_json()`` for the
curves and :func:`write_vtu_series` for ParaView.
"""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from coathertz import errors
from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.farfield import BoussinesqFarField
from coathertz.fem.material import LinearElastic
from coathertz.fem.mesh import LayeredMesh, MeshSpec, build_mesh
from coathertz.fem.method import axisymmetric_equivalent, refuse_plastic_stack
from coathertz.fem.model import FEModel, Region
from coathertz.fem.plastic.assembly import BBarAssembler
from coathertz.fem.plastic.contact import (
    ContactGeometry,
    IncrementalContact,
    NewtonSettings,
    PathState,
    geometry_of,
)
from coathertz.fem.plastic.edge import edge_radius
from coathertz.fem.plastic.j2 import J2Plastic, equivalent_stress
from coathertz.fem.plastic.onset import hertz_axis_onset
from coathertz.fem.plastic.remesh import transfer_state
from coathertz.fem.post import stress_report, surface_pressure
from coathertz.materials import Material
from coathertz.validity import A_OVER_R_MAX

ModelValidityWarning = getattr(errors, "ModelValidityWarning", UserWarning)

#: Mesh levels of the elastic-plastic model (elements across the reference contact radius). The
#: fine zone is wider and deeper than the elastic model's: the plastic zone reaches ~ 1.5 a deep.
PLASTIC_MESHES: dict[str, MeshSpec] = {
    "coarse": MeshSpec(n_a=12, r_fine=2.0, t_fine=1.5, growth=1.4, L=30.0),
    "default": MeshSpec(n_a=20, r_fine=2.0, t_fine=1.5, growth=1.3, L=30.0),
    "fine": MeshSpec(n_a=32, r_fine=2.0, t_fine=1.5, growth=1.25, L=30.0),
}


#: The contact may reach this fraction of the candidate zone (the fine zone, ``r_fine * a_ref``)
#: before the mesh is grown: the radius estimators read the gap of at least 4 free nodes beyond
#: the contact edge, and the fine zone's elements must still resolve the edge.
ZONE_FILL_MAX = 0.75
#: Each growth rebuilds the mesh with ``a_ref`` enlarged by at least this factor.
ZONE_GROWTH = 1.5


class ContactZoneExceeded(CoatHertzError):
    """The contact reached the edge of its candidate zone (raised inside the path, caught by
    :func:`solve_plastic`, which grows the mesh or stops with one clear line)."""

    def __init__(self, a_edge: float, r_zone: float, W: float) -> None:
        self.a_edge, self.r_zone, self.W = a_edge, r_zone, W
        super().__init__(f"contact radius {a_edge * 1e6:.4g} um at W = {W:.4g} N reaches "
                         f"{ZONE_FILL_MAX:.0%} of the contact candidate zone (r <= {r_zone * 1e6:.4g} um)")


def reference_radius(W: float, R: float, E_star_top: float, Y_min: float | None,
                     delta_max: float | None = None) -> float:
    """Contact radius [m] the mesh is sized for: the largest the path can reach, estimated before
    meshing with the plastic flattening accounted for.

    Load control: the larger of Hertz's radius (Johnson eq 4.22) and the fully plastic one,
    ``W = pi a^2 2.8 Y`` (Tabor), times 1.05. Approach control (``delta_max``, the model's
    approach): the larger of Hertz's ``a^2 = R delta`` and the truncated sphere's
    ``a^2 = 2 R delta`` (perfectly plastic flattening, no pile-up; Kogut & Etsion's fit
    ``a^2/a_c^2 = 0.94 (delta/delta_c)^1.146`` stays below it up to delta/delta_c ~ 300).
    """
    a = float(hertz_circular(W, R, E_star_top).a0)
    if Y_min is not None:
        a = max(a, 1.05 * math.sqrt(W / (math.pi * 2.8 * Y_min)))
    if delta_max is not None:
        a = max(a, math.sqrt(2.0 * R * delta_max)) if Y_min is not None else max(a, math.sqrt(R * delta_max))
    return a


#: Contact-following paths (``follow_contact``): a mesh sized for the contact radius ``a_ref`` is
#: kept while the loading increments' contact radius stays within ``[a_ref / FOLLOW_BAND,
#: FOLLOW_BAND a_ref]`` (between about ``n_a / FOLLOW_BAND`` and ``FOLLOW_BAND n_a`` elements across
#: it); the next mesh is sized for the predicted (or reached) radius.
FOLLOW_BAND = 1.25
#: Growth exponents ``a ~ target^p`` of the next target's predicted contact radius: under approach
#: control Hertz's 1/2 and Kogut & Etsion's fully plastic 0.573 (``a^2 ~ delta^1.146``), rounded
#: up; under load control the fully plastic 1/2 (Hertz's 1/3 is below it).
FOLLOW_EXPONENT = {"approach": 0.6, "load": 0.5}
#: A rebalanced contact that outgrows its new mesh again is remeshed at most this many times.
MAX_REBALANCE_GROWTHS = 3


@dataclass
class _Stage:
    """One mesh of a path: model, assembler, contact geometry and increment loop."""

    a_ref: float
    lm: LayeredMesh
    model: FEModel
    asm: BBarAssembler
    geom: ContactGeometry
    solver: IncrementalContact

    def __post_init__(self) -> None:
        self.weights = self.model.weights_all[self.geom.cand]
        self.r_zone = float(self.geom.r[-1])
        # element edges on the surface: the number of elements across a radius, counted from the axis
        p = self.lm.mesh.p
        self.r_edges = np.unique(np.round(p[0][np.abs(p[1]) <= 1e-9 * self.a_ref], 15))
        self.top = self.model.top


class _Outgrown(Exception):
    """A loading increment's contact left the band of its contact-following mesh."""

    def __init__(self, inc, state: PathState, a_edge: float) -> None:
        super().__init__(f"contact {a_edge:.4g} m outgrew its mesh")
        self.inc, self.state, self.a_edge = inc, state, a_edge


def _predicted_radius(control: str, target: float, R: float, E_top: float, a_hint, a_now: float | None = None,
                      current: float | None = None) -> float:
    """Contact radius [m] expected at ``target``: from the reached ``a_now`` at ``current`` by
    :data:`FOLLOW_EXPONENT`, or with no contact yet Hertz's (Johnson eq 4.22; ``a^2 = R delta``)."""
    if a_now is not None and current:
        return a_now * (target / current) ** FOLLOW_EXPONENT[control]
    return math.sqrt(R * target) if control == "approach" else a_hint(target)


#: SI unit of every curve of :class:`PlasticResult` (``""``: dimensionless or a label).
CURVE_UNITS: dict[str, str] = {
    "W": "N", "delta": "m", "a": "m", "p_max": "Pa", "p_mean": "Pa", "newton_iterations": "",
    "cutbacks": "", "ep_max": "", "zone_r": "m", "zone_depth": "m", "phase": "", "residual_depth": "m",
    "cycle": "", "a_lo": "m", "a_hi": "m", "a_err": "m", "edge_exponent": "", "p_mean_lo": "Pa",
    "p_mean_hi": "Pa", "p_mean_err": "Pa", "elements_across_a": "",
}


#: The elastic onset becomes the first loading target when it lies below this fraction of the first
#: equal step (else it is close enough to a target already).
ONSET_FIRST = 0.9


def _onset_target(body, R: float, control: str) -> float | None:
    """First yield of an uncoated, homogeneous body under a rigid sphere of radius ``R`` [m]: the
    load [N] (``control = "load"``) or approach [m] at which Hertz's p0 reaches ``p0_y``
    (:func:`~coathertz.fem.plastic.onset.hertz_axis_onset`, first yield on the axis):
    ``a_y = pi R p0_y / (2 E*)`` (Johnson eq 4.23 with 4.22), ``delta_y = a_y^2 / R``,
    ``W_y = 4 E* a_y^3 / (3 R)``. ``None`` for a coated body (the onset then needs the elastic
    solution; :mod:`~coathertz.fem.plastic.onset`) or one that does not yield."""
    if body.is_coated or body.material.plasticity is None or body.material.is_rigid:
        return None
    m = body.material
    p0_y = hertz_axis_onset(m.nu)[0] * m.plasticity.Y
    a_y = math.pi * R * p0_y / (2.0 * m.E_star)
    return a_y**2 / R if control == "approach" else 4.0 * m.E_star * a_y**3 / (3.0 * R)


def _law(m: Material):
    if m.plasticity is None:
        return LinearElastic(m.E, m.nu)
    return J2Plastic(m.E, m.nu, m.plasticity)


@dataclass
class PlasticResult:
    """Curves, per-increment profiles and final fields of one elastic-plastic load path."""

    curves: dict[str, list]
    profiles: list[dict]
    final: dict
    meta: dict
    model: FEModel | None = field(default=None, repr=False)
    assembler: BBarAssembler | None = field(default=None, repr=False)
    state: PathState | None = field(default=None, repr=False)
    snapshots: list = field(default_factory=list, repr=False)
    #: ``(model, assembler)`` of every mesh of the path, in order (one unless ``follow_contact``);
    #: each snapshot names its mesh by index.
    meshes: list = field(default_factory=list, repr=False)

    def to_json(self) -> dict:
        def clean(v):
            if isinstance(v, dict):
                return {k: clean(x) for k, x in v.items()}
            if isinstance(v, list | tuple):
                return [clean(x) for x in v]
            if isinstance(v, np.ndarray):
                return clean(v.tolist())
            if isinstance(v, float | np.floating):
                return float(v) if math.isfinite(v) else None
            if isinstance(v, np.integer | np.bool_):
                return v.item()
            return v

        return clean({"curves": self.curves, "profiles": self.profiles, "final": self.final,
                      "meta": self.meta})

    def write_json(self, path: str | Path) -> None:
        Path(path).write_text(json.dumps(self.to_json(), indent=1))

    def write_csv(self, path: str | Path) -> None:
        """The per-increment curves, one row per increment, SI units in the header; an undefined
        value (the edge exponent without contact) is an empty cell."""
        import csv

        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            keys = list(self.curves)
            w.writerow([f"{k} [{CURVE_UNITS[k]}]" if CURVE_UNITS.get(k) else k for k in keys])
            for row in zip(*(self.curves[k] for k in keys), strict=True):
                w.writerow([("" if not math.isfinite(v) else repr(float(v)))  # missing: empty cell
                            if isinstance(v, float | np.floating) else v for v in row])


def _plastic_zone(asm: BBarAssembler, states: list, tol: float = 1e-12) -> dict:
    """Largest ``ep`` and the extent (max r, max depth) of the points with ``ep > tol``."""
    out = {"ep_max": 0.0, "zone_r": 0.0, "zone_depth": 0.0, "zone_top": math.nan, "plastic_points": 0}
    for (els, _), st in zip(asm.regions, states, strict=True):
        if "ep" not in st:
            continue
        ep = st["ep"]
        pl = ep > tol
        out["ep_max"] = max(out["ep_max"], float(ep.max(initial=0.0)))
        if pl.any():
            out["plastic_points"] += int(pl.sum())
            out["zone_r"] = max(out["zone_r"], float(asm.rq[els][pl].max()))
            out["zone_depth"] = max(out["zone_depth"], float(-asm.zq[els][pl].min()))
            top = float(-asm.zq[els][pl].max())
            out["zone_top"] = top if math.isnan(out["zone_top"]) else min(out["zone_top"], top)
    return out


def _first_point_yield(asm: BBarAssembler, sigmas: list) -> tuple[float, int, float, float]:
    """Max over points of ``q / Y`` with region index and (r, z) of the maximum."""
    best = (-1.0, -1, math.nan, math.nan)
    for k, ((els, law), sig) in enumerate(zip(asm.regions, sigmas, strict=True)):
        pl = getattr(law, "plasticity", None)
        if pl is None:
            continue
        ratio = equivalent_stress(sig) / pl.Y
        i = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
        if ratio[i] > best[0]:
            best = (float(ratio[i]), k, float(asm.rq[els][i]), float(asm.zq[els][i]))
    return best


def solve_plastic(
    case: ContactCase,
    mesh: str | MeshSpec = "default",
    n_steps: int = 10,
    unload: bool = False,
    reload: bool = False,
    bbar: bool = True,
    rtol: float = 1e-9,
    keep_snapshots: bool = False,
    locate_first_yield: bool = False,
    progress: Callable | None = None,
    a_ref: float | None = None,
    newton: NewtonSettings | None = None,
    targets: list[float] | None = None,
    delta_max: float | None = None,
    max_growths: int = 3,
    follow_contact: bool = False,
) -> PlasticResult:
    """Follow the load path of ``case`` (load ``W``) with the elastic-plastic FE model.

    Parameters
    ----------
    case
        A case the FE model supports (rigid sphere on a (coated) body or two identical bodies);
        materials with ``plasticity`` yield.
    mesh
        A level of :data:`PLASTIC_MESHES` or a :class:`~coathertz.fem.mesh.MeshSpec`.
    n_steps
        Load increments to ``W`` (and as many for unloading and reloading).
    unload, reload
        Unload to zero after loading; reload to ``W`` after unloading (implies ``unload``).
    bbar
        B-bar (locking-free) strain; ``False`` only for comparisons.
    locate_first_yield
        Bisect the load of the first plastic quadrature point (relative precision 1e-4).
    progress
        Called with each converged increment.
    a_ref
        Reference contact radius of the mesh [m]; default: estimated from Hertz and the yield stress.
    newton
        Tolerances and caps of the increment loop (default
        :class:`~coathertz.fem.plastic.contact.NewtonSettings` with ``rtol``).
    targets
        Explicit loading targets instead of ``n_steps`` equal ones, e.g. geometric steps for deep
        indentation: loads [N] increasing to ``case.W`` (unloading mirrors them), or with
        ``delta_max`` approaches [m] increasing to ``delta_max``.
    delta_max
        Approach control: ``n_steps`` equal approach increments (or ``targets``) to ``delta_max``
        [m]; the load comes out. Unloading then runs under load control from the largest load.
        ``case.W`` then only scales the residual tolerance (the mesh is sized from
        ``delta_max``).
    max_growths
        When the contact reaches :data:`ZONE_FILL_MAX` of its candidate zone the path is solved
        again on a mesh with a larger reference radius (:data:`ZONE_GROWTH`), at most this many
        times; then (or with ``max_growths = 0``) :class:`~coathertz.errors.CoatHertzError` stops the run. The
        reference radii tried are in ``meta["zone_growths"]``.
    follow_contact
        Loading on meshes that follow the contact (:mod:`coathertz.fem.plastic.remesh`): the first
        mesh is sized for the first target's Hertz contact, and before a target whose predicted
        contact radius leaves ``[a_ref / FOLLOW_BAND, FOLLOW_BAND a_ref]`` (or after an increment
        whose contact outgrew that band) the committed state is carried to a mesh sized for that
        radius and solved again there. Every loading increment then has about ``n_a`` to
        ``FOLLOW_BAND n_a`` elements across its contact; ``meta["remeshes"]`` lists each remesh with
        the change of the load (``W_change``; of the approach, ``delta_change``, under load control:
        ``change`` is the one that is not prescribed) in its rebalance (the transfer's error; for an
        increment that outgrew its
        mesh (``reason`` ``"outgrown"``) also the correction of a contact its old candidate zone
        had cut short). Unloading stays on the last mesh.

    Raises
    ------
    CoatHertzError
        Bad input, or a contact that outgrows its candidate zone ``max_growths`` times.
    ConvergenceError
        An increment that does not converge.
    """
    if not isinstance(follow_contact, bool):
        raise CoatHertzError(f"follow_contact must be True or False, got {follow_contact!r}")
    if not (isinstance(max_growths, int) and 0 <= max_growths <= 10):
        raise CoatHertzError(f"max_growths must be an integer in [0, 10], got {max_growths!r}")
    tried: list[float] = []
    while True:
        try:
            res = _solve_plastic_once(case, mesh, n_steps, unload, reload, bbar, rtol, keep_snapshots,
                                      locate_first_yield, progress, a_ref, newton, targets, delta_max,
                                      bool(follow_contact))
        except ContactZoneExceeded as exc:
            tried.append(exc.r_zone)
            if len(tried) > max_growths:
                raise CoatHertzError(
                    f"elastic-plastic FE: {exc}; stopped after {max_growths} mesh growth(s) "
                    "(pass a larger a_ref or a smaller load/approach)") from None
            a_ref = ZONE_GROWTH * exc.a_edge / ZONE_FILL_MAX / _r_fine_of(mesh)
            continue
        res.meta["zone_growths"] = tried
        return res


def _r_fine_of(mesh: str | MeshSpec) -> float:
    spec = PLASTIC_MESHES.get(mesh) if isinstance(mesh, str) else mesh
    return spec.r_fine if isinstance(spec, MeshSpec) else 2.0


def _solve_plastic_once(case, mesh, n_steps, unload, reload, bbar, rtol, keep_snapshots, locate_first_yield,
                        progress, a_ref, newton, targets, delta_max, follow_contact=False) -> PlasticResult:
    """One attempt of :func:`solve_plastic` on one mesh (raises :class:`ContactZoneExceeded`)."""
    refuse_plastic_stack(case, "elastic-plastic FE")
    eq = axisymmetric_equivalent(case)
    if eq is None:
        raise CoatHertzError("the elastic-plastic FE model supports a rigid sphere on a (coated) body or two "
                             "identical bodies; got: " + case.describe())
    if case.interface_for("bonded") != "bonded":
        raise CoatHertzError("the elastic-plastic FE model has a bonded coating/substrate interface only; "
                             "the case's coating rests on its substrate without friction (interface = "
                             "'frictionless'): solve it elastically with fem, axisym or fft")
    spec = PLASTIC_MESHES[mesh] if isinstance(mesh, str) and mesh in PLASTIC_MESHES else mesh
    if not isinstance(spec, MeshSpec):
        raise CoatHertzError(f"mesh must be one of {sorted(PLASTIC_MESHES)} or a MeshSpec, got {mesh!r}")
    body = eq.body
    h = body.coating.h if body.is_coated else 0.0
    rigid_base = body.material.is_rigid
    mats = list(body.deformable_materials)
    for m in mats:
        if m.nu >= 0.5:
            raise CoatHertzError(f"the elastic-plastic model needs nu < 0.5 (B-bar form), got nu = {m.nu}")
    W = case.W
    if delta_max is not None and not (isinstance(delta_max, int | float) and 0 < delta_max < math.inf):
        raise CoatHertzError(f"delta_max must be a length > 0 [m], got {delta_max!r}")
    if a_ref is None:
        ys = [m.plasticity.Y for m in mats if m.plasticity is not None]
        a_ref = reference_radius(W, eq.R, mats[0].E_star, min(ys) if ys else None,
                                 None if delta_max is None else delta_max / eq.delta_factor)
    R = eq.R
    E_top = mats[0].E_star
    control = "load" if delta_max is None else "approach"
    settings = newton or NewtonSettings(rtol=rtol)

    def a_hint(W_: float) -> float:  # Hertz radius (Johnson eq 4.22) of the top material
        return float(hertz_circular(W_, R, E_top).a0) if W_ > 0 else 0.0

    def build_stage(a_ref_: float) -> _Stage:
        lm_ = build_mesh(a_ref_, h, spec, rigid_base)
        regions = []
        if h > 0:
            regions.append(Region(lm_.coating, _law(body.coating.material)))
        if not rigid_base:
            regions.append(Region(lm_.substrate if h > 0 else np.arange(lm_.n_elements), _law(body.material)))
        model_ = FEModel(lm_, regions, None if rigid_base else body.material, BoussinesqFarField())
        asm_ = BBarAssembler(model_.basis, [(reg.elements, reg.law) for reg in regions], bbar=bbar)
        geom_ = geometry_of(model_, lambda r: r**2 / (2.0 * R), a_hint)
        solver_ = IncrementalContact(asm_, geom_, control, W, settings)
        return _Stage(a_ref_, lm_, model_, asm_, geom_, solver_)

    if not (isinstance(n_steps, int) and 1 <= n_steps <= 10000):
        raise CoatHertzError(f"n_steps must be an integer in [1, 10000], got {n_steps!r}")
    if control == "approach":
        top = delta_max / eq.delta_factor  # the model's approach
        if targets is None:
            up = [top * k / n_steps for k in range(1, n_steps + 1)]
        else:
            up = [float(t) / eq.delta_factor for t in targets]
            if not (up and all(b > a for a, b in zip([0.0, *up], up, strict=False))
                    and math.isclose(up[-1], top)):
                raise CoatHertzError("targets must increase from > 0 to the approach delta_max [m]")
    elif targets is None:
        up = [W * k / n_steps for k in range(1, n_steps + 1)]
    else:
        up = [float(t) for t in targets]
        if not (up and all(b > a for a, b in zip([0.0, *up], up, strict=False)) and math.isclose(up[-1], W)):
            raise CoatHertzError("targets must increase from > 0 to the case load W")
    onset = _onset_target(body, eq.R, control)
    if onset is not None and onset < ONSET_FIRST * up[0]:
        up = [onset, *up]  # the first increment ends at first yield: elastic, then plastic
    meta_targets = {"loading": list(up), "onset_target": onset}
    if follow_contact:  # the first mesh fits the first target's (Hertz) contact
        a_ref = _predicted_radius(control, up[0], R, E_top, a_hint)
    stages = [build_stage(a_ref)]
    solver = stages[0].solver  # the first mesh's (first-yield bisection)

    curves: dict[str, list] = {k: [] for k in CURVE_UNITS}
    profiles: list[dict] = []
    snapshots: list = []
    increments: list = []
    stage_of: list[int] = []  # the mesh (index into stages) of every recorded increment
    remeshes: list[dict] = []

    def record(inc, state: PathState, phase: str) -> None:
        cur = stages[-1]
        geom = cur.geom
        p = surface_pressure(inc.lam, cur.weights)
        a = math.nan
        if inc.active.any():
            a_edge = float(geom.r[inc.active].max())
            if follow_contact and phase == "loading" and a_edge > min(FOLLOW_BAND * cur.a_ref,
                                                                       ZONE_FILL_MAX * cur.r_zone):
                raise _Outgrown(inc, state, a_edge)
            if a_edge > ZONE_FILL_MAX * cur.r_zone:
                raise ContactZoneExceeded(a_edge, cur.r_zone, inc.W)
            edge = edge_radius(geom.r, inc.lam, inc.active)  # one estimator, every increment
            a = edge["a"]
        delta = inc.delta
        if not inc.active.any():  # no contact: a = 0; under load control (W = 0, approach undefined)
            a = 0.0              # delta is where the sphere just touches the crater's bottom
            if not math.isfinite(delta):
                delta = float(-state.u[cur.top][0])
            edge = {"a_lo": 0.0, "a_hi": 0.0, "a_err": 0.0, "n": math.nan}
        for k in ("a_lo", "a_hi", "a_err"):
            curves[k].append(edge[k])
        curves["edge_exponent"].append(edge["n"])
        curves["p_mean_lo"].append(inc.W / (math.pi * edge["a_hi"] ** 2) if edge["a_hi"] > 0 else 0.0)
        curves["p_mean_hi"].append(inc.W / (math.pi * edge["a_lo"] ** 2) if edge["a_lo"] > 0 else 0.0)
        z = _plastic_zone(cur.asm, state.states)
        curves["W"].append(inc.W)
        curves["delta"].append(eq.delta_factor * delta)
        curves["a"].append(a)
        curves["elements_across_a"].append(float(np.interp(a, cur.r_edges, np.arange(len(cur.r_edges)))))
        curves["p_max"].append(float(p.max()) if p.size else 0.0)
        curves["p_mean"].append(inc.W / (math.pi * a**2) if a > 0 else 0.0)
        curves["p_mean_err"].append(2.0 * curves["p_mean"][-1] * edge["a_err"] / a if a > 0 else 0.0)
        curves["newton_iterations"].append(inc.newton_iterations)
        curves["cutbacks"].append(inc.cutbacks)
        curves["ep_max"].append(z["ep_max"])
        curves["zone_r"].append(z["zone_r"])
        curves["zone_depth"].append(z["zone_depth"])
        curves["phase"].append(phase)
        curves["cycle"].append(bool(inc.cycle))
        curves["residual_depth"].append(float(-state.u[cur.top][0]))
        profiles.append({"r": geom.r, "p": p, "u_z": state.u[geom.cand]})
        increments.append(inc)
        stage_of.append(len(stages) - 1)
        if keep_snapshots:
            # the committed state: stresses follow from it without further flow (write_vtu_series)
            snapshots.append((state.u.copy(), [{k: v.copy() for k, v in st.items()} for st in state.states],
                              inc.W, len(stages) - 1))

    saved: dict[str, PathState] = {}

    def on_phase(phase: str):
        def on_increment(inc, state: PathState, k: int) -> None:
            record(inc, state, phase)
            if phase == "unloading" and inc.W == 0.0:
                saved["residual"] = state
            if progress is not None:
                progress(inc, phase)
        return on_increment

    def remesh(state: PathState, a_new: float, target: float, W_now: float, reason: str,
               outgrown=None) -> PathState:
        """Carry ``state`` (converged at ``target``) to a mesh sized for ``a_new`` and solve the same
        target again there (the rebalance); an increment that outgrew its mesh (``outgrown``) is
        recorded as rebalanced."""
        for _ in range(MAX_REBALANCE_GROWTHS + 1):
            old = stages[-1]
            new = build_stage(a_new)
            st = transfer_state(old.model, old.asm, state, new.model, new.asm, W_now, new.geom.r)
            out = new.solver.solve_increment(st, target)
            if out is None:
                raise ConvergenceError(
                    f"elastic-plastic FE: the rebalance after remeshing at {control} {target:.6g} "
                    f"(a_ref {old.a_ref * 1e6:.4g} -> {a_new * 1e6:.4g} um) did not converge")
            st2, inc2 = out
            stages.append(new)
            d_now = state.delta  # the model's approach before the transfer
            d_change = inc2.delta / d_now - 1.0 if d_now and math.isfinite(d_now) else 0.0
            W_change = inc2.W / W_now - 1.0 if W_now else 0.0
            remeshes.append({"target": target, "reason": reason, "a_ref_old": old.a_ref, "a_ref_new": a_new,
                             "W_before": W_now, "W_after": inc2.W, "W_change": W_change,
                             "delta_change": d_change,
                             # the free variable's change: the load's under approach control, the
                             # approach's under load control (the other is prescribed)
                             "change": W_change if control == "approach" else d_change,
                             "newton_iterations": inc2.newton_iterations,
                             "elements": new.lm.n_elements})
            if outgrown is None:
                return st2
            inc2.newton_iterations += outgrown.newton_iterations
            inc2.cutbacks = outgrown.cutbacks
            inc2.residuals = list(outgrown.residuals) + list(inc2.residuals)
            try:
                on_phase("loading")(inc2, st2, 0)
                return st2
            except _Outgrown as again:  # the rebalanced contact outgrew the new mesh too
                state, a_new, W_now, outgrown = again.state, again.a_edge, again.inc.W, again.inc
        raise CoatHertzError(f"elastic-plastic FE: the contact kept outgrowing its mesh after "
                             f"{MAX_REBALANCE_GROWTHS} remeshes at {control} {target:.6g}")

    records = []
    if not follow_contact:
        records.append(solver.run(up, progress=on_phase("loading")))
        state = records[0].state
    else:
        state, current = None, 0.0
        for tgt in up:
            if state is not None and curves["a"] and curves["a"][-1] > 0:
                a_pred = _predicted_radius(control, tgt, R, E_top, a_hint, curves["a"][-1], current)
                cur = stages[-1]
                if not cur.a_ref / FOLLOW_BAND <= a_pred <= FOLLOW_BAND * cur.a_ref:
                    state = remesh(state, a_pred, current, curves["W"][-1], "predicted")
            while current != tgt:
                try:
                    rec = stages[-1].solver.run([tgt], state=state, start=current,
                                                progress=on_phase("loading"))
                except _Outgrown as exc:
                    state = remesh(exc.state, exc.a_edge, exc.inc.target, exc.inc.W, "outgrown",
                                   outgrown=exc.inc)
                    current = exc.inc.target
                    continue
                records.append(rec)
                state, current = rec.state, tgt
    saved["loaded"] = state
    W_top = float(curves["W"][-1])
    final_stage = stages[-1]
    asm, geom, model, lm = final_stage.asm, final_stage.geom, final_stage.model, final_stage.lm
    if unload or reload:
        # unloading under load control in as many equal load steps as the loading had: it ends
        # where the contact is lost (W = 0, solved without contact: the residual state)
        unloader = (final_stage.solver if control == "load"
                    else IncrementalContact(asm, geom, "load", W, settings))
        n_down = n_steps
        down = [W_top * (1 - k / n_down) for k in range(1, n_down + 1)]
        if control == "load" and targets is not None:
            down = [*up[-2::-1], 0.0]  # explicit targets: unloading mirrors them
        meta_targets["unloading"] = down
        records.append(unloader.run(down, state=state, start=W_top, progress=on_phase("unloading")))
        if reload:
            back = [*reversed(down[:-1]), W_top]
            meta_targets["reloading"] = back
            records.append(unloader.run(back, state=records[-1].state, start=0.0,
                                        progress=on_phase("reloading")))
    if unload or reload:
        state = records[-1].state  # else the loading's last state (a remesh may have followed its run)
    factorisations = sum(st_.solver.factorisations for st_ in stages)
    if (unload or reload) and unloader is not final_stage.solver:
        factorisations += unloader.factorisations
    top = model.top
    r_top = model.r_dof[top]
    solves: dict = {}
    for st_ in stages:
        for k_, v_ in st_.geom.solves.items():
            solves[k_] = solves.get(k_, 0) + v_
    mesh_d = {"n_a": spec.n_a, "r_fine": spec.r_fine, "t_fine": spec.t_fine, "growth": spec.growth,
              "L": spec.L}
    meta: dict = {
        "elements": lm.n_elements, "h": h, "dofs": int(model.n_u), "mesh": mesh_d, "a_ref": final_stage.a_ref,
        "bbar": bbar,
        "n_steps": n_steps, "unload": bool(unload), "reload": bool(reload), "control": control,
        "increments": len(increments), "factorisations": int(factorisations),
        "linear_solves": solves,  # condensed / whole-tangent solves, condensations built (every mesh)
        "wall_time": sum(rec_.wall_time for rec_ in records), "R_model": R, "delta_factor": eq.delta_factor,
        "targets": meta_targets,
        # with the rebalances between increments (an outgrown increment's are in its own count)
        "newton_iterations_total": int(sum(curves["newton_iterations"]) + sum(
            m_["newton_iterations"] for m_ in remeshes if m_["reason"] == "predicted")),
        "follow_contact": bool(follow_contact),
        "remeshes": remeshes,
        "residual_histories": [list(inc.residuals) for inc in increments],
        "yield": {("coating" if (h > 0 and k == 0) else "substrate"): m.plasticity.key()
                  for k, m in enumerate(mats) if m.plasticity is not None},
    }
    a_max = np.nanmax(np.array(curves["a"], dtype=float)) if curves["a"] else math.nan
    if a_max / R > A_OVER_R_MAX:
        msg = (f"a/R = {a_max / R:.3g} > {A_OVER_R_MAX:g}: the small-strain, half-space model is outside its "
               "assumptions (finite deformation and the sphere's curvature matter)")
        warnings.warn(msg, ModelValidityWarning, stacklevel=3)
        meta["validity"] = msg
    if locate_first_yield:
        # on the mesh of the first plastic increment (a following path's first mesh is sized for
        # the first target only); its contact zone holds every load below that increment's
        def stage_at(k: int) -> tuple[IncrementalContact, BBarAssembler]:
            st_ = stages[stage_of[k]]
            return st_.solver, st_.asm

        xs = curves["W"] if control == "load" else [d / eq.delta_factor for d in curves["delta"]]
        meta["first_yield"] = _first_yield_load(stage_at, xs, curves)
    # final fields: stresses at the largest load and, after unloading, the residual state
    final: dict = {"plastic_zone": _plastic_zone(asm, state.states)}
    for name, st in (("loaded", saved.get("loaded")), ("residual", saved.get("residual"))):
        if st is None:
            continue
        _, _, sig_q, _ = asm.evaluate(st.u, st.states, tangent=False)
        sfields, smeta = stress_report(model, st.u, a_max, dict(enumerate(sig_q)))
        final[name] = {"u_z_surface": {"r": r_top, "u_z": st.u[top]}, "depth": float(-st.u[top][0]),
                       "stresses": sfields, "stress_extrema": smeta}
    final["residual_depth"] = final["residual"]["depth"] if "residual" in final else None
    meta["plastic_zone"] = final["plastic_zone"]
    return PlasticResult(curves, profiles, final, meta, model, asm, state, snapshots,
                         [(st_.model, st_.asm) for st_ in stages])


def _first_yield_load(stage_at: Callable, xs: list[float], curves) -> dict:
    """Bisect the load at which the first quadrature point yields (relative precision 1e-4 in the
    path's control variable ``xs``: the loads, or the model's approaches, of the increments), on
    the mesh ``stage_at(k) -> (solver, assembler)`` of the first increment ``k`` with plastic
    strain."""
    ep = np.array(curves["ep_max"])
    Ws = np.array(curves["W"])
    k = int(np.argmax(ep > 0)) if (ep > 0).any() else -1
    if k < 0:
        return {"W": None, "note": "no plastic point along the path"}
    solver, asm = stage_at(k)
    lo = float(xs[k - 1]) if k > 0 else 0.0
    hi = float(xs[k])
    W_lo, W_hi = (float(Ws[k - 1]) if k > 0 else 0.0), float(Ws[k])
    state0 = solver.initial_state()
    if lo > 0:
        rec = solver.run([lo])
        state0, W_lo = rec.state, rec.increments[-1].W
    while hi - lo > 1e-4 * hi:
        mid = 0.5 * (lo + hi)
        rec = solver.run([mid], state=state0, start=lo)
        if max(float(s_["ep"].max()) for s_ in rec.state.states if "ep" in s_) > 0:
            hi, W_hi = mid, rec.increments[-1].W
        else:
            lo, state0, W_lo = mid, rec.state, rec.increments[-1].W
    _, _, sig, _ = asm.evaluate(state0.u, state0.states, tangent=False)
    ratio, k_reg, r, z = _first_point_yield(asm, sig)
    return {"W": 0.5 * (W_lo + W_hi), "W_lo": W_lo, "W_hi": W_hi, "region": k_reg, "r": r, "z": z,
            "q_over_Y": ratio}


def write_vtu_series(result: PlasticResult, outdir: str | Path, stem: str = "plastic") -> list[Path]:
    """One VTU per increment and a ParaView ``.pvd`` time series ``{stem}.pvd`` (time = increment
    number, the row of the curves: CSV / JSON); needs ``keep_snapshots=True``.

    Point data: displacement ``u`` [m]. Cell data (element means over the quadrature points):
    stresses ``sigma_rr, sigma_zz, sigma_tt, sigma_rz`` [Pa] and von Mises ``sigma_eq`` [Pa] of the
    committed state, equivalent plastic strain ``ep`` (0 in elastic regions), ``region`` index.
    Returns the VTU paths (the ``.pvd`` is written next to them).
    """
    import meshio

    from coathertz.fem.post import STRESS_NAMES

    if not result.snapshots:
        raise CoatHertzError("no snapshots: call solve_plastic(..., keep_snapshots=True)")
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    meshes = result.meshes or [(result.model, result.assembler)]
    paths = []
    for i, (u, states, _W, m_idx) in enumerate(result.snapshots):
        model, asm = meshes[m_idx]
        mesh = model.lm.mesh
        nodal = model.basis.nodal_dofs
        points = np.column_stack([mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])])
        n_el = mesh.t.shape[1]
        disp = np.zeros((mesh.p.shape[1], 3))
        disp[:, 0], disp[:, 1] = u[nodal[0]], u[nodal[1]]
        _, _, sigmas, _ = asm.evaluate(u, states, tangent=False)
        cells = {k: np.zeros(n_el) for k in (*STRESS_NAMES, "sigma_eq", "ep", "region")}
        for k, ((els, _), st, sig) in enumerate(zip(asm.regions, states, sigmas, strict=True)):
            cells["region"][els] = k
            for j, name in enumerate(STRESS_NAMES):
                cells[name][els] = sig[j].mean(axis=-1)
            cells["sigma_eq"][els] = equivalent_stress(sig).mean(axis=-1)
            if "ep" in st:
                cells["ep"][els] = st["ep"].mean(axis=-1)
        p = outdir / f"{stem}_{i:04d}.vtu"
        meshio.write(p, meshio.Mesh(points, [("quad", mesh.t.T)], point_data={"u": disp},
                                    cell_data={k: [v] for k, v in cells.items()}))
        paths.append(p)
    entries = "\n".join(f'    <DataSet timestep="{i}" part="0" file="{p.name}"/>'
                        for i, p in enumerate(paths))
    (outdir / f"{stem}.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        f"{entries}\n  </Collection>\n</VTKFile>\n")
    return paths
