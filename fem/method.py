"""``FEMMethod``: the axisymmetric finite-element model behind the common ``Method`` interface.

Supported cases (``supports``): circular contacts in which

* one body is rigid and uncoated (the indenter) and the other elastic, coated or not, with an
  elastic or a rigid substrate: one (coated) half-space under a rigid paraboloid of the
  relative radius ``R`` of the case;
* two identical elastic bodies (same substrate, coating and thickness): under the half-space
  assumption both carry the same pressure and deform alike, so the pair is one body under a
  rigid paraboloid of radius ``2 R`` with half the approach (``delta = 2 delta_1``).

* an elastic homogeneous indenter on a different elastic body, coated or not: both bodies are
  meshed as half-spaces under the same small-strain assumptions, with matching surface nodes
  (the indenter's mesh reuses the body's radial grid), and the contact couples them node to
  node: the gap is ``g0(r) - delta - u_z(body) - u_z(indenter)`` with equal and opposite nodal
  forces, ``g0 = r^2 / 2R`` with the case's relative radius. In the condensed contact solve the
  indenter enters as its own candidates' compliance added to the body's
  (:class:`coathertz.fem.contact.TwoBody`). Checked against Hertz (two different homogeneous
  bodies) and the DC-FFT (Section 6 B4C example) in ``tests/fem/test_two_body.py``.

The deformable body may carry a layer stack (``Body.layers``, top first): each layer is its own
region of the mesh (:func:`coathertz.fem.mesh.build_mesh` puts element edges on every interface),
each interface bonded or frictionless as the layer says, on an elastic or rigid substrate. A
one-layer stack is the coating case, number for number. Checked against the exact method
(axisym) in ``tests/multilayer/test_fe_stack.py``. Stacks are elastic only: the plastic path
(:mod:`coathertz.fem.plastic`) refuses them.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import numpy as np

from coathertz import validity
from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.contact import ActiveSet, Penalty, TwoBody
from coathertz.fem.farfield import BoussinesqFarField, FixedFarField
from coathertz.fem.loading import LoadPath, solve_incremental
from coathertz.fem.material import LinearElastic
from coathertz.fem.mesh import MESH_LEVELS, MeshSize, build_companion, build_mesh, edge_band, mesh_size
from coathertz.fem.model import FEModel, Region
from coathertz.fem.post import AXIS_TOL, contact_radius, peak_pressure, stress_report, surface_pressure
from coathertz.fem.solvers import AMGSolver, DirectSolver
from coathertz.materials import Body, Layer, Material
from coathertz.methods import require_case
from coathertz.results import ContactResult
from coathertz.validity import A_OVER_R_MAX

CONTACTS = {"active-set": lambda beta: ActiveSet(), "penalty": lambda beta: Penalty(beta=beta)}
SOLVERS = {"direct": DirectSolver, "amg": AMGSolver}
FARFIELDS = {"boussinesq": BoussinesqFarField, "fixed": FixedFarField}


@dataclass(frozen=True)
class Equivalent:
    """The single deformable body, the rigid paraboloid radius and the approach factor."""

    body: Body
    R: float
    delta_factor: float
    indenter: Material | None = None  # an elastic homogeneous indenter, modelled as a second body


def axisymmetric_equivalent(case: ContactCase, stacks: bool = False) -> Equivalent | None:
    """The model problem that ``case`` reduces to, or ``None`` (see module docstring); a case
    with a layer stack only with ``stacks=True`` (the elastic model; the plastic path has none)."""
    if not case.is_circular or (case.is_stacked and not stacks):
        return None
    b1, b2 = case.body1, case.body2
    if b1.is_rigid and not b2.is_rigid:
        return Equivalent(b2, case.R, 1.0)
    if b2.is_rigid and not b1.is_rigid:
        return Equivalent(b1, case.R, 1.0)
    pair = case.identical_pair_equivalent()  # the one two-identical-bodies equivalence
    if pair is not None:
        return Equivalent(pair.body2, pair.R, case.IDENTICAL_PAIR_DELTA_FACTOR)
    for ind, other in ((b1, b2), (b2, b1)):
        if not ind.is_coated and not ind.is_stacked and not ind.material.is_rigid and not other.is_rigid:
            return Equivalent(other, case.R, 1.0, indenter=ind.material)
    return None


#: Peak memory per unknown of one solve [bytes], measured as peak RSS over dofs: 7.4 kB
#: (displacement form, 194k dofs) and 12.3 kB (a mixed u-p region, 83k dofs; COLAMD fills the LU
#: four times more); rounded up, plus the interpreter and libraries (:data:`BASE_BYTES`).
BYTES_PER_DOF = {"displacement": 10_000, "mixed": 20_000}
#: Bytes of an FE solve independent of its size (the interpreter and the libraries).
BASE_BYTES = 300e6


def refuse_plastic_stack(case: ContactCase, what: str) -> None:
    """Raise one clear line if ``case`` has a layer stack: the elastic-plastic FE (``what``) models
    one coating at most."""
    for name in ("body1", "body2"):
        body = getattr(case, name)
        if body.is_stacked:
            raise CoatHertzError(
                f"{what}: {name} has a stack of {len(body.layers)} layers; plasticity is modelled for"
                " one coating at most (layers: not supported): solve the stack elastically with fem,"
                " axisym or fft")


def default_max_memory_gb() -> float:
    """Half the physical memory, at most 8 GiB: the default memory budget of one FE solve."""
    try:
        phys = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):
        phys = 16.0
    return min(8.0, 0.5 * phys)


def estimate_memory(
    size: MeshSize, coating_mixed: bool | tuple[bool, ...], substrate_mixed: bool
) -> tuple[int, float]:
    """Unknowns and estimated peak memory [bytes] of a solve on a mesh of ``size``
    (``coating_mixed``: one flag per layer of a stack)."""
    dofs = size.displacement_dofs + size.pressure_dofs(coating_mixed, substrate_mixed)
    any_coat = coating_mixed if isinstance(coating_mixed, bool) else any(coating_mixed)
    per = BYTES_PER_DOF["mixed" if (any_coat or substrate_mixed) else "displacement"]
    return dofs, BASE_BYTES + per * dofs


def _mesh_thickness(layers: tuple[Layer, ...]) -> float | tuple[float, ...]:
    """The ``h`` of :func:`~coathertz.fem.mesh.build_mesh`: the coating's thickness (0: none), or
    the layer thicknesses of a stack of two or more (top first)."""
    if len(layers) > 1:
        return tuple(L.h for L in layers)
    return layers[0].h if layers else 0.0


def _finite_or_none(x: float) -> float | None:
    """JSON has no NaN: undefined estimates are stored as ``None``."""
    return float(x) if math.isfinite(x) else None


def _choice(name: str, value: str, options: dict) -> Any:
    if value not in options:
        raise CoatHertzError(f"{name} must be one of {sorted(options)}, got {value!r}")
    return options[value]


#: Elements across the contact radius at the ``quick`` resolution (the main job): 30 instead of the
#: default mesh's 40. Measured on the 21 elastic FE cases of the quick studies (AMD EPYC, one
#: process): 14.5 -> 9.1 CPU-s; the largest difference from the exact method grows from 0.043 % to
#: 0.065 % in a and from 0.006 % to 0.011 % in p0 (delta: 0.007 % both), below every bound the FE
#: takes part in (multilayer: 0.1 % in a, 0.02 % in delta and p0).
QUICK_N_A = 30


class FEMMethod:
    """Axisymmetric FE contact model (scikit-fem, Q2 elements, Taylor-Hood u-p for nu >= 0.45).

    Parameters
    ----------
    mesh
        Mesh level: ``coarse`` (20 elements across a), ``default`` (40), ``fine`` (100).
    contact
        ``active-set`` (Lagrange multipliers, exact) or ``penalty``.
    solver
        ``direct`` (SuperLU, reference) or ``amg`` (CG + pyamg smoothed aggregation; the mixed
        u-p system always uses the direct solver).
    farfield
        ``boussinesq`` (point-load field on the outer boundary) or ``fixed`` (clamped).
    penalty_beta
        Dimensionless penalty stiffness (``penalty`` only), ``> 0``.
    mixed
        ``auto`` (u-p in regions with nu >= 0.45), ``always`` or ``never``.
    n_steps
        Load increments (>= 1); linear laws give the same answer for any value.
    stresses
        Compute the subsurface stress profiles (axis, interface) into ``fields``/``meta``.
    max_remesh
        How often the mesh may be rebuilt around the computed contact radius.
    n_a, L
        Override the mesh level's elements across ``a`` and domain size (units of max(a, h)).
    interface
        Coating/substrate interface: ``bonded`` (the paper's model) or ``frictionless`` (normal
        displacement continuous, tangential slip free; elastic or rigid substrate).
    max_memory_gb
        Memory budget of one solve [GiB] (default: half the physical memory, at most 8). The
        unknowns and memory are estimated from the mesh size before anything is built
        (:func:`estimate_memory`); a larger estimate raises
        :class:`~coathertz.errors.CoatHertzError`. Does not change any number, so it is not part of
        :meth:`settings`.
    """

    # method metadata (coathertz.methods)
    cost: ClassVar[str] = "expensive"
    marker: ClassVar[str] = "s"
    label: ClassVar[str] = "axisymmetric FE"
    reference_rank: ClassVar[int] = 10
    source_packages: ClassVar[tuple[str, ...]] = ("coathertz.fem",)

    @classmethod
    def settings_for(cls, resolution: str) -> dict[str, Any]:
        """Coarse mesh at ``tiny``; at ``quick`` the default mesh with :data:`QUICK_N_A` elements
        across a; the default mesh at ``full``."""
        if resolution == "tiny":
            return {"mesh": "coarse"}
        if resolution == "quick":
            return {"mesh": "default", "n_a": QUICK_N_A}
        return {"mesh": "default"}


    name = "fem"

    #: One factorisation per contact problem (condensed solve, :mod:`coathertz.fem.contact`) and
    #: the rectangle-table assembly (:mod:`coathertz.fem.affine`); False restores the refactorising
    #: active-set path and skfem's generic assembly (the path before the condensed solve, kept for the
    #: benchmark's ``--legacy`` rows).
    _reuse_factorisation: bool = True

    def __init__(
        self,
        mesh: str = "default",
        contact: str = "active-set",
        solver: str = "direct",
        farfield: str = "boussinesq",
        penalty_beta: float = 1e3,
        mixed: str = "auto",
        n_steps: int = 1,
        stresses: bool = False,
        max_remesh: int = 3,
        n_a: int | None = None,
        L: float | None = None,
        max_memory_gb: float | None = None,
        interface: str = "bonded",
    ) -> None:
        spec = _choice("mesh", mesh, MESH_LEVELS)
        over = {k: v for k, v in (("n_a", n_a), ("L", L)) if v is not None}
        self.spec = replace(spec, **over) if over else spec
        self.overrides = over
        _choice("contact", contact, CONTACTS)
        _choice("solver", solver, SOLVERS)
        _choice("farfield", farfield, FARFIELDS)
        _choice("mixed", mixed, {"auto": 0, "always": 1, "never": 2})
        _choice("interface", interface, {"bonded": 0, "frictionless": 1})
        self.interface = interface
        if not (isinstance(penalty_beta, int | float) and 0 < penalty_beta < math.inf):
            raise CoatHertzError(f"penalty_beta must satisfy 0 < penalty_beta < inf, got {penalty_beta!r}")
        if not (isinstance(n_steps, int) and 1 <= n_steps <= 1000):
            raise CoatHertzError(f"n_steps must be an integer in [1, 1000], got {n_steps!r}")
        if not (isinstance(max_remesh, int) and 0 <= max_remesh <= 10):
            raise CoatHertzError(f"max_remesh must be an integer in [0, 10], got {max_remesh!r}")
        self.mesh, self.contact, self.solver, self.farfield = mesh, contact, solver, farfield
        self.penalty_beta, self.mixed, self.n_steps = float(penalty_beta), mixed, n_steps
        self.stresses, self.max_remesh = bool(stresses), max_remesh
        if max_memory_gb is None:
            max_memory_gb = default_max_memory_gb()
        if not (isinstance(max_memory_gb, int | float) and 0 < max_memory_gb < math.inf):
            raise CoatHertzError(f"max_memory_gb must satisfy 0 < max_memory_gb < inf, got {max_memory_gb!r}")
        self.max_memory_gb = float(max_memory_gb)

    def settings(self) -> dict[str, Any]:
        s = {"mesh": self.mesh, "contact": self.contact, "solver": self.solver, "farfield": self.farfield}
        if self.contact == "penalty":
            s["penalty_beta"] = self.penalty_beta
        if self.mixed != "auto":
            s["mixed"] = self.mixed
        if self.interface != "bonded":
            s["interface"] = self.interface
        s.update(self.overrides)
        return s

    def supports(self, case: ContactCase) -> bool:
        return self._stack_refusal(case) is None and axisymmetric_equivalent(case, stacks=True) is not None

    def _stack_refusal(self, case: ContactCase) -> str | None:
        """Why this method cannot solve ``case``'s layer stack (``None``: it can, or no stack)."""
        if not case.is_stacked:
            return None
        name = "body1" if case.body1.is_stacked else "body2"
        n = len(getattr(case, name).layers)
        if self.interface != "bonded":
            return (f"fem: {name} has a stack of {n} layers, whose interfaces are set per layer"
                    f" (Layer.interface); the method's interface={self.interface!r} applies to one coating"
                    " only: leave it at 'bonded'")
        return None

    # ------------------------------------------------------------------------------------
    def _regions(self, lm, body: Body) -> list[Region]:
        is_mixed = self._is_mixed
        regions = []
        for els, layer in zip(lm.layers, body.stack, strict=True):
            cm = layer.material
            regions.append(Region(els, LinearElastic(cm.E, cm.nu), is_mixed(cm)))
        if not lm.rigid_base:
            sm = body.material
            els = lm.substrate if lm.h > 0 else np.arange(lm.n_elements)
            regions.append(Region(els, LinearElastic(sm.E, sm.nu), is_mixed(sm)))
        for reg in regions:
            if reg.law.nu >= 0.5 and not reg.mixed:
                raise CoatHertzError("nu = 0.5 needs the mixed u-p form: use mixed='auto' or 'always'")
        return regions

    def check_size(self, a_ref: float, body: Body, R: float) -> tuple[MeshSize, int, float]:
        """Refuse, before anything is built, a mesh whose estimated memory exceeds the budget.

        Returns the mesh size, the unknowns and the estimated peak memory [bytes].
        """
        layers = body.stack
        h = _mesh_thickness(layers)
        rigid_base = body.material.is_rigid
        size = mesh_size(a_ref, h, self.spec, rigid_base)
        c_mixed = tuple(self._is_mixed(L.material) for L in layers) if len(layers) > 1 else (
            bool(layers) and self._is_mixed(layers[0].material))
        s_mixed = not rigid_base and self._is_mixed(body.material)
        dofs, mem = estimate_memory(size, c_mixed, s_mixed)
        h = layers[0].h if layers else 0.0  # the top layer sets the contact-edge band
        limit = self.max_memory_gb * 2**30
        if mem <= limit:
            return size, dofs, mem
        level = f"mesh={self.mesh!r}" + "".join(f", {k}={v!r}" for k, v in self.overrides.items())
        s_e, _ = edge_band(a_ref, h, self.spec)
        if h > 0 and s_e < a_ref / self.spec.n_a and size.n_r > 4 * self.spec.n_a * self.spec.r_fine:
            what = "the top layer of the stack" if len(layers) > 1 else "the coating"
            cause = (
                f"{what} is very thin, H = h/a = {h / a_ref:.3g} (h = {h:.4g} m, a ~ {a_ref:.4g} m): the"
                f" contact edge is resolved with elements of size {self.spec.edge:g} h / n_a = {s_e:.3g} m"
            )
            without = "the stack without that layer" if len(layers) > 1 else "the uncoated substrate"
            hint = (
                f"use the fft method, or, for H < 1e-3, {without} ({what} changes delta, a"
                " and p0 by O(H)); a coarser mesh (mesh='coarse' or a smaller n_a) or a larger"
                " max_memory_gb if the machine has the memory"
            )
        else:
            cause = f"{self.spec.n_a} elements across the contact radius a ~ {a_ref:.4g} m"
            hint = "use a coarser mesh (mesh='coarse' or a smaller n_a) or a larger max_memory_gb"
        if a_ref / R > A_OVER_R_MAX:
            cause += f"; note a/R ~ {a_ref / R:.3g} > {A_OVER_R_MAX:g}: outside the half-space model anyway"
        bound = "" if size.exact else "at least "
        raise CoatHertzError(
            f"fem ({level}): the mesh would have {bound}{size.elements:.3g} elements and {bound}{dofs:.3g}"
            f" unknowns, an estimated {mem / 2**30:.3g} GiB of memory, over the limit max_memory_gb ="
            f" {self.max_memory_gb:g} GiB. Cause: {cause}. To change: {hint}."
        )

    def _indenter(self, lm, mat: Material, W: float, contact, r_c: np.ndarray) -> TwoBody:
        """The indenter's half-space model on the body's radial grid, condensed on its candidates."""
        im = build_companion(lm)
        region = Region(np.arange(im.n_elements), LinearElastic(mat.E, mat.nu), self._is_mixed(mat))
        model = FEModel(im, [region], mat, FARFIELDS[self.farfield]())
        if not self._reuse_factorisation:
            raise CoatHertzError("an elastic indenter needs the condensed contact solve")
        return TwoBody.build(contact, model, W, r_c)

    def _is_mixed(self, m: Material) -> bool:
        return self.mixed == "always" or (self.mixed == "auto" and m.nu >= 0.45)

    def _predict_a(self, eq: Equivalent, W: float) -> float:
        """Contact radius to build the first mesh around: the Hertz radii of the layers and the
        substrate weighted by ``exp(-depth / a)`` (a stack: each layer by its share of it)."""
        body = eq.body
        layers = body.stack
        c_ind = eq.indenter.compliance if eq.indenter is not None else 0.0

        def E_pair(m: Material) -> float:  # the pair's E* (eq 2) with an elastic indenter
            return 1.0 / (m.compliance + c_ind) if (m.compliance + c_ind) > 0 else math.inf

        if not layers:
            return float(hertz_circular(W, eq.R, E_pair(body.material)).a0)
        a_c = float(hertz_circular(W, eq.R, E_pair(layers[0].material)).a0)
        if len(layers) == 1:
            h = layers[0].h
            if body.material.is_rigid and c_ind == 0:
                return a_c
            a_s = float(hertz_circular(W, eq.R, E_pair(body.material)).a0)
            wgt = 1.0 - math.exp(-h / a_s)
            return a_s + (a_c - a_s) * wgt
        rigid = body.material.is_rigid and c_ind == 0
        a_s = a_c if rigid else float(hertz_circular(W, eq.R, E_pair(body.material)).a0)
        depth, a_w = 0.0, 0.0
        for L in layers:
            w_top, w_bot = math.exp(-depth / a_s), math.exp(-(depth + L.h) / a_s)
            a_w += float(hertz_circular(W, eq.R, E_pair(L.material)).a0) * (w_top - w_bot)
            depth += L.h
        w_sub = math.exp(-depth / a_s)
        return a_w / (1.0 - w_sub) if rigid else a_w + a_s * w_sub

    def solve(self, case: ContactCase) -> ContactResult:
        return self.solve_full(require_case(case, self.name))[0]

    def solve_full(self, case: ContactCase, a_guess: float | None = None
                   ) -> tuple[ContactResult, FEModel, LoadPath]:
        """Like :meth:`solve`, also returning the model and the load path (for VTU output).

        ``a_guess``: the contact radius to build the first mesh around, where the caller knows a
        better one than the layered Hertz estimate (``_predict_a``), e.g. a search over loads
        from its previous solve; the mesh is rebuilt around the computed radius as always if that
        falls outside the refined zone."""
        why = self._stack_refusal(case)
        if why is not None:
            raise CoatHertzError(why)
        eq = axisymmetric_equivalent(case, stacks=True)
        if eq is None:
            raise CoatHertzError(
                "fem supports circular contacts of a rigid or elastic uncoated indenter with an elastic"
                " (coated) body, or of two identical bodies; got: " + case.describe()
            )
        t0 = time.perf_counter()
        body = eq.body
        layers = body.stack  # the coating as a one-layer stack
        h = _mesh_thickness(layers)
        h_top = layers[0].h if layers else 0.0  # sets the contact-edge band
        rigid_base = body.material.is_rigid
        ff_mat = None if rigid_base else body.material
        E_ref = layers[0].material.E_star if layers else body.material.E_star

        def g0(r):
            return r**2 / (2.0 * eq.R)  # Hertz paraboloid

        if a_guess is not None and not (0 < a_guess < math.inf):
            raise CoatHertzError(f"a_guess must satisfy 0 < a_guess < inf [m], got {a_guess!r}")
        a_ref = self._predict_a(eq, case.W) if a_guess is None else float(a_guess)
        interface = case.interface_for(self.interface)
        interfaces = tuple(L.interface for L in layers) if case.is_stacked else interface
        remeshes = 0
        active0 = None
        while True:
            self.check_size(a_ref, body, eq.R)
            lm = build_mesh(a_ref, h, self.spec, rigid_base, interfaces)
            model = FEModel(lm, self._regions(lm, body), ff_mat, FARFIELDS[self.farfield](),
                            legacy_assembly=not self._reuse_factorisation)
            if any(reg.mixed for reg in model.regions) or model.tie.shape[1]:
                solver = DirectSolver(symmetric_mode=False)  # indefinite saddle point
            else:
                solver = SOLVERS[self.solver]()
            r_c = model.r_dof[model.candidates]
            active0 = r_c <= a_ref
            contact = replace(CONTACTS[self.contact](self.penalty_beta), reuse=self._reuse_factorisation)
            if eq.indenter is not None:
                contact = self._indenter(lm, eq.indenter, case.W, contact, r_c)
            path = solve_incremental(
                model, contact, solver, case.W, g0, E_ref,
                a_ref / self.spec.n_a, n_steps=self.n_steps, active0=active0,
            )
            sol = path.solution
            p = surface_pressure(sol.lam, model.weights_all[model.candidates])
            radii = contact_radius(r_c, p, sol.gap, sol.active)
            a = radii["a"]
            # penetration outside the candidate zone?
            top = model.top
            gap_top = g0(model.r_dof[top]) - sol.delta - path.x[top]
            outside_ok = np.all(gap_top[model.r_dof[top] > lm.r_fine] >= 0)
            s_e, w = edge_band(a_ref, h_top, self.spec)
            if s_e < a_ref / self.spec.n_a:
                in_zone = abs(a - a_ref) <= 0.7 * w
            else:
                in_zone = 0.85 * a_ref <= a <= lm.r_fine / 1.2
            if (in_zone and outside_ok) or remeshes >= self.max_remesh:
                break
            a_ref = a if outside_ok else 1.5 * a_ref
            remeshes += 1
        if not (in_zone and outside_ok):
            raise ConvergenceError(
                f"contact radius {a:.4g} m stayed outside the refined zone after max_remesh={self.max_remesh}"
            )
        p_axis = peak_pressure(r_c, p, a)
        p[r_c <= AXIS_TOL * a] = p_axis
        p0 = max(p_axis, float(p.max()))  # maximum contact pressure (on the axis in all cases seen)
        wall = time.perf_counter() - t0
        meta = {
            "settings": self.settings(),
            "interface": interface if not case.is_stacked else lm.interface,
            "mesh_level": self.mesh,
            "elements": lm.n_elements,
            "dofs": int(model.n_dofs),
            "elements_across_a": float(a / (a_ref / self.spec.n_a)),
            "domain_L": lm.L,
            "solver": solver.name,
            "solver_stats": dict(solver.stats),
            "contact": self.contact,
            "contact_iterations": path.contact_iterations,
            "newton_iterations": path.newton_iterations,
            "load_steps": path.steps,
            "remeshes": remeshes,
            "a_ref": a_ref,
            "mixed_regions": [bool(reg.mixed) for reg in model.regions],
            **({"layers": [{"h": L.h, "interface": f, "elements": len(els)}
                           for L, f, els in zip(layers, lm.interfaces, lm.layers, strict=True)]}
               if case.is_stacked else {}),
            "R_model": eq.R,
            "delta_factor": eq.delta_factor,
            "a_node": radii["a_node"],
            "a_gap": _finite_or_none(radii["a_gap"]),
            "a_pfit": _finite_or_none(radii["a_pfit"]),
            "a_num": radii["a_num"],
            "active_nodes": int(sol.active.sum()),
            "p_axis": p_axis,
            "r_p_max": float(r_c[int(np.argmax(p))]) if p.max() > p_axis else 0.0,
        }
        fields = {"r": r_c, "p": p, "gap": sol.gap, "active": sol.active}
        if self.stresses:
            sfields, smeta = stress_report(model, path.x, a)
            fields.update(sfields)
            meta.update(smeta)
        meta["wall_time"] = time.perf_counter() - t0
        meta["wall_time_solve"] = wall
        res = ContactResult("fem", eq.delta_factor * sol.delta, a, p0, case.W, meta=meta, fields=fields)
        return validity.check(case, res), model, path
