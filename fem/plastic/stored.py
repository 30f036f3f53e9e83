"""Elastic-plastic load paths and onset searches through the result store (resumable runs).

A load path is stored like every other result (:class:`coathertz.store.ResultStore`): under the
case's key, the method name ``PATH_METHOD`` (``fem-plastic``), the hash of its path settings
(:func:`path_settings`: mesh, targets, approach, unloading, tolerance) and the code version. What
is stored is :func:`summarise`: the per-increment curves, the final depths, plastic zone and
interface stress extrema, and the equivalent plastic strain over the r-z section near the
contact (for figures) - JSON, not the model. An elastic onset search
(:func:`~coathertz.fem.plastic.onset.yield_onset`) is stored under ``ONSET_METHOD``
(``fem-onset``) with its yield stresses and elastic mesh as settings.

:func:`run_stored` runs a list of jobs: the stored ones are read back, the others are solved
(in forked processes when ``workers > 1``) and each is written to the store as soon as it has
finished, so that an interrupted study recomputes only the jobs that had not finished. A failed
job is stored as an error (and not retried unless ``retry_errors``) and returned as its message.

The code version that keys the results is the one of every numerical source (the plastic wing
is not a registered method): a change to any solver recomputes the paths.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fem.mesh import MeshSpec

PATH_METHOD = "fem-plastic"
ONSET_METHOD = "fem-onset"


def path_settings(
    mesh: MeshSpec, targets: Sequence[float], delta_max: float, unload_steps: int = 0, rtol: float = 1e-9,
    follow: bool = False,
) -> dict:
    """JSON settings of an approach-controlled path (they key the stored result).

    Parameters
    ----------
    mesh
        The FE mesh (relative to the reference radius sized from ``delta_max``).
    targets
        Approaches [m] of the loading increments, increasing to ``delta_max``.
    delta_max
        Largest approach [m].
    unload_steps
        Equal load steps of the unloading to ``W = 0`` (0: no unloading).
    rtol
        Newton tolerance (relative to the path's largest load).
    follow
        Meshes that follow the contact (``solve_plastic(follow_contact=True)``; ``mesh`` then
        relative to each one's contact radius). Keyed only when set, so that the fixed-mesh paths
        keep their keys.
    """
    if not isinstance(mesh, MeshSpec):
        raise CoatHertzError(f"path_settings: mesh must be a MeshSpec, got {mesh!r}")
    if not (isinstance(unload_steps, int) and 0 <= unload_steps <= 1000):
        raise CoatHertzError(
            f"path_settings: unload_steps must be an integer in [0, 1000], got {unload_steps!r}"
        )
    out = {
        "mesh": asdict(mesh),
        "targets": [float(t) for t in targets],
        "delta_max": float(delta_max),
        "unload_steps": int(unload_steps),
        "rtol": float(rtol),
    }
    if follow:
        out["follow"] = True
    return out


def onset_settings(Yc: float | None, Ys: float | None, n_a: int) -> dict:
    """JSON settings of an elastic onset search (coarse elastic mesh with ``n_a`` elements across a)."""
    return {"Yc": None if Yc is None else float(Yc), "Ys": None if Ys is None else float(Ys), "n_a": int(n_a)}


#: The r-z window of the stored plastic-strain field, in units of the largest contact radius.
ZONE_WINDOW = (3.0, 3.0)


def summarise(res: Any, cpu: float) -> dict:
    """JSON summary of a :class:`~coathertz.fem.plastic.method.PlasticResult` (see module docstring);
    ``cpu``: the CPU seconds the path took."""
    c = {
        k: [v if not isinstance(v, float | np.floating) else float(v) for v in vals]
        for k, vals in res.curves.items()
    }
    a_max = float(np.nanmax(np.r_[0.0, np.array(c["a"], dtype=float)]))
    asm, states = res.assembler, res.state.states
    rq, zq, ep = [], [], []
    for (els, _), st in zip(asm.regions, states, strict=True):
        r, z = asm.rq[els].ravel(), asm.zq[els].ravel()
        e = st["ep"].ravel() if "ep" in st else np.zeros(r.size)
        sel = (r <= ZONE_WINDOW[0] * a_max) & (z >= -ZONE_WINDOW[1] * a_max)
        rq += r[sel].tolist()
        zq += z[sel].tolist()
        ep += e[sel].tolist()
    final: dict = {
        "plastic_zone": res.final["plastic_zone"],
        "residual_depth": res.final.get("residual_depth"),
    }
    for name in ("loaded", "residual"):
        if name in res.final:
            final[name] = {
                "depth": res.final[name]["depth"],
                "stress_extrema": res.final[name]["stress_extrema"],
            }
    meta = {
        k: res.meta[k]
        for k in (
            "elements",
            "dofs",
            "h",
            "a_ref",
            "increments",
            "factorisations",
            "newton_iterations_total",
            "zone_growths",
            "targets",
            "mesh",
            "follow_contact",
            "remeshes",
        )
        if k in res.meta
    }
    meta["cpu"] = cpu
    return {"curves": c, "final": final, "meta": meta, "zone": {"r": rq, "z": zq, "ep": ep}}


def solve_path(case: ContactCase, settings: dict) -> dict:
    """Solve the path of ``settings`` (:func:`path_settings`) and return :func:`summarise`."""
    from coathertz.fem.plastic.method import solve_plastic

    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = solve_plastic(
            case,
            mesh=MeshSpec(**settings["mesh"]),
            n_steps=max(1, settings["unload_steps"]),
            unload=settings["unload_steps"] > 0,
            targets=list(settings["targets"]),
            delta_max=settings["delta_max"],
            rtol=settings["rtol"],
            follow_contact=bool(settings.get("follow", False)),
        )
    return summarise(res, time.process_time() - t0)


def solve_onset(case: ContactCase, settings: dict) -> dict:
    """The elastic onset search of ``settings`` (:func:`onset_settings`) as a JSON dict."""
    from coathertz.fem.method import FEMMethod
    from coathertz.fem.plastic.onset import yield_onset

    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        o = yield_onset(
            case, FEMMethod(mesh="coarse", n_a=settings["n_a"]), Yc=settings["Yc"], Ys=settings["Ys"]
        )
    return {**asdict(o), "p0_over_Y": o.p0_over_Y, "cpu": time.process_time() - t0}


SOLVERS: dict[str, Callable[[ContactCase, dict], dict]] = {PATH_METHOD: solve_path, ONSET_METHOD: solve_onset}


@dataclass(frozen=True)
class Job:
    """One stored computation: ``method`` (``PATH_METHOD`` or ``ONSET_METHOD``) of ``case``."""

    id: str
    case: ContactCase
    method: str
    settings: dict


@dataclass(frozen=True)
class JobsOutcome:
    """Results by job id (a failed job: its error message as a ``str``), and how many were solved
    now and how many read back from the store."""

    results: dict
    computed: int
    reused: int


def _run_one(job: Job) -> dict | str:
    try:
        return SOLVERS[job.method](job.case, job.settings)
    except Exception as exc:  # stored as the job's error, reported by the caller
        return f"{type(exc).__name__}: {exc}"


def run_stored(
    jobs: Sequence[Job], store: Any = None, workers: int = 1, retry_errors: bool = False
) -> JobsOutcome:
    """Run ``jobs``, reusing and filling ``store`` (a :class:`~coathertz.store.ResultStore` or None).

    Every finished job is written to the store at once (in the calling process, the store's one
    writer), so an interrupted run keeps it. ``workers > 1``: the unstored jobs run in up to that
    many forked processes, the longest first as listed.
    """
    for j in jobs:
        if j.method not in SOLVERS:
            raise CoatHertzError(f"job {j.id!r}: method must be one of {sorted(SOLVERS)}, got {j.method!r}")
    results: dict = {}
    todo: list[Job] = []
    for j in jobs:
        sr = store.get(j.case, j.method, j.settings) if store is not None else None
        if sr is not None and (sr.ok or not retry_errors):
            results[j.id] = sr.result if sr.ok else sr.error
        else:
            todo.append(j)
    reused = len(results)

    def keep(j: Job, out: dict | str) -> None:
        results[j.id] = out
        if store is not None:
            if isinstance(out, str):
                store.put(j.case, j.method, j.settings, None, error=out)
            else:
                store.put(j.case, j.method, j.settings, out)

    import multiprocessing

    if workers <= 1 or len(todo) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        for j in todo:
            keep(j, _run_one(j))
    else:
        from concurrent.futures import ProcessPoolExecutor, as_completed

        ctx = multiprocessing.get_context("fork")
        with ProcessPoolExecutor(min(workers, len(todo)), mp_context=ctx) as ex:
            futures = {ex.submit(_run_one, j): j for j in todo}
            for f in as_completed(futures):
                keep(futures[f], f.result())
    return JobsOutcome({j.id: results[j.id] for j in jobs}, len(todo), reused)


def finite(x: Any) -> float:
    """``x`` as a float, NaN for None (a value the store read back as missing)."""
    return math.nan if x is None else float(x)
