"""The study framework shared by every module of :mod:`coathertz.verification`.

A study module defines

``NAME``, ``TITLE``
    Registry name (``coathertz verify --study NAME``) and a one-line title.
``CLAIM``
    The paper's claim the study checks, in words (the module docstring gives the details).
``cases(resolution) -> list[StudyCase]``
    The cases at resolution ``tiny`` (tests), ``quick`` (CI, the README main job) or ``full``
    (the paper's grids), each with the set of methods that should run it.
``analyse(result) -> None``
    Fills ``result.claims`` (and ``result.extra``) from ``result.rows`` and ``result.errors``.
``plot(result, outdir) -> list[Path]``
    Writes its figures (PNG and SVG) and returns their paths.

:func:`run_study` builds the cases, runs every (case, method) pair through
:func:`coathertz.runner.run_tasks` (reusing stored results), assembles tidy rows (one per case
and method, with the paper's bars) and error rows (closed form against each numerical
method), then calls the module's ``analyse``.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.hertz import hertz_circular
from coathertz.materials import RIGID, Body, Coating, Material
from coathertz.store import ResultStore, case_key

RESOLUTIONS = ("tiny", "quick", "full")
CLOSED = "closed-form"
NUMERICAL = ("fft", "fem")
ALL = frozenset({CLOSED, *NUMERICAL})
CF_FFT = frozenset({CLOSED, "fft"})
QUANTITIES = ("a", "p", "delta")
#: Result field of each quantity.
FIELD = {"a": "a", "p": "p0", "delta": "delta", "r_a": "r_a", "r_b": "r_b"}
SYMBOL = {"a": r"$\bar a$", "p": r"$\bar p$", "delta": r"$\bar\delta$",
          "r_a": r"$\bar r_a$", "r_b": r"$\bar r_b$"}
MARKERS = {"fft": "o", "fem": "s"}

# --- the paper's standard configuration -----------------------------------------------------
R_SPHERE = 10e-3  # [m]
W_LOAD = 1.0  # [N]
E_SUBSTRATE = 200e9  # [Pa]
NU = 0.3


def check_resolution(resolution: str) -> str:
    if resolution not in RESOLUTIONS:
        raise CoatHertzError(f"resolution must be one of {RESOLUTIONS}, got {resolution!r}")
    return resolution


def h_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """``n`` values of H, geometric from ``lo`` to ``hi`` (the paper does not state its spacing;
    geometric spacing resolves the thin-coating end, where the curves change fastest)."""
    return np.round(np.geomspace(lo, hi, n), 6)


def nearest(values, targets) -> set[float]:
    """The members of ``values`` nearest (in log) to each target, rounded to 9 digits: FE runs on
    grid points, so the grids keep the paper's sizes."""
    v = np.asarray(values, dtype=float)
    return {round(float(v[np.argmin(np.abs(np.log(v / t)))]), 9) for t in targets}


def fig3_ratios() -> list[float]:
    """The 25 modulus ratios of figure 3: 1/E = 4 - (i-1)/4, i = 1..12; E = 1 + i/4, i = 0..12."""
    return [1.0 / (4.0 - (i - 1) / 4.0) for i in range(1, 13)] + [1.0 + i / 4.0 for i in range(13)]


def elastic_case(E: float, H: float, nu_c: float = NU, nu_s: float = NU, label: str = "") -> ContactCase:
    """Rigid sphere on a coated elastic half-space with ``Ec*/Es* = E`` and ``h = H a0s``."""
    sub = Material(E_SUBSTRATE, nu_s)
    Ec = E * sub.E_star * (1.0 - nu_c**2)
    coat = Material(Ec, nu_c)
    a0s = float(hertz_circular(W_LOAD, R_SPHERE, sub.E_star).a0)  # eq (1a), rigid sphere
    return ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, coat, H * a0s, sub, label=label)


def rigid_substrate_case(Ec: float, H: float, nu_c: float = NU, label: str = "") -> ContactCase:
    """Rigid sphere on a coating of modulus ``Ec`` bonded to a rigid substrate, ``h = H a0c``."""
    coat = Material(Ec, nu_c)
    h = H * float(hertz_circular(W_LOAD, R_SPHERE, coat.E_star).a0)  # a0c, eq (1a)
    return ContactCase(Body.rigid_sphere(R_SPHERE), Body.half_space(RIGID, Coating(coat, h)), W_LOAD,
                       label=label)


