"""The DC-FFT method: :class:`FFTMethod` (a :class:`coathertz.methods.Method`) and batch sweeps.

``FFTMethod(n=128).solve(case)`` builds the grid from the Hertz estimate
(:mod:`coathertz.fft.grid`), the cell influence coefficients of both bodies from their FRFs
(:mod:`coathertz.fft.influence`; compliances add), solves the contact by Polonsky & Keer's CG
with load control (:mod:`coathertz.fft.solver`) and measures it
(:mod:`coathertz.fft.estimators`).

A solve without a warm start begins from the solution on the grid with cells twice as large
(recursively, ``nested``; :func:`prolong_pressure`), and CG is preconditioned by the inverse
of the kernel (:meth:`~coathertz.fft.solver.Convolver.precondition`). The contact radius is the
sub-cell closing
of the gap outside the contact (:func:`~coathertz.fft.estimators.gap_fit_axes`); the paper's
``sqrt(S/pi)`` stays in ``meta["a_num"]``. A coating thinner than a cell is resolved by
solving the case again with finer cells on the same domain (``layer_cells``,
``meta["layer_refinement"]``).

For sweeps use :meth:`FFTMethod.solve_many` (or ``solve_many``): cases sharing a grid (in the
fig-3 study every ``H`` of one modulus ratio does: the grid depends only on ``a0s`` and ``a0c``)
are solved as one batch with stacked arrays, and the coefficient transforms are cached per
``(body, grid, interface)``.
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
import warnings
from collections import OrderedDict
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np

from coathertz.case import ContactCase
from coathertz.closedform.hertz import pressure_elliptical
from coathertz.errors import CoatHertzError
from coathertz.fft import estimators
from coathertz.fft.frf import INTERFACES
from coathertz.fft.grid import (
    DEFAULT_MARGIN,
    DEFAULT_N,
    N_MAX,
    REFIT_BELOW,
    RESOLVE_BELOW,
    Grid,
    check_n,
    fast_n,
    grid_for_axes,
)
from coathertz.fft.influence import body_coefficients, circulant
from coathertz.fft.solver import (
    Convolver,
    default_workers,
    get_backend,
    polonsky_keer,
)
from coathertz.materials import Body
from coathertz.methods import require_case
from coathertz.results import ContactResult

_CACHE: OrderedDict = OrderedDict()
_CACHE_SIZE = 64
INIT_SCALE = 0.8
#: Nested start: grids with at least this many cells per side start from the solution on the
#: grid with cells twice as large, solved to ``NESTED_TOL``. With the kernel-inverse
#: preconditioner, over the 30 cases of the benchmark set (tests/benchmarks/bench_fft.py
#: ``--family``) the largest count of transform pairs at n = 128 / 512 was 47.8 / 42.6 for
#: 3e-4, 40.8 / 41.6 for 1e-3, 40.4 / 51.0 for 2e-3, 36.6 / 42.2 for 3e-3, 38.9 / 52.9 for
#: 5e-3 and 41.4 / 63.9 for 1e-2 (medians 20-22 / 23-25): the worst case is sensitive to it.
NESTED_MIN_N = 64
NESTED_TOL = 3e-3
#: The sub-cell radius needs the thinnest coating to span this many cells. Below, the
#: coating's edge boundary layer (width ~h) lies inside the cell next to the edge, and no fit
#: of the grid solution recovers it. Measured against the exact axisymmetric method at
#: n = 128 over E = 1/4-4 and h/a0s = 0.01-0.03, bonded and frictionless (tests/fft/
#: test_radius.py): max |error in a| 0.067 % with h >= 1 cell, but up to +0.169 % below
#: (stiff coatings: bonded E = 4, h = 0.64 cells; frictionless E = 3, h = 0.51 cells: +0.160 %);
#: at n = 256, where h >= 1 cell in all of them, 0.037 %. ``FFTMethod(layer_cells=...)``
#: therefore refines such cases by default; a result left below says so (warning,
#: ``meta["accuracy"]``).
LAYER_CELLS_MIN = 1.0
#: Memory of one solve [bytes]: ``MEMORY_BASE + MEMORY_PER_CELL * nx * ny * batch``. Measured
#: (peak resident set over the interpreter's, one FFT thread, B4C and fig-10 ellipse cases):
#: 423-428 bytes per cell at n = 256, 374-377 at 512, 360-361 at 1024; 5.5 GB at n = 4096
#: (328 per cell) was reported. The estimate takes the largest with a margin.
MEMORY_PER_CELL = 450
#: Bytes of a solve independent of the grid (the interpreter, numpy, scipy).
MEMORY_BASE = 100 * 2**20
#: A coating more than ``STIFF_CONTRAST`` times stiffer than its substrate (Ec*/Es*; outside
#: the paper's range) needs ``STIFF_FACTOR`` times as many cells. Measured at n = 128, bonded
#: and frictionless, H = 0.01-0.05: with one cell max |error in a| 0.063 % at E = 6 but
#: 0.19 % at E = 10 (H = 0.02, 1.02 cells); with 1.5 cells 0.046 % at E = 10.
STIFF_CONTRAST = 4.0
STIFF_FACTOR = 1.5
#: Bound on |error in a| quoted where a coating stays thinner than the cells it needs (the
#: refinement could not be afforded, or was switched off, or the caller gave the grid).
#: Measured against the exact method at n = 128 with ``layer_cells=None`` over E = 1/4, 1/2, 2,
#: 4, 10 and H = 5e-4 ... 0.012 (0.025-0.61 cells), bonded and frictionless (70 cases): largest
#: 0.209 % for E <= 4 (frictionless E = 4, 0.25 cells; 0.17 % was quoted before and did not
#: hold) and 0.680 % at E = 10 (bonded, 0.41 cells). The bounds are about 1.5 times those.
#: Stiffer coatings than E = 10 were not measured, and the note says so.
SUB_CELL_RADIUS_ERROR = 0.003
SUB_CELL_RADIUS_ERROR_STIFF = 0.010
#: The modulus ratios Ec*/Es* between which the bounds above were measured.
SUB_CELL_MEASURED_E_MIN, SUB_CELL_MEASURED_E_MAX = 0.25, 10.0
#: Coarse levels with at least this many cells per side are preconditioned too (it saved up
#: to a fifth of the pairs at n = 512 and cost 2-10 % at n = 128, where the coarse levels are
#: 64 and 32).
PRECONDITION_COARSE_MIN_N = 128


#: Cells whose pressure is below this fraction of the peak do not count in the contact extent
#: (and axes) that decide the re-gridding (``FFTMethod._refit``): the decision is discrete
#: (one cell more or less), and an edge cell at round-off level (a change of kernel
#: coefficients by 1e-16 moves the pressures by up to ~1e-6 of the peak through the iteration,
#: tolerance 1e-6) flipped it once (a moved by 1.9e-4). 1e-4 leaves a margin of 100 over that;
#: a Hertzian edge cell falls below it only within 5e-9 a of the edge.
DECISION_FLOOR = 1e-4


def settled_contact(p: np.ndarray) -> np.ndarray:
    """``p`` with the cells below :data:`DECISION_FLOOR` of its peak set to 0 (the contact the
    re-gridding decisions look at; results use ``p`` itself)."""
    top = float(np.max(p)) if p.size else 0.0
    return np.where(p >= DECISION_FLOOR * top, p, 0.0) if top > 0 else p


def coefficients(body: Body, grid: Grid, interface: str = "bonded") -> np.ndarray:
    """Quadrant coefficients of one body on ``grid``, cached per (body, grid, interface)."""
    key = (body, grid.key(), interface)
    if key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    K = body_coefficients(body, grid.nx, grid.ny, grid.dx, grid.dy, interface)
    _CACHE[key] = K
    if len(_CACHE) > _CACHE_SIZE:
        _CACHE.popitem(last=False)
    return K


def case_quadrant(case: ContactCase, grid: Grid, interface: str = "bonded") -> np.ndarray:
    """Quadrant coefficients of the pair (offsets ``0..n``): the bodies' compliances add."""
    return coefficients(case.body1, grid, interface) + coefficients(case.body2, grid, interface)


