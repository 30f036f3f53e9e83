r"""Incremental elastic-plastic contact of a rigid paraboloid: Newton on contact + plasticity.

One semi-smooth Newton loop per increment solves equilibrium, the J2 return mapping at every
quadrature point (:mod:`coathertz.fem.plastic.j2`, B-bar strain of
:mod:`coathertz.fem.plastic.assembly`) and the frictionless contact conditions together
(primal-dual active set, Hintermueller, Ito & Kunisch 2002, as in
:mod:`coathertz.fem.contact`). With the current active set ``A`` and the tangent
``K_t(u_k)`` iteration ``k`` solves for the new total displacement

.. math:: K_t u_{k+1} = K_t u_k - F_{int}(u_k) - B^T\lambda, \qquad
          u_{z,i} = g_0(r_i) - \delta \ (i \in A),\qquad u = \bar u \ \text{(essential dofs)},

``lambda_i >= 0`` the nodal contact forces pushing the body down, with either the load
``sum(lambda) = W`` prescribed (load control, ``delta`` unknown) or the approach ``delta``
prescribed (approach control, ``W`` unknown). The outer boundary carries the Boussinesq field
of the current load (linear in ``W``), so both controls are solved exactly by superposition of
two solves with one factorisation. Then ``A <- {lambda > 0} U {g < 0}``, filled in to a disc
(all candidates inside the outermost contact node: a convex indenter on these bodies makes a
simply connected contact; without this the axis node, whose Q2 area weight is zero, and the
Q2 vertex/mid-side force oscillation at the edge make the set flicker). The increment has
converged when the active set repeats and the out-of-balance force on the free dofs and the
load balance are below ``rtol`` times the path's largest load. History is committed only then.
A full Newton step that raises the residual is shortened (backtracking over
:data:`LINE_SEARCH`; the best shortened step is kept): perfectly plastic points that switch
between elastic and plastic make the full step overshoot, and without it 40 % of the linear
solves of the README's approach path (20 um, 10 + 10 steps) went to failed attempts (0 with it).
The first contact under approach control starts from Hertz's disc ``a^2 = R delta``, not the
rigid penetration's ``2 R delta``. Under load control every later increment starts from the disc
out to the contact front extrapolated from the path's last two converged fronts
(``IncrementalContact._predicted_active``): on the README load path 78 -> 54 Newton iterations,
wall 6.2-7.8 -> 5.1-6.5 s together with the elastic tangent's kept box factors
(:mod:`~coathertz.fem.plastic.condense`; three runs each, alternating, the shared 2-core machine).

Linear solves: the elements away from the contact keep the elastic tangent, so their stiffness is
condensed once on the boundary of a box around the contact and the plastic zone, and each
iteration factorises only that box (:mod:`coathertz.fem.plastic.condense`; exact, rebuilt larger
when the plastic zone or the contact leaves the box, the whole tangent when the box would hold most
of the mesh; ``NewtonSettings(condense=False)`` factorises the whole tangent every iteration).
Measured on the shared 2-core machine (CPU time, both in one run,
``tests/benchmarks/bench_plastic.py --baseline``, default mesh, 28710 unknowns): the README's load
path (``--unload --steps 10``, 78 iterations) 11.4 s against 26.1 s, its approach path with
unloading (20 um, 95 iterations) 15.0 s against 32.6 s; the same loads to 1e-14. Of the 15.7 s
CPU of the approach path: the box factorisations 5.3 s, the solves with the far field's factor and
the box's slicing 3.6 s, the assembly 3.8 s, the condensations 0.9 s (since then the box matrix
is gathered, not sliced, and ``t`` is not solved again within an increment where ``b_e`` changed by
round-off only: the same path 16.0 -> 14.8 s CPU, same run). Then the assembly restricted to the
elements that may yield (:mod:`~coathertz.fem.plastic.assembly`) and the box's factors kept across
the active-set changes of elastic unloading (:mod:`~coathertz.fem.plastic.condense`): the README
load path 13.3 / 10.7 -> 8.2 / 7.4 s CPU (old and new code alternately in one shell, 1 BLAS thread,
the shared machine at load 5-10; with the far field solved once per iteration for the combined
solution and no line search for a step already within the tolerance), delta/delta_c = 200
(E/Y = 1000, 20 steps) 39.9 -> 35.5 s; the same iterations, loads and residual depth. Where the
README load path's 8.3 s CPU go now: the box factorisations 2.6 s (45), the rest of the condensed
solves (far-field solves, gathers) 1.8 s, the assembly 1.45 s (103 calls), the contact-radius fit
0.7 s, the two condensations 0.6 s, the final stress report 0.6 s. Tried and dropped: GMRES on the box
system right-preconditioned with the box's last factorisation (same active set; true residual
1e-12 of the right-hand side, at most 12 iterations, else factorised again): on the README load
path 21 attempts, 10 gave up, 275 preconditioner solves at ~3.4 ms against ~57 ms a factorisation,
CPU 12.7 -> 14.4 s (slower; a perfectly plastic tangent changes at many points between
iterations, so the Krylov space needs about as many solves as a factorisation costs);
starting each increment from the displacement extrapolated from the last (88 -> 92 iterations on
the coarse approach path); its first iteration with the last increment's converged tangent instead
of the committed state's (elastic on the yield surface): coarse mesh, approach path 88 -> 84, load
path 68 -> 69, approach to delta/delta_c = 200 (E/Y = 1000, 20 steps) 185 -> 198.

Increments: every target of the load path is reached by sub-increments; a failed Newton loop
(``max_newton`` iterations, or a diverging residual) halves the sub-increment, a converged one
lets it grow again (x 1.5); after ``max_cutbacks`` consecutive halvings
:class:`~coathertz.errors.ConvergenceError` is raised.
Load ``W = 0`` (full unloading under load control) is solved without contact: the residual
state.
"""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from coathertz.blas import norm2
from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.plastic.assembly import BBarAssembler
from coathertz.fem.plastic.condense import MAX_FRACTION, ElasticCondensation, ElementBoxes, box_for
from coathertz.fem.solvers import nd_lu

