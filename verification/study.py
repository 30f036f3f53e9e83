"""The study protocol's data types: a case of a study, a checked claim, a study's result.

A study module (see :mod:`coathertz.verification`) returns :class:`StudyCase` objects from
``cases(resolution)`` and fills :attr:`StudyResult.claims` with :class:`Claim` objects in
``analyse(result)``. :func:`judge` turns a number, the paper's bound and the number's
uncertainty into a verdict.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field, fields, is_dataclass
from typing import Any

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.methods import COSTS, RESOLUTIONS

__all__ = ["CLOSED", "COSTS", "RESOLUTIONS", "VERDICTS", "Claim", "StudyCase", "StudyResult",
           "check_resolution", "fork_map", "fork_pool", "judge"]

#: The method the paper's claims are about: the closed form is judged, never a reference.
CLOSED = "closed-form"
HOLDS, FAILS, INCONCLUSIVE = "holds", "does not hold", "inconclusive (within numerical error)"
#: Tier of a case no registered method runs.
NO_METHOD = "none"
#: Every verdict a claim can have, in the order the report counts them.
VERDICTS = (HOLDS, FAILS, INCONCLUSIVE, "observed", "n/a")


def fork_map(fn: Callable[[Any], Any], jobs: Sequence[Any], workers: int) -> list:
    """``fn(job)`` of each job, in order, a failed job giving its exception (not raised).

    The independent solves of a study's ``analyse`` (its own FFT or FE searches): on up to
    ``workers`` forked processes (the run's ``workers``; all of them finish with the call), in
    this process where there is one worker, one job or no ``fork`` (:func:`fork_pool`). ``fn``
    must be a module-level function (it is pickled by name).
    """
    with fork_pool(fn, len(jobs), workers) as submit:
        futures = [submit(j) for j in jobs]
        return [f.result() for f in futures]


@contextlib.contextmanager
def fork_pool(fn: Callable[[Any], Any], n_jobs: int, workers: int):
    """A block in which ``submit(job)`` starts ``fn(job)`` and returns its future (``result()``:
    its value, or the exception of a failed job): on up to ``min(workers, n_jobs)`` forked
    processes, which all finish with the block, or at once in this process where there is one
    worker, one job or no ``fork``. For searches whose later jobs depend on earlier results."""
    import multiprocessing

    if workers <= 1 or n_jobs <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        yield lambda job: _Done(_call(fn, job))
        return
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(min(workers, n_jobs), mp_context=multiprocessing.get_context("fork")) as ex:
        yield lambda job: ex.submit(_call, fn, job)


class _Done:
    """A job already done (in this process): the ``result()`` of a future."""

    def __init__(self, value: Any) -> None:
        self.value = value

    def result(self) -> Any:
        return self.value


def _call(fn: Callable[[Any], Any], job: Any) -> Any:
    try:
        return fn(job)
    except Exception as exc:  # the caller reports it; one job must not sink the others
        return exc


def check_resolution(resolution: str) -> str:
    if resolution not in RESOLUTIONS:
        raise CoatHertzError(f"resolution must be one of {RESOLUTIONS}, got {resolution!r}")
    return resolution


@dataclass(frozen=True)
class StudyCase:
    """One case of a study.

    Parameters
    ----------
    id, case, params
        Identifier within the study, the contact case, and its parameters (columns of the rows).
    tier
        The most expensive cost class worth running on this case (``cheap``, ``moderate``,
        ``expensive``): every registered method that supports the case and whose ``cost`` the
        tier admits runs it. A study marks the subset worth an expensive method. ``none``: no
        registered method runs it (a study that solves it itself in ``analyse``). For studies
        written against the old protocol, a set of method names is accepted and read as the tier
        of its most expensive member (the empty set as ``none``).
    variants
        Names of study-declared method variants (module ``VARIANTS``) that run this case too.
    refine
        Also solve this case with its reference method at refined settings (the method's optional
        ``refined_settings(resolution)``): a convergence estimate of the reference where no other
        method cross-checks it.
    """

    id: str
    case: ContactCase
    params: Mapping[str, Any]
    tier: str = "moderate"
    variants: frozenset[str] = frozenset()
    refine: bool = False

    def __post_init__(self) -> None:
        if isinstance(self.tier, set | frozenset | list | tuple):  # the old protocol's method set
            from coathertz.methods import method_info

            costs = [COSTS.index(method_info(n).cost) for n in self.tier]
            object.__setattr__(self, "tier", COSTS[max(costs)] if costs else NO_METHOD)
        if self.tier not in (*COSTS, NO_METHOD):
            raise CoatHertzError(f"StudyCase {self.id!r}: tier must be one of {(*COSTS, NO_METHOD)}, "
                                 f"got {self.tier!r}")
        object.__setattr__(self, "variants", frozenset(self.variants))


def judge(kind: str, value: float, bound: float | tuple[float, float], uncertainty: float = 0.0,
          values: tuple[float, float] | None = None) -> tuple[bool | None, bool]:
    """``(holds, inconclusive)`` of a number against the paper's bound, respecting its uncertainty.

    ``kind``: ``"<"`` (value below bound), ``">"`` (value above bound) or ``"within"`` (every
    value in ``[lo, hi]``; pass the extremes as ``values = (min, max)``). The verdict is
    *inconclusive* when moving the number(s) by the uncertainty ``u`` could flip it, i.e. when the
    number lies within ``u`` of the bound; otherwise it holds or does not hold as computed.
    ``holds`` is the verdict at the computed number (kept for regression), None for NaN.
    """
    u = uncertainty if math.isfinite(uncertainty) else 0.0
    if kind == "within":
        lo, hi = bound  # type: ignore[misc]
        mn, mx = values if values is not None else (value, value)
        if not (math.isfinite(mn) and math.isfinite(mx)):
            return None, False
        holds = lo <= mn and mx <= hi
        margin = min(mn - lo, hi - mx)  # > 0 inside, < 0 outside
    else:
        b = float(bound)  # type: ignore[arg-type]
        if not math.isfinite(value):
            return None, False
        holds = value < b if kind == "<" else value > b
        margin = (b - value) if kind == "<" else (value - b)
    return bool(holds), bool(abs(margin) <= u and u > 0)


@dataclass(frozen=True)
class Claim:
    """A checked statement: the number we measure against the paper's bound.

    ``holds`` is None where the paper states no bound (an observation) or nothing could be
    computed. ``tol`` is the regression tolerance on ``value`` (same unit). ``uncertainty`` is
    the numerical uncertainty of ``value`` (same unit; NaN: not estimated) and ``inconclusive``
    says the value lies within it of the bound. ``judged_against`` names the reference
    method(s) and the set of cases the number was computed on.
    """

    id: str
    text: str
    value: float
    bound: str = ""
    holds: bool | None = None
    unit: str = "%"
    tol: float = 0.05
    detail: str = ""
    uncertainty: float = math.nan
    inconclusive: bool = False
    judged_against: str = ""

    @property
    def verdict(self) -> str:
        if self.holds is None:
            return "n/a" if not math.isfinite(self.value) else "observed"
        if self.inconclusive:
            return INCONCLUSIVE
        return HOLDS if self.holds else FAILS


@dataclass
class StudyResult:
    """Everything a study produced.

    ``rows``: one per (case, method) with the results and the paper's bars; ``errors``: the
    closed form against each case's reference (``reference``: case id -> arbitrating method);
    ``crosscheck``: every other numerical method against the reference, per case and quantity;
    ``uncertainty``: case id -> quantity -> the largest cross-check difference (percent).
    """

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
    reference: dict[str, str] = field(default_factory=dict)
    crosscheck: list[dict] = field(default_factory=list)
    uncertainty: dict[str, dict[str, float]] = field(default_factory=dict)
    skipped: dict[str, str] = field(default_factory=dict)
    #: local processes the study's own solves in ``analyse`` may use (the run's ``workers``)
    workers: int = 1

    def rows_of(self, method: str) -> list[dict]:
        return [r for r in self.rows if r["method"] == method]

    def reference_rows(self) -> list[dict]:
        """The row of each case's reference method."""
        return [r for r in self.rows if self.reference.get(r["case"]) == r["method"]]

    def to_json(self) -> dict:
        """Every field as plain dicts and lists (as ``dataclasses.asdict`` makes them, a dataclass
        nested anywhere turned into the dict of its fields), the claims with their verdicts.

        The containers are new; their numbers, strings and arrays are this result's own (not the
        deep copies ``asdict`` would make: the report only writes them out)."""
        d = {f.name: _plain(getattr(self, f.name)) for f in fields(self)}
        d["claims"] = [{**asdict(c), "verdict": c.verdict} for c in self.claims]
        return d


_ATOMS = frozenset({float, int, str, bool, type(None)})


def _plain(obj: Any) -> Any:
    """``dataclasses.asdict``'s conversion of a value, without copying what is not a container."""
    t = type(obj)
    if t in _ATOMS:
        return obj
    if t is dict:
        return {(k if type(k) in _ATOMS else _plain(k)): (v if type(v) in _ATOMS else _plain(v))
                for k, v in obj.items()}
    if t is list:
        return [v if type(v) in _ATOMS else _plain(v) for v in obj]
    if is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: _plain(getattr(obj, f.name)) for f in fields(obj)}
    if isinstance(obj, tuple) and hasattr(obj, "_fields"):  # a named tuple
        return t(*[_plain(v) for v in obj])
    if isinstance(obj, list | tuple):
        return t(_plain(v) for v in obj)
    if isinstance(obj, dict):  # a subclass: as asdict does
        if hasattr(t, "default_factory"):
            out = t(obj.default_factory)
            for k, v in obj.items():
                out[_plain(k)] = _plain(v)
            return out
        return t((_plain(k), _plain(v)) for k, v in obj.items())
    return obj