def case_coefficients(case: ContactCase, grid: Grid, interface: str = "bonded") -> np.ndarray:
    """Wrap-around (``2ny x 2nx``) coefficients of the pair: the bodies' compliances add."""
    return circulant(case_quadrant(case, grid, interface))


def initial_gap(case: ContactCase, grid: Grid) -> np.ndarray:
    """``g0 = x^2/(2 Rx) + y^2/(2 Ry)`` (principal relative radii, x along Rx)."""
    gx = 0.0 if math.isinf(case.Rx) else grid.x**2 / (2 * case.Rx)
    gy = 0.0 if math.isinf(case.Ry) else grid.y**2 / (2 * case.Ry)
    return np.zeros(grid.shape) + gx + np.asarray(gy)[:, None] * np.ones((1, grid.nx))


def estimate_axes(case: ContactCase) -> tuple[float, float]:
    """Larger of the Hertz semi-axes with coatings removed and as half-spaces [m]."""
    cands = [case.hertz_s, case.hertz_c]
    ra = max(float(h.r_a0) for h in cands if float(h.r_a0) > 0)
    rb = max(float(h.r_b0) for h in cands if float(h.r_b0) > 0)
    return ra, rb


@dataclass(frozen=True)
class FFTMethod:
    """DC-FFT contact solver for coated bodies (the paper's numerical method).

    Parameters
    ----------
    n
        Resolution knob: cells along each side of the domain (``16 <= n <= 4096``).
    margin
        Domain half-width over the estimated semi-axis (> 1).
    spacing_ratio
        ``dy/dx``; ``None``: ``r_b/r_a`` (square cells for circles). The paper's ellipses: 1/3.
    interface
        ``bonded`` (eq 13, the paper's model) or ``frictionless`` (layer resting on its
        substrate without friction; transfer-matrix FRF).
    tol, max_iter
        CG tolerance on ``sum |dp| dA / W`` (P&K's measure) and iteration cap. At the default
        1e-6 the results differ from those at 1e-12 by < 1.3e-9 in delta and < 1.4e-8 in p0
        (preconditioned; measured on four coated cases at n = 128), far below the
        discretisation error.
    precondition
        CG direction preconditioned by the inverse of the kernel
        (:func:`~coathertz.fft.solver.polonsky_keer`; default ``True``): iterations flat in
        ``n``; half the transform pairs of plain CG on half-space-like kernels, about as many
        on thin layers over a rigid base.
    nested
        Start a solve without a warm start from the solution on the grid with cells twice
        as large (``n >= 64``): about 20 % fewer transform-pair equivalents in all.
    adapt
        Re-grid on the computed contact when it fills less than ``REFIT_BELOW`` of the
        estimate or touches the margin (see :mod:`coathertz.fft.grid`), so that the radius
        gets the nominal ``n / (2 margin)`` cells. The contact of the nested start's coarse
        solve decides it before the fine solve (or, in a sweep with warm starts, the previous
        case's contact); the fine solve is repeated only when the fine contact disagrees.
    radius
        Estimator reported as ``a``: ``edge-fit`` (default, sub-cell) or ``area`` (the paper's
        ``sqrt(S/pi)``, ``meta["a_num"]``); both are always in ``meta``. The edge fit is the
        closing of the gap outside the contact for coated bodies and ellipses
        (:func:`~coathertz.fft.estimators.gap_fit_axes`) and the wide-band fit of ``p^2``
        (exact for Hertz, :func:`~coathertz.fft.estimators.edge_fit_axes`) for circular
        contacts of uncoated bodies (or bonded coatings identical to their substrates);
        ``meta["radius_estimator"]`` names the one used (``area`` where the fit failed).
    layer_cells
        Cells the thinnest coating must span for the sub-cell radius (default
        ``LAYER_CELLS_MIN = 1``; ``STIFF_FACTOR = 1.5`` times that for a coating more than
        ``STIFF_CONTRAST = 4`` times stiffer than its substrate; ``None``: off). Where it
        spans fewer, the case is solved again
        on the same domain with the ``n`` that gives it that many (rounded up to a fast
        transform length, :func:`~coathertz.fft.grid.fast_n`; as far as ``max_memory_gb``
        allows, from the grid solution prolonged), and ``meta["layer_refinement"]`` records it:
        below a cell the coating's edge boundary layer lies inside one cell and no fit of the
        grid solution recovers ``a`` to 0.1 % (see :data:`LAYER_CELLS_MIN`). Where even that
        ``n`` is not enough, or the caller gave the grid, the result carries a warning and
        ``meta["accuracy"]``.
    max_memory_gb
        Memory one solve may take [GiB] (default: a quarter of the physical memory, at most
        4 GiB). A grid whose estimated memory (:func:`estimate_memory`) exceeds it is refused
        before anything is allocated; the thin-coating refinement goes as far as it allows.
    backend, workers
        ``numpy`` or ``cupy``; ``workers`` FFT threads (``None``: by grid size, see
        :func:`~coathertz.fft.solver.default_workers`: 1 up to n = 256 and in the worker
        processes of a sweep, all cores above). With one thread the CG iteration runs in
        buffers allocated once per solve (no grid-size allocation per iteration).
    keep_fields
        Return the pressure and displacement arrays in ``ContactResult.fields``.
    """

    # method metadata (coathertz.methods.Method): class variables, not dataclass fields
    cost: ClassVar[str] = "moderate"
    marker: ClassVar[str] = "o"
    label: ClassVar[str] = "DC-FFT"
    reference_rank: ClassVar[int] = 20
    source_packages: ClassVar[tuple[str, ...]] = ("coathertz.fft",)

    @classmethod
    def settings_for(cls, resolution: str) -> dict[str, Any]:
        """The paper's 128 x 128 grid (32 at ``tiny``); one FFT thread (the runner supplies
        the parallelism), no fields kept."""
        tiny = resolution == "tiny"
        return {"n": 32 if tiny else 128, "keep_fields": False, "workers": 1,
                **({"layer_cells": None} if tiny else {})}

    @classmethod
    def refined_settings(cls, resolution: str) -> dict[str, Any]:
        """Twice the grid (convergence estimate of a study's reference)."""
        return {**cls.settings_for(resolution), "n": 2 * cls.settings_for(resolution)["n"]}


    n: int = DEFAULT_N
    margin: float = DEFAULT_MARGIN
    spacing_ratio: float | None = None
    interface: str = "bonded"
    tol: float = 1e-6
    max_iter: int = 2000
    precondition: bool = True
    nested: bool = True
    adapt: bool = True
    radius: str = "edge-fit"
    backend: str = "numpy"
    workers: int | None = None
    keep_fields: bool = True
    layer_cells: float | None = LAYER_CELLS_MIN
    max_memory_gb: float | None = None
    name: str = "fft"

    def __post_init__(self) -> None:
        check_n(self.n)
        if self.interface not in INTERFACES:
            raise CoatHertzError(f"interface must be one of {INTERFACES}, got {self.interface!r}")
        if self.radius not in ("edge-fit", "area"):
            raise CoatHertzError(f"radius must be 'edge-fit' or 'area', got {self.radius!r}")
        if not isinstance(self.precondition, bool):
            raise CoatHertzError(f"precondition must be True or False, got {self.precondition!r}")
        if not (isinstance(self.tol, float | int) and 0 < self.tol < 1e-2):
            raise CoatHertzError(f"tol must satisfy 0 < tol < 1e-2, got {self.tol!r}")
        lc = self.layer_cells
        if lc is not None and not (isinstance(lc, float | int) and not isinstance(lc, bool)
                                   and 0.1 <= lc <= 8.0):
            raise CoatHertzError(f"layer_cells must be None or a number in [0.1, 8], got {lc!r}")
        mm = self.max_memory_gb
        if mm is not None and not (isinstance(mm, float | int) and not isinstance(mm, bool)
                                   and 0 < mm < math.inf):
            raise CoatHertzError(f"max_memory_gb must be None or satisfy 0 < max_memory_gb < inf, got {mm!r}")
        get_backend(self.backend, self.fft_workers())

    def memory_budget(self) -> float:
        """Memory one solve may take [bytes]: ``max_memory_gb``, or by default a quarter of the
        physical memory and at most 4 GiB (:func:`default_max_memory_gb`)."""
        return (default_max_memory_gb() if self.max_memory_gb is None else self.max_memory_gb) * 2**30

    def check_memory(self, nx: int, ny: int, batch: int = 1) -> None:
        """Refuse, before anything is allocated, a solve whose estimated memory
        (:func:`estimate_memory`) exceeds :meth:`memory_budget`."""
        need, limit = estimate_memory(nx, ny, batch), self.memory_budget()
        if need <= limit:
            return
        fitting = [n for n in range(16, N_MAX + 1, 16) if estimate_memory(n, n, batch) <= limit]
        smaller = f"a smaller grid (--grid {fitting[-1]} fits)" if fitting else "a smaller grid"
        per = f" in batches of {batch}" if batch > 1 else ""
        raise CoatHertzError(
            f"fft: a {nx} x {ny} grid{per} needs about {need / 2**30:.3g} GiB (estimate), more than "
            f"the limit max_memory_gb = {limit / 2**30:.3g} GiB; use {smaller}, or a larger "
            "max_memory_gb (--max-memory) if the machine has the memory")

    def fft_workers(self) -> int:
        """FFT threads used (``workers``, or the default for ``n``)."""
        return default_workers(self.n) if self.workers is None else self.workers

    # Method protocol ------------------------------------------------------------------
    def settings(self) -> Mapping[str, Any]:
        # the fields' values directly (all plain numbers and strings): ``asdict`` deep-copies
        # each one, and a run asks for the settings of each result several times
        skip = ("name", "backend", "workers", "keep_fields", "max_memory_gb")
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in skip}

    def supports(self, case: ContactCase) -> bool:
        """Any point contact: finite relative radii (a non-conforming contact)."""
        return math.isfinite(case.Rx) and math.isfinite(case.Ry)

    def grid_for(self, case: ContactCase, axes: tuple[float, float] | None = None) -> Grid:
        ra, rb = estimate_axes(case) if axes is None else axes
        return grid_for_axes(ra, rb, self.n, self.margin, self.spacing_ratio)

    def solve(self, case: ContactCase, grid: Grid | None = None) -> ContactResult:
        """Solve one case (re-gridding if ``adapt``); raises ConvergenceError on failure."""
        return self.solve_many([require_case(case, self.name)], grid=grid)[0]

    def solve_many(
        self,
        cases: Sequence[ContactCase],
        grid: Grid | None = None,
        batch: int = 1,
        warm_start: bool = True,
    ) -> list[ContactResult]:
        """Solve many cases efficiently.

        Cases are grouped by grid (cases whose Hertz estimates coincide share one, e.g. all
        ``H`` of one modulus ratio). Within a group, ``batch = 1`` solves them in the given
        order, each starting from the previous pressure field (``warm_start``: order a sweep by
        ``H``); ``batch > 1`` stacks that many cases into one array problem (pays off on a GPU,
        not on 2 CPU cores). Coefficients are cached per (body, grid, interface).
        """
        if not (isinstance(batch, int) and batch >= 1):
            raise CoatHertzError(f"batch must be an integer >= 1, got {batch!r}")
        for c in cases:
            if not self.supports(c):
                raise CoatHertzError("FFT method needs a point contact (finite Rx and Ry)")
        grids = [grid or self.grid_for(c) for c in cases]
        for g in {(g.nx, g.ny) for g in grids}:
            self.check_memory(*g, min(batch, len(cases)))
        adaptive = self.adapt and grid is None
        groups: dict[tuple, list[int]] = {}
        for i, g in enumerate(grids):
            groups.setdefault(g.key(), []).append(i)
        out: list[ContactResult | None] = [None] * len(cases)
        for idx in groups.values():
            prev: tuple[ContactResult, Grid] | None = None
            for s in range(0, len(idx), batch):
                chunk = idx[s : s + batch]
                g = grids[chunk[0]]
                p_start = None
                if prev is not None:
                    # warm start from the previous case; with ``adapt``, on the grid its contact
                    # asked for (a sweep along H changes the contact little from case to case)
                    r_prev, g_prev = prev
                    if adaptive:
                        g = self._refit(r_prev.meta["extent"], (r_prev.r_a, r_prev.r_b), g) or g
                    p_start = r_prev.fields["pressure"]
                    if g != g_prev:
                        p_start = prolong_pressure(p_start, g_prev, g)
                res = self._solve_batch(
                    [cases[i] for i in chunk], g, p_start, probe=adaptive and batch == 1
                )
                if adaptive:
                    res = [self._adapt(cases[i], r) for i, r in zip(chunk, res, strict=True)]
                if warm_start and batch == 1:  # the next case starts on this grid, not a refined one
                    prev = (res[0], Grid(**res[0].meta["grid"]))
                if grid is None:  # a grid given by the caller is kept (and flagged if too coarse)
                    res = [self._resolve_layer(cases[i], r) for i, r in zip(chunk, res, strict=True)]
                for i, r in zip(chunk, res, strict=True):
                    self._resolution_note(cases[i], r)
                for i, r in zip(chunk, res, strict=True):
                    out[i] = r if self.keep_fields else dataclasses.replace(r, fields={})
        return out  # type: ignore[return-value]

    def _adapt(self, case: ContactCase, r: ContactResult) -> ContactResult:
        """Re-solve on the grid the computed contact asks for (at most 4 times), see
        :mod:`coathertz.fft.grid`; the pairs spent on grids given up are counted in meta."""
        g = Grid(**r.meta["grid"])
        spent = 0.0
        for _ in range(4):
            new = self._refit(r.meta["extent"], (r.r_a, r.r_b), g, RESOLVE_BELOW)
            if new is None:
                break
            spent += r.meta["pair_equivalents_total"]
            g = new
            r = self._solve_batch([case], g)[0]
        if spent > 0:
            r.meta["pair_equivalents_total"] += spent
            r.meta["regridded"] = True
        return r

    def _resolve_layer(self, case: ContactCase, r: ContactResult) -> ContactResult:
        """``r``, or the case solved again on a grid on which its thinnest coating spans
        ``layer_cells`` cells (same domain, finer cells; see the ``layer_cells`` parameter). The
        finer ``n`` is the next one whose transforms are fast (:func:`~coathertz.fft.grid.fast_n`),
        where the memory budget allows."""
        if self.layer_cells is None or r.meta["radius_estimator"] != "gap-fit":
            return r
        g = Grid(**r.meta["grid"])
        cells, need, n_fine = _layer_resolution(case, g, self.layer_cells)
        if cells >= need:
            return r
        if n_fine > N_MAX or estimate_memory(n_fine, n_fine) > self.memory_budget():
            return r  # left to the note
        fast = fast_n(n_fine)  # a few more cells, on transform lengths that run fast
        if fast <= N_MAX and estimate_memory(fast, fast) <= self.memory_budget():
            n_fine = fast
        dx = g.half_widths[0] / (n_fine // 2 - 0.5)
        fine = Grid(n_fine, n_fine, dx, dx * g.dy / g.dx)
        p_start = prolong_pressure(r.fields["pressure"], g, fine)
        finer = dataclasses.replace(self, n=n_fine, layer_cells=None)
        rf = finer._solve_batch([case], fine, p_start)[0]
        # the cost in transform pairs of the fine grid: one on the requested grid is about
        # (n / n_fine)^2 of one there
        rf.meta["pair_equivalents_total"] += r.meta["pair_equivalents_total"] * (self.n / n_fine) ** 2
        rf.meta["regridded"] = bool(r.meta["regridded"])
        rf.meta["wall_time"] += r.meta["wall_time"]
        rf.meta["layer_refinement"] = {
            "n_requested": self.n, "n": n_fine, "layer_cells_before": cells,
            "a_before": r.a, "r_a_before": r.r_a, "r_b_before": r.r_b,
        }
        return rf

    def _resolution_note(self, case: ContactCase, r: ContactResult) -> None:
        """Record ``meta["layer_cells"]`` (thinnest coating over the cell size) and, where the
        coating spans fewer cells than it needs (:func:`_layer_resolution`) and the radius is
        the sub-cell fit, warn and say in ``meta["accuracy"]`` how far ``a`` can be off (see
        :data:`LAYER_CELLS_MIN`)."""
        grid = Grid(**r.meta["grid"])
        cells, need, n_need = _layer_resolution(case, grid, LAYER_CELLS_MIN)
        r.meta["layer_cells"] = cells if math.isfinite(cells) else None
        if cells >= need or r.meta["radius_estimator"] != "gap-fit":
            return
        bound = _sub_cell_bound(case)
        budget = self.memory_budget()
        why = ""
        if n_need > N_MAX or estimate_memory(n_need, n_need) > budget:
            need_gib = estimate_memory(n_need, n_need) / 2**30
            why = (f"; refining to n = {n_need} would need about {need_gib:.2g} GiB, beyond "
                   f"max_memory_gb = {budget / 2**30:.3g}"
                   + (f" (and n = {n_need} is beyond {N_MAX})" if n_need > N_MAX else ""))
        msg = (f"the coating is {cells:.2g} cells thick (h = {cells * max(grid.dx, grid.dy):.4g} m, cell "
               f"{max(grid.dx, grid.dy):.4g} m), fewer than the {need:g} its edge boundary layer "
               f"needs: the sub-cell radius can be off by up to {bound}; "
               f"n >= {n_need} resolves it{why} (delta and p0 are not affected)")
        warnings.warn(msg, UserWarning, stacklevel=3)
        r.meta["accuracy"] = msg

    # internals ------------------------------------------------------------------------
    def _refit(
        self,
        extent: Sequence[float],
        axes: tuple[float, float],
        g: Grid,
        below: float = REFIT_BELOW,
    ) -> Grid | None:
        """The grid for a contact of ``extent`` (half-widths of its cells) and semi-axes
        ``axes`` found on ``g``, or ``None`` when ``g`` suits it: the contact neither comes
        within two cells of the boundary nor fills less than ``below`` of the estimate (see
        :mod:`coathertz.fft.grid`)."""
        ext_x, ext_y = extent
        hx, hy = g.half_widths
        touching = ext_x > hx - 2 * g.dx or ext_y > hy - 2 * g.dy
        small = max(ext_x / hx, ext_y / hy) < below / self.margin
        if not (touching or small):
            return None
        if touching:
            ra, rb = 1.5 * max(axes[0], ext_x), 1.5 * max(axes[1], ext_y)
        else:  # on the computed contact, leaving at least 3 cells outside its extent
            room = self.margin * (1.0 - 3.0 / (self.n / 2 - 0.5))
            ra = max(axes[0], ext_x / room)
            rb = max(axes[1], ext_y / room)
        ratio = self.spacing_ratio if self.spacing_ratio is not None else g.dy / g.dx
        return grid_for_axes(ra, rb, self.n, self.margin, ratio)

    def _coarse_start(self, cases: list[ContactCase], grid: Grid, be) -> tuple[list, float]:
        """Initial pressures from the same problems on the grid with cells twice as large.

        The coarse solve (tolerance ``NESTED_TOL``) costs a quarter per transform and saves
        a third of the fine iterations (measured at n = 128-512; see the module docstring).
        Applied recursively down to ``NESTED_MIN_N``. Returns the prolonged pressures and
        the cost of the coarse solves in transform pairs of ``grid``.
        """
        coarse = Grid(grid.nx // 2, grid.ny // 2, 2 * grid.dx, 2 * grid.dy)
        kern = np.stack([case_quadrant(c, coarse, c.interface_for(self.interface)) for c in cases])
        g0 = np.stack([initial_gap(c, coarse) for c in cases])
        if min(coarse.nx, coarse.ny) >= NESTED_MIN_N:  # nested in turn
            p0, cost = self._coarse_start(cases, coarse, be)
        else:
            X, Y = np.meshgrid(coarse.x, coarse.y)
            p0, cost = [], 0.0
            for c in cases:
                ra, rb = estimate_axes(c)
                p0.append(pressure_elliptical(X, Y, INIT_SCALE * ra, INIT_SCALE * rb, 1.0))
        sol = polonsky_keer(
            Convolver.from_quadrant(kern, be), g0, np.array([c.W for c in cases]), coarse.cell_area,
            tol=NESTED_TOL, max_iter=self.max_iter, p_init=np.stack(p0),
            precondition=self.precondition and min(coarse.nx, coarse.ny) >= PRECONDITION_COARSE_MIN_N,
            symmetric=True,
        )
        cost = (sol.convolutions + cost) / 4
        return [prolong_pressure(sol.p[k], coarse, grid) for k in range(len(cases))], cost

    def _solve_batch(
        self,
        cases: list[ContactCase],
        grid: Grid,
        p_prev: np.ndarray | None = None,
        probe: bool = False,
    ) -> list[ContactResult]:
        """Solve ``cases`` on ``grid``, from ``p_prev`` or the nested coarse start.

        ``probe`` (one case): when the coarse start's contact asks for another grid
        (:meth:`_refit`), move there before the fine solve, so that the re-gridding costs a
        coarse solve rather than a fine one; the coarse cost is counted in
        ``meta["pair_equivalents_total"]``.
        """
        t0 = time.perf_counter()
        be = get_backend(self.backend, self.fft_workers())
        probe_cost, moved = 0.0, False
        nested = p_prev is None and self.nested and min(grid.nx, grid.ny) >= NESTED_MIN_N
        probe = probe and nested and len(cases) == 1
        if probe:
            p_c, cost = self._coarse_start(cases, grid, be)
            p_d = settled_contact(p_c[0])
            if np.any(p_d > 0):
                ext = estimators.contact_extent(p_d, grid)
                new = self._refit(ext, estimators.moment_axes(p_d, grid), grid)
                if new is not None:  # start from the probe, interpolated to the new grid
                    p_c = [prolong_pressure(p_c[0], grid, new)]
                    probe_cost, moved, grid = cost, True, new
        kern = np.stack([case_quadrant(c, grid, c.interface_for(self.interface)) for c in cases])
        g0 = np.stack([initial_gap(c, grid) for c in cases])
        W = np.array([c.W for c in cases])
        X, Y = np.meshgrid(grid.x, grid.y)
        p_init = []
        for c in cases:
            ra, rb = estimate_axes(c)
            if p_prev is not None:
                p_init.append(p_prev)
            else:
                p_init.append(pressure_elliptical(X, Y, INIT_SCALE * ra, INIT_SCALE * rb, 1.0))
        nested_conv = 0.0
        if probe:  # the probe was the coarse start (on this grid, or moved to it)
            p_init, nested_conv = p_c, (0.0 if moved else cost)
        elif nested:
            p_init, nested_conv = self._coarse_start(cases, grid, be)
        t1 = time.perf_counter()
        conv = Convolver.from_quadrant(kern, be)
        pre = bool(self.precondition)
        sol = polonsky_keer(
            conv, g0, W, grid.cell_area, tol=self.tol, max_iter=self.max_iter,
            p_init=np.stack(p_init), precondition=pre, symmetric=True,
        )
        t_setup = t1 - t0
        per_case = (time.perf_counter() - t0) / len(cases)
        results = []
        for k, c in enumerate(cases):
            p = sol.p[k]
            a_num = estimators.area_radius(p, grid)
            ra_m, rb_m = estimators.moment_axes(p, grid)
            circular = c.is_circular and self.spacing_ratio in (None, 1.0)
            if circular:
                ra_m = rb_m = a_num
            # a coating of its substrate's material is the homogeneous body only when bonded:
            # a frictionless interface slips even then (p is not Hertzian; the p^2 fit missed
            # a by -0.18 % at E = 1, H = 0.01, and did not converge with n)
            hertzian = all(
                (b.coating is None and not b.is_stacked)
                or (b.coating is not None and b.coating.material == b.material
                    and c.interface_for(self.interface) == "bonded")
                for b in (c.body1, c.body2)
            )
            if not (hertzian and circular):
                gap = sol.u[k] + g0[k] - sol.delta[k]
                fit = estimators.gap_fit_axes(p, gap, grid, ra_m, rb_m, circular=circular)
                fit_name = "gap-fit"
            else:  # circular Hertz (also a coating identical to its substrate): p^2 is exactly
                # linear in r^2, a wide band averages the collocation scatter best
                fit = estimators.edge_fit_axes(p, grid, ra_m, rb_m)
                fit_name = "pressure-fit"
            ra_f, rb_f = fit if fit is not None else (ra_m, rb_m)
            ext_x, ext_y = estimators.contact_extent(settled_contact(p), grid)  # drives re-gridding
            use_fit = self.radius == "edge-fit" and fit is not None
            ra, rb = (ra_f, rb_f) if use_fit else (ra_m, rb_m)
            i0 = np.unravel_index(int(np.argmax(p)), p.shape)
            meta = {
                "grid": grid.describe(),
                "iterations": int(sol.iterations[k]),
                "eps": float(sol.eps[k]),
                "residual": float(sol.residual[k]),
                "penetration": float(sol.penetration[k]),
                "convolutions_batch": int(sol.convolutions),
                "coarse_pair_equivalents_batch": float(nested_conv),
                # transform pairs of this solve per case (coarse levels weighted by their size)
                # and with the solves on grids given up by the re-gridding (``adapt``)
                "pair_equivalents": (sol.convolutions + nested_conv) / len(cases),
                "pair_equivalents_total": (sol.convolutions + nested_conv) / len(cases)
                + probe_cost,
                "regridded": moved,
                "preconditioned": bool(pre),
                "batch": len(cases),
                "wall_time": per_case,
                "setup_time_batch": t_setup,
                "a_num": a_num,
                "area": estimators.contact_area(p, grid),
                "r_a_num": ra_m,
                "r_b_num": rb_m,
                "a_fit": math.sqrt(ra_f * rb_f),
                "r_a_fit": ra_f,
                "r_b_fit": rb_f,
                "radius_estimator": fit_name if use_fit else "area",
                "radius_fit_failed": fit is None,
                "r_p0": float(math.hypot(grid.x[i0[1]], grid.y[i0[0]])),
                "extent": [ext_x, ext_y],
                "interface": c.interface_for(self.interface),
                "settings": dict(self.settings()),
            }
            fields = {"pressure": p, "displacement": sol.u[k], "x": grid.x, "y": grid.y}
            results.append(
                ContactResult(
                    self.name,
                    float(sol.delta[k]),
                    math.sqrt(ra * rb),
                    estimators.peak_pressure(p),
                    c.W,
                    ra,
                    rb,
                    meta,
                    fields,
                )
            )
        return results


def _sub_cell_bound(case: ContactCase) -> str:
    """The bound on the radius error of a coating thinner than its cells, as the note quotes it
    (:data:`SUB_CELL_RADIUS_ERROR`): by the stiffest coating's modulus ratio; unmeasured on a
    rigid substrate and above :data:`SUB_CELL_MEASURED_E_MAX`."""
    coated = case.coated_bodies
    if case.is_stacked or not coated:
        return "an unmeasured amount (measured for single coatings, not for layer stacks)"
    if any(b.material.is_rigid for b in coated):
        return "an unmeasured amount (not measured on a rigid substrate)"
    E = max(b.modulus_ratio for b in coated)
    if E < SUB_CELL_MEASURED_E_MIN:
        return f"an unmeasured amount (measured for Ec*/Es* >= {SUB_CELL_MEASURED_E_MIN:g}; here {E:.3g})"
    if E > SUB_CELL_MEASURED_E_MAX:
        return (f"an unmeasured amount (measured up to Ec*/Es* = {SUB_CELL_MEASURED_E_MAX:g}, where it "
                f"stayed within {SUB_CELL_RADIUS_ERROR_STIFF:.1%}; here Ec*/Es* = {E:.3g})")
    if E > STIFF_CONTRAST:
        return f"{SUB_CELL_RADIUS_ERROR_STIFF:.1%} (1.5 x the largest measured, Ec*/Es* 4-10)"
    return f"{SUB_CELL_RADIUS_ERROR:.1%} (1.5 x the largest measured, Ec*/Es* 1/4-4)"


def estimate_memory(nx: int, ny: int, batch: int = 1) -> float:
    """Estimated peak memory [bytes] of one solve on an ``nx`` x ``ny`` grid (``batch`` cases
    stacked): :data:`MEMORY_BASE` plus :data:`MEMORY_PER_CELL` per cell and case."""
    return MEMORY_BASE + MEMORY_PER_CELL * nx * ny * batch


def default_max_memory_gb() -> float:
    """A quarter of the physical memory, at most 4 GiB: the default memory budget of one FFT
    solve (an automatic refinement stays within it too)."""
    try:
        phys = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):
        phys = 16.0
    return min(4.0, 0.25 * phys)


def _layer_resolution(case: ContactCase, grid: Grid, base: float) -> tuple[float, float, int]:
    """``(cells, need, n)`` for the thinnest coating of the pair: the cells it spans on
    ``grid`` (the larger cell side; ``inf`` without coatings), the cells it needs (``base``,
    times ``STIFF_FACTOR`` for a coating more than ``STIFF_CONTRAST`` times stiffer than its
    elastic substrate) and the even ``n`` that gives it those on the same domain (the cell
    shrinks like ``1 / (n/2 - 1/2)``)."""
    # (h, material, material below) of each coating, or of a stack's top layer (the
    # edge boundary layer has the width of the top layer; buried layers act at longer waves)
    layers = []
    for b in (case.body1, case.body2):
        if b.coating is not None and b.coating.h > 0:
            layers.append((b.coating.h, b.coating.material, b.material))
        if b.layers:
            below = b.layers[1].material if len(b.layers) > 1 else b.material
            layers.append((b.layers[0].h, b.layers[0].material, below))
    if not layers:
        return math.inf, base, grid.nx
    h, coat, sub = min(layers, key=lambda x: x[0])
    cells = h / max(grid.dx, grid.dy)
    stiff = not sub.is_rigid and coat.E_star > STIFF_CONTRAST * sub.E_star
    need = base * STIFF_FACTOR if stiff else base
    return cells, need, 2 * math.ceil((grid.nx / 2 - 0.5) * need / cells + 0.5)


#: Round-off margin of the contact indicator's midline in :func:`prolong_pressure` (the
#: bilinear weights carry ~1e-16 of round-off; the indicator's values are multiples of 1/4).
PROLONG_TIE = 1e-9


def prolong_pressure(pc: np.ndarray, coarse: Grid, fine: Grid) -> np.ndarray:
    """A coarse contact pressure on ``fine``: :func:`prolong`, cut to the contact.

    Bilinear interpolation spreads pressure half a coarse cell beyond the coarse contact set;
    the prolonged pressure is set to zero where the interpolated contact indicator is below
    1/2, i.e. outside the midline between the last contact and the first free coarse cell
    centres (the coarse set's best estimate of the edge). The fine iteration then starts with
    the contact set within about a fine cell of its own (measured: frictionless E = 4,
    H = 0.1 at n = 128, 8128 cells at the start for 7661 at the end without the cut, 7757
    with it) and changes it less.
    """
    pf = prolong(pc, coarse, fine)
    chi = prolong((pc > 0).astype(float), coarse, fine)
    # a fine cell on the midline (chi = 1/2 exactly) is kept: a plain ``chi < 0.5`` left the
    # tie to the round-off of the weights, which differs between mirror images (an even start
    # came out uneven by a fifth of its peak)
    pf[chi < 0.5 - PROLONG_TIE] = 0.0
    return pf


def prolong(pc: np.ndarray, coarse: Grid, fine: Grid) -> np.ndarray:
    """Bilinear interpolation of a cell field from ``coarse`` to ``fine`` (same origin)."""

    def weights(xf: np.ndarray, xc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.clip((xf - xc[0]) / (xc[1] - xc[0]), 0.0, len(xc) - 1.0)
        i0 = np.minimum(t.astype(int), len(xc) - 2)
        return i0, t - i0

    ix, wx = weights(fine.x, coarse.x)
    iy, wy = weights(fine.y, coarse.y)
    rows = pc[:, ix] * (1 - wx) + pc[:, ix + 1] * wx
    return rows[iy, :] * (1 - wy)[:, None] + rows[iy + 1, :] * wy[:, None]