@dataclass(frozen=True)
class StudyCase:
    """One case of a study: its id, the case, its parameters and the methods that run it."""

    id: str
    case: ContactCase
    params: Mapping[str, Any]
    methods: frozenset[str] = CF_FFT


@dataclass(frozen=True)
class Claim:
    """A checked statement: the number we measure against the paper's bound.

    ``holds`` is None where the paper states no bound (an observation) or nothing could be
    computed. ``tol`` is the regression tolerance on ``value`` (same unit).
    """

    id: str
    text: str
    value: float
    bound: str = ""
    holds: bool | None = None
    unit: str = "%"
    tol: float = 0.05
    detail: str = ""

    @property
    def verdict(self) -> str:
        if self.holds is None:
            return "n/a" if not math.isfinite(self.value) else "observed"
        return "holds" if self.holds else "does not hold"


@dataclass
class StudyResult:
    """Everything a study produced: tidy rows, error rows, claims and run information."""

    name: str
    title: str
    claim: str
    resolution: str
    rows: list[dict] = field(default_factory=list)
    errors: list[dict] = field(default_factory=list)
    claims: list[Claim] = field(default_factory=list)
    extra: dict = field(default_factory=dict)
    methods: list[str] = field(default_factory=list)
    failures: list[dict] = field(default_factory=list)
    wall_time: float = 0.0
    computed: int = 0
    reused: int = 0
    method_time: dict = field(default_factory=dict)

    def rows_of(self, method: str) -> list[dict]:
        return [r for r in self.rows if r["method"] == method]

    def to_json(self) -> dict:
        d = asdict(self)
        d["claims"] = [{**asdict(c), "verdict": c.verdict} for c in self.claims]
        return d


# --- rows ----------------------------------------------------------------------------------
def bars(case: ContactCase, res: Mapping[str, Any]) -> dict[str, float]:
    """The paper's bars of a result: ratios to the eq (7) normalisers of the case."""
    n = case.normalisers
    return {
        "a_bar": res["a"] / n.a0,
        "p_bar": res["p0"] / n.p0,
        "delta_bar": res["delta"] / n.delta0,
        "r_a_bar": res["r_a"] / n.r_a0,
        "r_b_bar": res["r_b"] / n.r_b0,
    }


def make_rows(cases: Sequence[StudyCase], records: Mapping[str, Mapping[str, Mapping]]) -> list[dict]:
    """One tidy row per (case, method) that produced a result."""
    rows = []
    for sc in cases:
        for m, res in records.get(sc.id, {}).items():
            if res.get("error"):
                continue
            row = {"case": sc.id, **sc.params, "method": m,
                   **{k: res[k] for k in ("delta", "a", "p0", "r_a", "r_b")}, **bars(sc.case, res)}
            meta = res.get("meta", {})
            if "a_num" in meta:
                row["a_num"] = meta["a_num"]
            if "wall_time" in meta:
                row["wall_time"] = meta["wall_time"]
            rows.append(row)
    return rows


def make_errors(rows: Sequence[dict], quantities: Sequence[str] = QUANTITIES,
                predicted: str = CLOSED) -> list[dict]:
    """Error rows: ``err = (predicted - numerical)/numerical`` in percent (the paper's definition)."""
    by_case: dict[str, dict[str, dict]] = {}
    for r in rows:
        by_case.setdefault(r["case"], {})[r["method"]] = r
    out = []
    for cid, ms in by_case.items():
        if predicted not in ms:
            continue
        pred = ms[predicted]
        params = {k: v for k, v in pred.items() if k not in _RESULT_KEYS}
        for ref, num in ms.items():
            if ref == predicted:
                continue
            for q in quantities:
                f = FIELD[q]
                out.append({**params, "case": cid, "reference": ref, "quantity": q,
                            "predicted": pred[f], "numerical": num[f],
                            "err": 100.0 * (pred[f] / num[f] - 1.0)})
    return out