#: Complementarity violations below this (relative to the largest multiplier / the approach) are
#: round-off: such an edge node does not change the active set (cf. ``contact.CYCLE_TOL``).
ROUND_OFF = 1e-7
#: An edge node may flip in and out of the active set forever (a cycle), most often at large
#: plastic indentation. A converged state (residual below ``rtol``) whose active set belongs to
#: a cycle is accepted if its complementarity violation (relative, as above) is below this (one
#: edge node penetrating by <= 2 % of the approach, or pulling with <= 2 % of the largest nodal
#: force); the increment records ``cycle = True``.
CYCLE_ACCEPT = 2e-2
#: Load control: a Newton step that changes the approach by more than this fraction of the
#: previous approach is scaled down to it (damped Newton). With few contact nodes and perfectly
#: plastic flow the linearised contact stiffness ``sum(lambda_2)`` can be small, and the undamped
#: step overshoots far into the body. Near convergence steps are small, so the damping is idle
#: and the convergence stays quadratic.
DELTA_DAMP = 0.5
#: Step lengths tried, in order, when a full Newton step raises the residual.
LINE_SEARCH = (0.5, 0.25, 0.125)


@dataclass
class Increment:
    """One converged (sub-)increment."""

    target: float
    W: float
    delta: float
    newton_iterations: int
    residuals: list
    cutbacks: int
    active: np.ndarray
    lam: np.ndarray
    gap: np.ndarray
    cycle: bool = False


@dataclass
class PathState:
    """The committed state: total displacement and history of every region."""

    u: np.ndarray
    states: list
    active: np.ndarray
    delta: float = math.nan  # approach of the committed state (load control damping)


