"""Run a study: which methods run which cases (from the registry), the arbiter, the tables.

:func:`build_methods` instantiates the registered methods at a study resolution
(``settings_for``). :func:`run_study` gives every case to every method that supports it and
whose cost the case's tier admits (plus the study's own variants), runs the (case, method)
pairs through :func:`coathertz.runner.run_tasks` (reusing stored results), picks each case's
reference (the top-ranked method that solved it), and builds the rows, the errors of the
closed form against the reference, the cross-checks of the other methods, and the per-case
uncertainty; then calls the module's ``analyse``.
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

from coathertz.errors import CoatHertzError
from coathertz.methods import admits, get_method, method_info, method_names, reference_for, settings_for
from coathertz.store import ResultStore, case_key

from .study import CLOSED, StudyResult, check_resolution
from .tables import QUANTITIES, crosscheck, make_errors, make_rows, uncertainty_by_case

__all__ = ["build_methods", "plan", "run_study", "study_tasks", "variants_of"]


def build_methods(resolution: str, names: Sequence[str] | None = None) -> tuple[dict[str, Any], list[str]]:
    """Instances of the requested registered methods (default: all) at ``resolution``, and notes on
    those that could not be built (a method whose package is missing or broken is reported, not
    fatal)."""
    check_resolution(resolution)
    available = method_names()
    wanted = list(names) if names else available
    unknown = [n for n in wanted if n not in available]
    if unknown:
        raise CoatHertzError(f"unknown method(s) {unknown}; choose from {available}")
    methods, notes = {}, []
    for n in wanted:
        try:
            methods[n] = get_method(n, **settings_for(n, resolution))
        except Exception as exc:
            notes.append(f"method {n!r} unavailable: {type(exc).__name__}: {exc}")
    return methods, notes


def variants_of(module, methods: Mapping[str, Any], resolution: str) -> tuple[dict[str, Any], list[str]]:
    """Instances of the study's ``VARIANTS`` (name -> (registered method, extra settings)) whose
    base method is in ``methods``: the built base instance with the extra settings replaced
    (``dataclasses.replace``), so a variant has exactly its base's settings otherwise (the
    resolution was turned into settings once, by :func:`build_methods`); a base that is not a
    dataclass is built again from ``resolution``."""
    out, notes = {}, []
    for v, (base, extra) in getattr(module, "VARIANTS", {}).items():
        if base not in methods:
            continue
        inst = methods[base]
        try:
            out[v] = (dataclasses.replace(inst, **extra) if dataclasses.is_dataclass(inst)
                      else get_method(base, **{**settings_for(base, resolution), **extra}))
        except Exception as exc:
            notes.append(f"variant {v!r} unavailable: {type(exc).__name__}: {exc}")
    return out, notes


def plan(cases: Sequence[Any], methods: Mapping[str, Any], variants: Mapping[str, Any]
         ) -> tuple[list[tuple[Any, str, Any]], dict[str, dict[str, str]]]:
    """The (study case, method name, instance) pairs to run, and why each registered method
    does not run a case (``{case id: {method: reason}}``)."""
    todo, absent = [], {}
    for sc in cases:
        for name, m in methods.items():
            info = method_info(name)
            if not m.supports(sc.case):
                absent.setdefault(sc.id, {})[name] = "does not support this configuration"
            elif sc.tier == "none" or not admits(sc.tier, info.cost):
                absent.setdefault(sc.id, {})[name] = (f"{info.cost} method, run on the study's chosen subset "
                                                      "only")
            else:
                todo.append((sc, name, m))
        for v in sorted(sc.variants):
            if v in variants and variants[v].supports(sc.case):
                todo.append((sc, v, variants[v]))
    return todo, absent


def study_tasks(module, resolution: str, methods: Mapping[str, Any]) -> list:
    """The (case, method) tasks :func:`run_study` gives the runner for ``module``: its cases, then
    its reference refinements as they will be asked for if every reference solve succeeds (they
    are chosen from the results): what a run may start ahead while the study before it is
    analysed (``run_tasks(..., ahead=...)``). A refinement predicted wrongly is solved and
    stored for nothing; the study asks for its own."""
    from coathertz.runner import Task

    variants, _ = variants_of(module, methods, resolution)
    cases = module.cases(resolution)
    todo, _ = plan(cases, methods, variants)
    numerical = _numerical(module, methods)
    ran: dict[str, list[str]] = {}
    for sc, name, _ in todo:
        if name in numerical:
            ran.setdefault(sc.id, []).append(name)
    reference = {sc.id: ref for sc in cases
                 if (ref := reference_for(sc.case, ran.get(sc.id, []))) is not None}
    return ([Task(sc.case, m) for sc, _, m in todo]
            + [Task(sc.case, m) for sc, _, m in _refine_todo(cases, reference, resolution)])


def _numerical(module, methods: Mapping[str, Any]) -> list[str]:
    """The registered methods that may serve as a case's reference in ``module`` (not the
    closed form it judges)."""
    predicted = getattr(module, "PREDICTED", CLOSED)
    return [n for n in methods if method_info(n).reference_rank > 0 and n != predicted]


#: Suffix of the rows of a reference solved again at refined settings (convergence estimate).
REFINED = "-refined"


def _refine_todo(cases: Sequence[Any], reference: Mapping[str, str], resolution: str) -> list:
    """(study case, reference name, refined instance) of the cases marked ``refine`` whose
    reference (``reference``: case id -> method name) has ``refined_settings``."""
    from coathertz.methods import method_class

    todo = []
    for sc in cases:
        ref = reference.get(sc.id)
        if not sc.refine or ref is None:
            continue
        fn = getattr(method_class(ref), "refined_settings", None)
        settings = fn(resolution) if fn is not None else None
        if settings is None:
            continue
        todo.append((sc, ref, get_method(ref, **settings)))
    return todo


def _refine(cases: Sequence[Any], reference: Mapping[str, str], resolution: str, store: ResultStore,
            opts: Mapping[str, Any]) -> tuple[dict[str, dict[str, dict]], int, int]:
    """Solve the cases marked ``refine`` with their reference at its ``refined_settings``;
    ``{case id: {"<method>-refined": result}}``, and how many were computed and reused."""
    from coathertz.runner import Task, run_tasks

    todo = _refine_todo(cases, reference, resolution)
    if not todo:
        return {}, 0, 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        outcome = run_tasks([Task(sc.case, m) for sc, _, m in todo], store, **opts)
    out: dict[str, dict[str, dict]] = {}
    for sc, ref, m in todo:
        sr = outcome.get(sc.case, m)
        if sr is not None and sr.ok:
            out[sc.id] = {f"{ref}{REFINED}": sr.result}
    return out, outcome.computed + outcome.failed, outcome.reused


def run_study(module, resolution: str, methods: Mapping[str, Any], store: ResultStore,
              runner_options: Mapping[str, Any] | None = None) -> StudyResult:
    """Build, run and analyse one study module with the given (registered) method instances."""
    from coathertz.runner import Task, run_tasks

    check_resolution(resolution)
    t0 = time.perf_counter()
    cases = module.cases(resolution)
    variants, vnotes = variants_of(module, methods, resolution)
    todo, absent = plan(cases, methods, variants)
    opts = dict(runner_options or {})
    opts.setdefault("desc", module.NAME)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        outcome = run_tasks([Task(sc.case, m) for sc, _, m in todo], store, **opts)
    records: dict[str, dict[str, dict]] = {}
    failures = []
    for sc, name, m in todo:
        sr = outcome.get(sc.case, m)
        if sr is None:
            continue
        if sr.ok:
            records.setdefault(sc.id, {})[name] = sr.result
        else:
            failures.append({"case": sc.id, **sc.params, "method": name, "error": sr.error})
            absent.setdefault(sc.id, {})[name] = f"failed: {str(sr.error).splitlines()[0][:160]}"
    result = StudyResult(module.NAME, module.TITLE, module.CLAIM, resolution,
                         methods=sorted({n for _, n, _ in todo}))
    result.rows = make_rows(cases, records)
    predicted = getattr(module, "PREDICTED", CLOSED)
    quantities = getattr(module, "QUANTITIES", QUANTITIES)
    numerical = _numerical(module, methods)
    byid = {sc.id: sc for sc in cases}
    for cid, ms in records.items():
        ref = reference_for(byid[cid].case, [n for n in ms if n in numerical])
        if ref is not None:
            result.reference[cid] = ref
    result.errors = make_errors(result.rows, result.reference, quantities, predicted)
    result.crosscheck = crosscheck(result.rows, result.reference, numerical, quantities)
    refined, n_new, n_old = _refine(cases, result.reference, resolution, store, opts)
    if refined:
        rows = result.rows + make_rows(cases, refined)
        finer = {f"{r}{REFINED}" for r in result.reference.values()}
        result.crosscheck += [d for d in crosscheck(rows, result.reference, finer, quantities)
                              if d["method"] in finer]
        result.extra["refined"] = {cid: next(iter(v)) for cid, v in refined.items()}
    result.uncertainty = uncertainty_by_case(result.crosscheck)
    result.failures = failures
    result.computed, result.reused = outcome.computed + outcome.failed, outcome.reused
    result.computed += n_new
    result.reused += n_old
    result.method_time = dict(outcome.method_time)
    n_cases = len(cases)
    for name in methods:
        n_run = sum(1 for sc, n, _ in todo if n == name)
        if n_run < n_cases:
            reasons: dict[str, int] = {}
            for sc in cases:
                why = absent.get(sc.id, {}).get(name)
                if why:
                    reasons[why] = reasons.get(why, 0) + 1
            result.skipped[name] = f"runs {n_run} of {n_cases} cases; " + "; ".join(
                f"not on {v}: {k}" for k, v in sorted(reasons.items(), key=lambda kv: -kv[1]))
    result.extra["notes"] = vnotes
    result.extra["absent"] = absent
    result.extra["cases"] = {sc.id: {"params": dict(sc.params), "case_key": case_key(sc.case),
                                     "describe": sc.case.describe(), "tier": sc.tier} for sc in cases}
    result.workers = 1 if opts.get("scheduler") else max(1, int(opts.get("workers", 1)))
    # the run's store, for studies that solve in ``analyse`` and store their own results (not a
    # dataclass field: it stays out of ``to_json``)
    result.store = store  # type: ignore[attr-defined]
    module.analyse(result)
    result.wall_time = time.perf_counter() - t0
    return result