_RESULT_KEYS = {"method", "delta", "a", "p0", "r_a", "r_b", "a_bar", "p_bar", "delta_bar", "r_a_bar",
                "r_b_bar", "a_num", "wall_time"}


def pairwise(rows: Sequence[dict], quantities: Sequence[str] = QUANTITIES) -> list[dict]:
    """Pairwise differences (percent of the second method) of every two methods on each case."""
    by_case: dict[str, dict[str, dict]] = {}
    for r in rows:
        by_case.setdefault(r["case"], {})[r["method"]] = r
    out = []
    for cid, ms in by_case.items():
        names = sorted(ms)
        for i, m1 in enumerate(names):
            for m2 in names[i + 1 :]:
                for q in quantities:
                    f = FIELD[q]
                    params = {k: v for k, v in ms[m1].items() if k not in _RESULT_KEYS}
                    out.append({**params, "case": cid, "pair": f"{m1} vs {m2}", "quantity": q,
                                "diff": 100.0 * (ms[m1][f] / ms[m2][f] - 1.0)})
    return out


def pairwise_summary(rows: Sequence[dict], quantities: Sequence[str] = QUANTITIES) -> list[dict]:
    """Max |difference| and count per (pair, quantity)."""
    out: dict[tuple[str, str], list[float]] = {}
    for d in pairwise(rows, quantities):
        out.setdefault((d["pair"], d["quantity"]), []).append(d["diff"])
    return [{"pair": p, "quantity": q, "n": len(v), "max_abs": float(np.max(np.abs(v))),
             "mean": float(np.mean(v))} for (p, q), v in sorted(out.items())]


def max_abs(errors: Iterable[dict], reference: str, quantities: Sequence[str] = QUANTITIES,
            where=None) -> tuple[float, int, dict | None]:
    """Largest |err| against ``reference`` (and the row where it occurs), and the count."""
    sel = [e for e in errors if e["reference"] == reference and e["quantity"] in quantities
           and (where is None or where(e))]
    if not sel:
        return math.nan, 0, None
    worst = max(sel, key=lambda e: abs(e["err"]))
    return abs(worst["err"]), len({e["case"] for e in sel}), worst


def bound_claim(cid: str, text: str, errors: Sequence[dict], reference: str, bound: float,
                quantities: Sequence[str] = QUANTITIES, where=None, tol: float = 0.05) -> Claim:
    """Claim ``max |err| < bound`` against one numerical reference."""
    value, n, worst = max_abs(errors, reference, quantities, where)
    detail = ""
    if worst is not None:
        keys = [k for k in ("E", "H", "nu_c", "Ec_GPa") if k in worst]
        detail = (f"{n} cases; worst: {worst['quantity']} at "
                  + ", ".join(f"{k} = {worst[k]:.4g}" for k in keys) + f" ({worst['err']:+.2f} %)")
    holds = None if n == 0 else bool(value < bound)
    return Claim(f"{cid}-{reference}", f"{text} against {reference.upper()}", value,
                 f"< {bound:g} %", holds, "%", tol, detail or "method not run")


# --- running -------------------------------------------------------------------------------
def run_study(module, resolution: str, methods: Mapping[str, Any], store: ResultStore,
              runner_options: Mapping[str, Any] | None = None) -> StudyResult:
    """Build, run and analyse one study module with the given method instances."""
    from coathertz.runner import Task, run_tasks

    check_resolution(resolution)
    t0 = time.perf_counter()
    cases = module.cases(resolution)
    tasks, wanted = [], {}
    for sc in cases:
        for name in sorted(sc.methods):
            m = methods.get(name)
            if m is not None and m.supports(sc.case):
                tasks.append(Task(sc.case, m))
                wanted.setdefault(sc.id, []).append(name)
    opts = dict(runner_options or {})
    opts.setdefault("desc", module.NAME)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        outcome = run_tasks(tasks, store, **opts)
    records: dict[str, dict[str, dict]] = {}
    failures = []
    for sc in cases:
        for name in wanted.get(sc.id, []):
            sr = outcome.get(sc.case, methods[name])
            if sr is None:
                continue
            if sr.ok:
                records.setdefault(sc.id, {})[name] = sr.result
            else:
                failures.append({"case": sc.id, **sc.params, "method": name, "error": sr.error})
    result = StudyResult(module.NAME, module.TITLE, module.CLAIM, resolution,
                         methods=sorted({n for ns in wanted.values() for n in ns}))
    result.rows = make_rows(cases, records)
    result.errors = make_errors(result.rows, getattr(module, "QUANTITIES", QUANTITIES))
    result.failures = failures
    result.computed, result.reused = outcome.computed + outcome.failed, outcome.reused
    result.method_time = dict(outcome.method_time)
    result.extra["cases"] = {sc.id: {"params": dict(sc.params), "case_key": case_key(sc.case),
                                     "describe": sc.case.describe()} for sc in cases}
    module.analyse(result)
    result.wall_time = time.perf_counter() - t0
    return result