@dataclass
class ContactGeometry:
    """Candidates (``u_z`` dofs, radii, obstacle shape) and essential conditions of a model."""

    cand: np.ndarray
    r: np.ndarray
    g0: np.ndarray
    fixed: np.ndarray
    vals0: np.ndarray  # essential values at W = 0
    vals_unit: np.ndarray  # d(values)/dW (far field of a unit load)
    a_hint: Callable[[float], float] | None = None  # contact radius guess for a load (first contact)
    grid: tuple[np.ndarray, np.ndarray] | None = None  # grid node of every dof (nested-dissection LU)
    condensation: object = None  # the elastic far field's condensation, shared by the paths on this model
    solves: dict = field(default_factory=lambda: {"condensed": 0, "full": 0, "condensations": 0, "reused": 0,
                                                   "elastic": 0, "t_solves": 0, "t_reused": 0})


def geometry_of(model, g0_fun: Callable[[np.ndarray], np.ndarray],
                a_hint: Callable[[float], float] | None = None) -> ContactGeometry:
    """Contact candidates and essential conditions of a :class:`coathertz.fem.model.FEModel`."""
    cand = model.candidates
    r = model.r_dof[cand]
    fixed, v1 = model.dirichlet(1.0)
    fixed0, v0 = model.dirichlet(0.0)
    if not np.array_equal(fixed, fixed0):
        raise CoatHertzError("essential dofs must not depend on the load")
    grid = model.dof_grid() if model.n_dofs == model.n_u else None
    return ContactGeometry(cand, r, g0_fun(r), fixed, v0, v1 - v0, a_hint, grid)


@dataclass
class NewtonSettings:
    """Tolerances and caps of the increment loop."""

    rtol: float = 1e-9
    max_newton: int = 25
    max_cutbacks: int = 8
    grow: float = 1.5
    #: Backtrack a Newton step that raises the residual (:data:`LINE_SEARCH`).
    line_search: bool = True
    #: Condense the elastic far field once and factorise only the box at the contact per
    #: iteration (:mod:`coathertz.fem.plastic.condense`; exact, ``False`` factorises the whole
    #: tangent every time, for comparison).
    condense: bool = True
    #: Load control: start each increment's Newton loop from the active set extrapolated from the
    #: path's last two converged contact fronts (``IncrementalContact._predicted_active``; only
    #: the start changes, ``False`` starts from the committed active set, for comparison).
    predict_active: bool = True

    def __post_init__(self) -> None:
        """One clear error for a setting outside what the loop can use (no silent coercion: a
        truthy string would switch a feature on, a tolerance below the out-of-balance force's
        round-off floor, about 1e-12 of the load, would never be met)."""
        ranges = {"rtol": (1e-13, 1e-3), "max_newton": (1, 200), "max_cutbacks": (0, 30), "grow": (1.0, 4.0)}
        for name, (lo, hi) in ranges.items():
            v = getattr(self, name)
            kind = numbers.Integral if name.startswith("max_") else numbers.Real
            if isinstance(v, bool) or not isinstance(v, kind) or not (lo <= v <= hi):  # NaN fails the range
                what = "an integer" if kind is numbers.Integral else "a number"
                raise CoatHertzError(f"NewtonSettings: {name} must be {what} in [{lo:g}, {hi:g}], got {v!r}")
        for name in ("line_search", "condense", "predict_active"):
            v = getattr(self, name)
            if not isinstance(v, bool):
                raise CoatHertzError(f"NewtonSettings: {name} must be True or False, got {v!r}")


@dataclass
class PathRecord:
    """Everything a load path produced."""

    increments: list[Increment] = field(default_factory=list)
    state: PathState | None = None
    wall_time: float = 0.0
    factorisations: int = 0


def _solve_constrained(K, rhs, fixed, vals_list, grid=None):
    """Solve ``K u = rhs_k`` with ``u[fixed] = vals_k`` for each ``(rhs_k, vals_k)`` (one LU, in the
    nested-dissection order of ``grid`` if given, :func:`coathertz.fem.solvers.nd_lu`; else
    SuperLU's minimum degree)."""
    n = K.shape[0]
    free = np.ones(n, dtype=bool)
    free[fixed] = False
    Kc = K.tocsc()
    Kff = Kc[free][:, free]
    Kfd = Kc[free][:, fixed]
    if grid is not None:
        solve = nd_lu(Kff, (grid[0][free], grid[1][free]))
    else:
        solve = spla.splu(Kff.tocsc(), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True}).solve
    out = []
    for rh, val in zip(rhs, vals_list, strict=True):
        u = np.zeros(n)
        u[fixed] = val
        u[free] = solve(rh[free] - Kfd @ val)
        out.append(u)
    return out