# --- plotting helpers ----------------------------------------------------------------------
def save(fig, outdir: str | Path, name: str) -> list[Path]:
    """Save ``fig`` as PNG (150 dpi) and SVG in ``outdir``; close it."""
    import matplotlib.pyplot as plt

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = []
    for ext in ("png", "svg"):
        p = outdir / f"{name}.{ext}"
        fig.savefig(p, dpi=150 if ext == "png" else None, bbox_inches="tight")
        paths.append(p)
    plt.close(fig)
    return paths


def figure(ncols: int, nrows: int = 1, width: float = 4.2, height: float = 3.4):
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False)
    return fig, axes


def colour(i: int, n: int):
    import matplotlib

    return matplotlib.colormaps["viridis"](i / max(n - 1, 1))


def series(rows: Sequence[dict], method: str, key: str, value: float, x: str, y: str):
    """(x, y) arrays of ``rows`` of ``method`` with ``row[key] == value``, sorted by x."""
    sel = sorted((r[x], r[y]) for r in rows if r["method"] == method and math.isclose(r[key], value))
    if not sel:
        return np.array([]), np.array([])
    xs, ys = zip(*sel, strict=True)
    return np.array(xs), np.array(ys)


# --- methods -------------------------------------------------------------------------------
#: Settings of each method per resolution (FFT: the paper's 128 x 128 grid; one FFT thread per
#: worker process, the runner supplies the parallelism).
METHOD_SETTINGS: dict[str, dict[str, dict[str, Any]]] = {
    CLOSED: {r: {"warn": False} for r in RESOLUTIONS},
    "fft": {"tiny": {"n": 32, "keep_fields": False, "workers": 1},
            "quick": {"n": 128, "keep_fields": False, "workers": 1},
            "full": {"n": 128, "keep_fields": False, "workers": 1}},
    "fem": {"tiny": {"mesh": "coarse"}, "quick": {"mesh": "default"}, "full": {"mesh": "default"}},
}


#: Variants of registered methods that studies may ask for by name: name -> (method, extra settings).
#: ``fft-frictionless``: the layer resting on its base without friction (fig 7 asks which interface
#: each literature solution assumes; the paper's model, and our default, is bonded).
VARIANTS: dict[str, tuple[str, dict[str, Any]]] = {
    "fft-frictionless": ("fft", {"interface": "frictionless"}),
}


def build_methods(resolution: str, names: Sequence[str] | None = None) -> tuple[dict[str, Any], list[str]]:
    """Instances of the requested registered methods at ``resolution``, and notes on those that
    could not be built (a method whose package is missing or broken is reported, not fatal)."""
    from coathertz.methods import get_method, method_names

    check_resolution(resolution)
    available = method_names()
    wanted = list(names) if names else available
    unknown = [n for n in wanted if n not in available]
    if unknown:
        raise CoatHertzError(f"unknown method(s) {unknown}; choose from {available}")
    methods, notes = {}, []
    todo = [(n, n, {}) for n in wanted] + [(v, base, extra) for v, (base, extra) in VARIANTS.items()
                                           if base in wanted]
    for key, n, extra in todo:
        settings = {**METHOD_SETTINGS.get(n, {}).get(resolution, {}), **extra}
        try:
            methods[key] = get_method(n, **settings)
        except Exception as exc:
            notes.append(f"method {key!r} unavailable: {type(exc).__name__}: {exc}")
    return methods, notes