def _combined(cols: list[np.ndarray], combine) -> np.ndarray:
    """``sum_k c_k cols_k`` with ``c = combine(cols)``."""
    c = combine(cols)
    return sum((ck * col for ck, col in zip(c[1:], cols[1:], strict=True)), cols[0] * c[0])


class IncrementalContact:
    """The increment loop (module docstring) for one assembled model.

    Parameters
    ----------
    assembler
        :class:`~coathertz.fem.plastic.assembly.BBarAssembler` of the model.
    geom
        :class:`ContactGeometry` (candidates, obstacle, essential conditions).
    control
        ``"load"`` (targets are loads ``W`` [N]) or ``"approach"`` (targets are ``delta`` [m]).
    force_scale
        Force [N] the residual tolerance refers to (the path's largest load).
    """

    def __init__(self, assembler: BBarAssembler, geom: ContactGeometry, control: str, force_scale: float,
                 settings: NewtonSettings | None = None) -> None:
        if control not in ("load", "approach"):
            raise CoatHertzError(f"control must be 'load' or 'approach', got {control!r}")
        self.asm, self.geom, self.control = assembler, geom, control
        self.scale = float(force_scale)
        self.settings = settings or NewtonSettings()
        self.factorisations = 0
        self._fronts: list[tuple[float, float]] = []  # (target, contact front [m]) of converged states
        self._predict = True  # no failed attempt since the last converged increment

    def initial_state(self) -> PathState:
        states = [law.initial_state(self.asm.w[els].shape) for els, law in self.asm.regions]
        return PathState(np.zeros(self.asm.n), states, np.zeros(len(self.geom.cand), dtype=bool))

    def _solve(self, K, rhs, fixed, vals, active, combine):
        """``sum_k c_k u_k`` with ``K u_k = rhs_k``, ``u_k[fixed] = vals_k`` and ``c = combine(u)``
        (``combine`` reads the solutions on the rows of the active contact dofs only; in the
        condensed solve it gets them before their far field is solved, which is then solved once,
        for the combination): through the elastic far field's condensation where it is exact
        (:mod:`~coathertz.fem.plastic.condense`, rebuilt larger when the plastic zone or the contact
        leaves its box), else one factorisation of the whole tangent."""
        g = self.geom
        nonelastic = getattr(K, "nonelastic", None)
        if not self.settings.condense or g.grid is None or nonelastic is None:
            g.solves["full"] += 1
            return _combined(_solve_constrained(K, rhs, fixed, vals, g.grid), combine)
        A = g.cand[active]
        c = g.condensation
        if c is None or (c is not False and not c.valid(nonelastic, A)):
            c = self._condense(nonelastic, active, None if c is None else c.box)
        if c is False:
            g.solves["full"] += 1
            return _combined(_solve_constrained(K, rhs, fixed, vals, g.grid), combine)
        g.solves["condensed"] += 1
        keys = ("reused", "elastic", "t_solves", "t_reused")
        before = [getattr(c, k) for k in keys]
        out = c.solve(K, rhs, fixed, vals, self.scale, combine)
        for k, b in zip(keys, before, strict=True):
            g.solves[k] += getattr(c, k) - b
        return out

    def _condense(self, nonelastic, active, old):
        """(Re)build the condensation for a box holding the plastic zone and the contact; ``False``
        (stored: no more tries on this model) when the box would hold most of the mesh."""
        g = self.geom
        if not hasattr(self, "_boxes"):
            self._boxes = ElementBoxes.of(self.asm.basis.mesh)
        b = self._boxes
        s0 = float((b.r_max - b.r_min).min())
        r_act = float(g.r[active].max()) if active.any() else 0.0
        r_n, t_n = box_for(b, nonelastic, r_act + 2 * s0, s0, old)
        in_box = (b.r_min < r_n * (1 - 1e-12)) & (b.t_min < t_n * (1 - 1e-12))
        if in_box.mean() > MAX_FRACTION or in_box.all():
            g.condensation = False
            return False
        c = ElasticCondensation(self.asm, g.fixed, g.grid, in_box, (r_n, t_n))
        g.solves["condensations"] += 1
        if not c.valid(nonelastic, g.cand[active]):  # cannot happen: the box holds both (internal check)
            raise CoatHertzError("elastic condensation: the box misses the plastic zone (internal error)")
        g.condensation = c
        return c

    # -- one Newton solve with a fixed active set -------------------------------------------------
    def _linear_step(self, K, rhs, active, target):
        g = self.geom
        A = g.cand[active]
        fixed = np.concatenate([g.fixed, A])
        order = np.argsort(fixed)
        fixed = fixed[order]
        zf = np.zeros(len(g.fixed))
        nA = len(A)
        KA = K[A]  # the contact forces need the active rows only (the same numbers as (K u)[A])
        if self.control == "load":
            W = target
            v1 = np.concatenate([g.vals0 + W * g.vals_unit, g.g0[active]])[order]
            v2 = np.concatenate([zf, -np.ones(nA)])[order]
            out: dict = {}

            def by_load(cols):  # the approach that carries the load W: u = u1 + delta u2
                l1 = rhs[A] - KA @ cols[0]
                l2 = -(KA @ cols[1])
                if nA == 0 or abs(l2.sum()) == 0.0:
                    out.update(delta=math.nan, lam=np.zeros(0))
                    return 1.0, 0.0
                delta = (W - l1.sum()) / l2.sum()
                out.update(delta=delta, lam=l1 + delta * l2)
                return 1.0, delta

            u = self._solve(K, [rhs, np.zeros_like(rhs)], fixed, [v1, v2], active, by_load)
            self.factorisations += 1
            return u, out["delta"], W, out["lam"]
        delta = target
        v1 = np.concatenate([g.vals0, g.g0[active] - delta])[order]
        v3 = np.concatenate([g.vals_unit, np.zeros(nA)])[order]
        out = {}

        def by_approach(cols):  # the load that the far field must carry: u = u1 + W u3
            l1 = rhs[A] - KA @ cols[0]
            l3 = -(KA @ cols[1])
            W = l1.sum() / (1.0 - l3.sum()) if nA else 0.0
            out.update(W=W, lam=l1 + W * l3)
            return 1.0, W

        u = self._solve(K, [rhs, np.zeros_like(rhs)], fixed, [v1, v3], active, by_approach)
        self.factorisations += 1
        return u, delta, out["W"], out["lam"]

    def _update_active(self, active, lam_full, gap, delta):
        """New active set; round-off-level violations at single nodes do not change it."""
        lam_scale = max(float(np.abs(lam_full).max()) if lam_full.size else 0.0, 1e-300)
        drop = active & (lam_full <= 0.0)
        add = ~active & (gap < 0.0)
        gscale = max(abs(delta) if math.isfinite(delta) else 0.0, float(np.abs(self.geom.g0).max()) * 1e-6)
        drop &= lam_full < -ROUND_OFF * lam_scale
        add &= gap < -ROUND_OFF * gscale
        new = (active & ~drop) | add
        if self.control == "load" and not new.any():
            new = self.geom.g0 <= self.geom.g0.min()
        if new.any():  # the contact area is a disc: fill in up to the outermost contact node
            new = np.arange(len(new)) <= np.nonzero(new)[0].max()
        return new

    def _residual(self, u, states, active, W):
        """``(F, K, trial states, contact forces, residual)`` at ``u``: the out-of-balance force on
        the free dofs and (load control) the load balance on the active set, over the force scale."""
        g = self.geom
        F, K, _, trial = self.asm.evaluate(u, states, stresses=False)
        R = F.copy()
        R[g.fixed] = 0.0
        R[g.cand[active]] = 0.0
        lam = -F[g.cand[active]]
        bal = (W - lam.sum()) if self.control == "load" else 0.0
        return F, K, trial, lam, math.hypot(norm2(R), bal) / self.scale

    def _front_of(self, active: np.ndarray) -> float:
        """Radius of the outermost active candidate [m] (0 without contact)."""
        return float(self.geom.r[np.nonzero(active)[0].max()]) if active.any() else 0.0

    def _predicted_active(self, active: np.ndarray, target: float) -> np.ndarray:
        """The first iteration's active set: the disc out to the contact front extrapolated as a
        power of the target, ``a = a_1 (target / t_1)^p`` with ``p`` through the last two
        converged states of this path (:attr:`_fronts`), else the committed ``active`` (fewer
        than two such states with contact, a target or front that is not positive, or a failed
        attempt since the last converged one). Only the start changes: the converged active set
        is still the one that passes the complementarity test (module docstring).

        Load control only (``NewtonSettings.predict_active``). Measured on the default mesh:
        the README load path (10 + 10 steps) 78 -> 54 Newton iterations (unloading 34 -> 15:
        without it each increment spent one iteration per ring of nodes the contact lost), the
        README approach path's load-controlled unloading 27 -> 18; the same loads, approaches and
        residual depth. Under approach control it did not help: loading on the README approach
        path 68 -> 69 iterations, delta/delta_c = 200 (E/Y = 1000) 197 -> 228 (its Newton loops
        are long for the plastic flow, not for the contact, and a larger first active set
        pushed more of the surface at once). A linear extrapolation from the unloaded start
        predicted twice the second increment's radius (Hertz ``a ~ W^(1/3)``), and that
        increment diverged."""
        if len(self._fronts) < 2 or not self._predict:
            return active
        (t0, a0), (t1, a1) = self._fronts[-2:]
        if min(t0, t1, a0, a1, target) <= 0.0 or t1 == t0:
            return active
        a_pred = a1 * (target / t1) ** (math.log(a1 / a0) / math.log(t1 / t0))
        r = self.geom.r
        last = int(np.searchsorted(r, a_pred * (1.0 + 1e-12), side="right")) - 1
        last = min(max(last, 1), len(r) - 1)
        return np.arange(len(r)) <= last

    def solve_increment(self, state: PathState, target: float) -> tuple[PathState, Increment] | None:
        """Newton loop to ``target`` from the committed ``state``; ``None`` if it fails."""
        s = self.settings
        g = self.geom
        no_contact = self.control == "load" and target == 0.0
        active = np.zeros_like(state.active) if no_contact else state.active.copy()
        if not no_contact and not active.any() and self.control == "load":
            a0 = g.a_hint(target) if g.a_hint is not None else 0.0
            active = g.r <= max(a0, g.r[1])
        if self.control == "approach" and not active.any():
            # first contact: Hertz's a^2 = R delta, half the rigid penetration's 2 R delta (the
            # rigid penetration's disc is twice the contact's area and Newton would have to
            # release a ring of nodes at once)
            active = (g.g0 - 0.5 * target - state.u[g.cand]) < 0
        elif s.predict_active and self.control == "load" and not no_contact and active.any():
            active = self._predicted_active(active, target)
        u = state.u.copy()
        F, K, _, _ = self.asm.evaluate(u, state.states, stresses=False)
        residuals = []
        self.last_attempt = {"target": target, "residuals": residuals, "active": []}  # diagnostics
        seen: set[bytes] = set()
        delta_prev = state.delta
        for it in range(1, s.max_newton + 1):
            rhs = K @ u - F
            u_new, delta, W, lam = self._linear_step(K, rhs, active, target)
            if (self.control == "load" and math.isfinite(delta_prev) and delta_prev > 0
                    and math.isfinite(delta) and abs(delta - delta_prev) > DELTA_DAMP * delta_prev):
                step = DELTA_DAMP * delta_prev / abs(delta - delta_prev)
                u_new = u + step * (u_new - u)
                delta = delta_prev + step * (delta - delta_prev)
            delta_prev = delta
            lam_full = np.zeros(len(g.cand))
            lam_full[active] = lam
            if self.control == "load" and not no_contact:
                gap = g.g0 - delta - u_new[g.cand]
            elif self.control == "approach":
                gap = g.g0 - target - u_new[g.cand]
            else:
                gap = np.full(len(g.cand), np.inf)
            new_active = active if no_contact else self._update_active(active, lam_full, gap, delta)

            F, K, trial, lam_eq, res = self._residual(u_new, state.states, active, W)
            if s.line_search and residuals and res > residuals[-1] and res > s.rtol:
                # backtracking: the full step raised the out-of-balance force (perfectly plastic
                # points switching between elastic and plastic overshoot); keep the best of the
                # shortened steps if it is better. The active set update stays the full step's.
                # Not for a step already within the tolerance: its out-of-balance force is
                # round-off (elastic unloading while the active set shrinks: 1e-12 of the load, up
                # and down), and a shortened step would only undo part of the active-set change.
                du = u_new - u
                for alpha in LINE_SEARCH:
                    out_a = self._residual(u + alpha * du, state.states, active, W)
                    if out_a[-1] < res:
                        F, K, trial, lam_eq, res = out_a
                        u_new = u + alpha * du
                        if res < residuals[-1]:
                            break
            u = u_new
            residuals.append(res)
            self.last_attempt["active"].append(int(active.sum()))
            if not np.isfinite(res) or (it > 8 and res > 1e2):  # out-of-balance >> the load: diverging
                return None
            same = np.array_equal(new_active, active)
            cycle = False
            if not same and res <= s.rtol and new_active.tobytes() in seen:
                lam_scale = max(float(np.abs(lam_eq).max()) if lam_eq.size else 0.0, 1e-300)
                v_lam = max(0.0, -float(lam_eq.min())) / lam_scale if lam_eq.size else 0.0
                gin = gap[~active]
                v_gap = max(0.0, -float(gin.min())) / max(abs(delta), 1e-300) if gin.size else 0.0
                cycle = max(v_lam, v_gap) < CYCLE_ACCEPT
            if (same or cycle) and res <= s.rtol:
                lam_out = np.zeros(len(g.cand))
                lam_out[active] = lam_eq
                W_out = float(lam_eq.sum()) if self.control == "approach" else W
                inc = Increment(target, W_out, delta, it, residuals, 0, active.copy(), lam_out, gap, cycle)
                return PathState(u, trial, active.copy(), delta), inc
            seen.add(active.tobytes())
            active = new_active
        return None

    def run(self, targets: Sequence[float], state: PathState | None = None, start: float = 0.0,
            progress: Callable[[Increment, PathState, int], None] | None = None) -> PathRecord:
        """Follow ``targets`` (loads or approaches) from ``start`` with adaptive sub-increments;
        ``progress(increment, state, target_index)`` is called after each converged one."""
        t0 = time.perf_counter()
        s = self.settings
        state = state or self.initial_state()
        rec = PathRecord()
        current = float(start)
        if not self._fronts or self._fronts[-1][0] != current:  # a path that does not continue the last one
            self._fronts = [(current, self._front_of(state.active))]
        for k, tgt in enumerate(targets):
            tgt = float(tgt)
            step = tgt - current
            cut = 0
            while True:
                nxt = tgt if abs(tgt - current) <= abs(step) * (1 + 1e-12) else current + step
                out = self.solve_increment(state, nxt)
                if out is None:
                    self._predict = False  # the retry starts from the committed active set
                    cut += 1
                    if cut > s.max_cutbacks:
                        raise ConvergenceError(
                            f"increment to {self.control} {nxt:.6g} failed after {s.max_cutbacks} cutbacks "
                            f"(from {current:.6g}; max_newton = {s.max_newton})")
                    step *= 0.5
                    continue
                state, inc = out
                self._fronts = [*self._fronts[-1:], (nxt, self._front_of(state.active))]
                self._predict = True
                inc.cutbacks = cut
                cut = 0  # max_cutbacks counts consecutive failures
                rec.increments.append(inc)
                if progress is not None:
                    progress(inc, state, k)
                current = nxt
                if nxt == tgt:
                    break
                if inc.newton_iterations <= 6:
                    step = math.copysign(min(abs(step) * s.grow, abs(tgt - current)), tgt - current)
        rec.state = state
        rec.wall_time = time.perf_counter() - t0
        rec.factorisations = self.factorisations
        return rec
