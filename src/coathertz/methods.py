"""The interface every method implements, and the registry that lists them.

A method is a class registered in the ``coathertz.methods`` entry-point group of
``pyproject.toml`` (a plug-in package can add its own). Its instances have ``settings()``
(the knobs that change its numbers, part of the result-store key), ``supports(case)`` and
``solve(case) -> ContactResult``. The class declares what a study needs to use it well:

``name``
    Registry name.
``cost``
    ``cheap`` | ``moderate`` | ``expensive`` per case: a study runs a method on a case only
    when the case's tier admits the method's cost (:func:`admits`).
``marker``, ``label``
    Matplotlib marker and legend label (every figure and legend takes them from here).
``reference_rank``
    Who arbitrates: of the methods that solved a case, the one of highest rank is the reference
    the closed form is judged against (closed form 0: it is the thing judged).
``source_packages``
    Modules / packages whose source defines its numbers; the result store's code version
    hashes them together with the shared case model (:data:`SHARED_SOURCES`).
``settings_for(resolution)``
    Constructor keyword arguments at a study resolution (``tiny`` | ``quick`` | ``full``).

Optional hooks (:data:`OPTIONAL_HOOKS`), used when present:

``solve_many(cases) -> list[ContactResult]``
    Solve a chunk of cases at once (the runner passes a method's pending cases through it:
    shared tables, warm starts); results in the order of ``cases``.
``refined_settings(resolution)`` (classmethod)
    Constructor settings of a finer discretisation at a resolution: a study re-solves its
    reference with them to measure the reference's own numerical uncertainty.
``inline`` (class variable, bool)
    True for a method that costs microseconds per case: the runner solves its cases in the
    calling process instead of shipping them to workers.

:func:`method_class` checks every registered class against this contract when it is loaded
(:func:`validate`) and names what is missing or malformed. Nothing else in the suite names a
method: studies, the store and the report read the metadata through :func:`method_info`,
:func:`method_class` and :func:`numerical_sources`.
"""

from __future__ import annotations

import inspect
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from importlib.metadata import entry_points
from typing import Any, ClassVar, Protocol, runtime_checkable

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.results import ContactResult

GROUP = "coathertz.methods"
#: Cost classes, cheapest first.
COSTS = ("cheap", "moderate", "expensive")
#: Study resolutions.
RESOLUTIONS = ("tiny", "quick", "full")
#: Modules every method's numbers depend on (the shared case model): always hashed.
SHARED_SOURCES = ("coathertz.case", "coathertz.materials", "coathertz.stack", "coathertz.closedform.hertz",
                  "coathertz.results", "coathertz.validity", "coathertz.units")


@runtime_checkable
class Method(Protocol):
    """A way to compute the contact characteristics of a case: the required members (see the
    module docstring for their meaning and for the optional hooks ``solve_many``,
    ``refined_settings`` and ``inline``). Metadata are class variables (``ClassVar``)."""

    name: ClassVar[str]
    cost: ClassVar[str]
    marker: ClassVar[str]
    label: ClassVar[str]
    reference_rank: ClassVar[int]
    source_packages: ClassVar[tuple[str, ...]]

    @classmethod
    def settings_for(cls, resolution: str) -> dict[str, Any]:
        """Constructor keyword arguments at a study resolution."""
        ...

    def settings(self) -> Mapping[str, Any]:
        """Settings that change the numbers (JSON-serialisable)."""
        ...

    def supports(self, case: ContactCase) -> bool:
        """Whether this method can solve ``case``."""
        ...

    def solve(self, case: ContactCase) -> ContactResult:
        """Solve ``case``; raise :class:`~coathertz.errors.ConvergenceError` if it cannot."""
        ...


@dataclass(frozen=True)
class MethodInfo:
    """The metadata of a registered method (defaults for a plug-in that declares none)."""

    name: str
    cost: str = "expensive"
    marker: str = "x"
    label: str = ""
    reference_rank: int = 1
    source_packages: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.cost not in COSTS:
            raise CoatHertzError(f"method {self.name!r}: cost must be one of {COSTS}, got {self.cost!r}")


def _entry_points() -> dict[str, Any]:
    return dict(_scanned_entry_points())


@lru_cache(maxsize=1)
def _scanned_entry_points() -> dict[str, Any]:
    """The group's entry points, scanned once per process (a scan reads every installed
    distribution's metadata: about 5 ms, and a run asked for it some 200 times)."""
    return {ep.name: ep for ep in entry_points(group=GROUP)}


def method_names() -> list[str]:
    """Names of the registered methods."""
    return sorted(_entry_points())


#: Required members of a method class: (name, kind) with kind ``method`` (callable), or the
#: type of a class variable.
REQUIRED_MEMBERS: tuple[tuple[str, Any], ...] = (
    ("settings_for", "method"), ("settings", "method"), ("supports", "method"), ("solve", "method"),
    ("name", str), ("cost", str), ("marker", str), ("label", str), ("reference_rank", int),
    ("source_packages", tuple),
)
#: Optional hooks and what they must be when present (see the module docstring).
OPTIONAL_HOOKS: tuple[tuple[str, Any], ...] = (
    ("solve_many", "method"), ("refined_settings", "method"), ("inline", bool),
)


def validate(cls: Any, name: str) -> Any:
    """``cls`` if it meets the method contract (:data:`REQUIRED_MEMBERS`, :data:`OPTIONAL_HOOKS`,
    ``cost`` in :data:`COSTS`); else :class:`~coathertz.errors.CoatHertzError` naming the method and
    every member that is missing or malformed."""
    problems = []
    for member, kind in (*REQUIRED_MEMBERS, *OPTIONAL_HOOKS):
        required = (member, kind) in REQUIRED_MEMBERS
        if not hasattr(cls, member):
            if required:
                problems.append(f"missing {member}" + (" (method)" if kind == "method" else
                                                       f" (class variable, {kind.__name__})"))
            continue
        value = getattr(cls, member)
        if kind == "method":
            if not callable(value):
                problems.append(f"{member} must be callable, got {type(value).__name__}")
        elif not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
            problems.append(f"{member} must be a {kind.__name__}, got {value!r}")
    if not problems and getattr(cls, "cost", None) not in COSTS:
        problems.append(f"cost must be one of {COSTS}, got {cls.cost!r}")
    if problems:
        raise CoatHertzError(f"method {name!r} ({getattr(cls, '__module__', '?')}."
                             f"{getattr(cls, '__qualname__', cls)!s}) does not meet the method contract "
                             f"(coathertz.methods): {'; '.join(problems)}")
    return cls


def method_class(name: str) -> type:
    """The registered class of method ``name``, checked against the contract (:func:`validate`)."""
    eps = _entry_points()
    if name not in eps:
        raise CoatHertzError(f"unknown method {name!r}; choose one of {sorted(eps)}")
    return validate(eps[name].load(), name)


def get_method(name: str, **settings: Any) -> Method:
    """Instantiate the registered method ``name`` with ``settings``.

    A setting the method does not take, or a value its constructor refuses, raises
    :class:`~coathertz.errors.CoatHertzError` naming the method and the setting.
    """
    cls = method_class(name)
    try:
        params = inspect.signature(cls).parameters
    except (TypeError, ValueError):  # pragma: no cover - a builtin or C factory
        params = {}
    if params and not any(p.kind is p.VAR_KEYWORD for p in params.values()):
        known = [k for k, p in params.items() if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        unknown = sorted(set(settings) - set(known))
        if unknown:
            raise CoatHertzError(f"get_method({name!r}): unknown setting{'s' if len(unknown) > 1 else ''} "
                                 f"{', '.join(unknown)}; {name} takes {', '.join(known) or 'none'}")
    try:
        return cls(**settings)
    except CoatHertzError as exc:
        raise CoatHertzError(f"get_method({name!r}): {exc}") from None
    except (TypeError, ValueError) as exc:
        raise CoatHertzError(f"get_method({name!r}): bad settings {settings}: {exc}") from None


def require_case(case: Any, method: str) -> ContactCase:
    """``case`` if it is a :class:`~coathertz.case.ContactCase`; else
    :class:`~coathertz.errors.CoatHertzError` naming the argument
    (a method's ``solve`` calls this first)."""
    if not isinstance(case, ContactCase):
        raise CoatHertzError(f"{method}.solve(case): case must be a coathertz ContactCase (e.g. from "
                             f"coathertz.casefile.load_case), got {type(case).__name__} {case!r:.60}")
    return case


def info_of(obj: Any, name: str | None = None) -> MethodInfo:
    """:class:`MethodInfo` read from a method class or instance (defaults where absent)."""
    name = name or getattr(obj, "name", None) or getattr(obj, "__name__", "?")
    return MethodInfo(name=str(name), cost=getattr(obj, "cost", "expensive"),
                      marker=getattr(obj, "marker", "x"), label=getattr(obj, "label", "") or str(name),
                      reference_rank=int(getattr(obj, "reference_rank", 1)),
                      source_packages=tuple(getattr(obj, "source_packages", ())))


@lru_cache(maxsize=64)
def method_info(name: str) -> MethodInfo:
    """Metadata of the registered method ``name``; a name that is not registered (e.g. a
    study's variant such as ``fft-frictionless``) gets the metadata of its registered prefix."""
    names = method_names()
    if name not in names:
        base = max((n for n in names if name.startswith(n + "-")), key=len, default=None)
        if base is None:
            return MethodInfo(name=name, label=name)
        b = method_info(base)
        return MethodInfo(name, b.cost, b.marker, f"{b.label} ({name[len(base) + 1:]})", b.reference_rank,
                          b.source_packages)
    return info_of(method_class(name), name)


def settings_for(name: str, resolution: str) -> dict[str, Any]:
    """Constructor settings of registered method ``name`` at a study resolution."""
    if resolution not in RESOLUTIONS:
        raise CoatHertzError(f"resolution must be one of {RESOLUTIONS}, got {resolution!r}")
    cls = method_class(name)
    fn = getattr(cls, "settings_for", None)
    return dict(fn(resolution)) if fn is not None else {}


def admits(tier: str, cost: str) -> bool:
    """Whether a case of ``tier`` (the most expensive cost class worth running on it) admits a
    method of ``cost``."""
    if tier not in COSTS:
        raise CoatHertzError(f"tier must be one of {COSTS}, got {tier!r}")
    if cost not in COSTS:
        raise CoatHertzError(f"cost must be one of {COSTS}, got {cost!r}")
    return COSTS.index(cost) <= COSTS.index(tier)


def reference_for(case: ContactCase, methods: Mapping[str, Any] | Iterable[str]) -> str | None:
    """The arbiter of ``case`` among ``methods`` (names, or name -> instance): the highest
    ``reference_rank`` above 0 among those that support the case (instances) or are listed
    (names: the caller passes the methods that solved it). None if there is none."""
    if isinstance(methods, Mapping):
        cands = [n for n, m in methods.items() if m is None or m.supports(case)]
    else:
        cands = list(methods)
    ranked = [(method_info(n).reference_rank, n) for n in cands if method_info(n).reference_rank > 0]
    return max(ranked)[1] if ranked else None


def rank_order(names: Iterable[str]) -> list[str]:
    """Method names, reference first (highest rank), the judged closed form last."""
    return sorted(names, key=lambda n: (-method_info(n).reference_rank, n))


def numerical_sources(names: Sequence[str] | None = None) -> list[str]:
    """Modules whose source defines the numbers: the shared case model and every registered
    method's ``source_packages`` (what :func:`coathertz.store.code_version` hashes)."""
    out = list(SHARED_SOURCES)
    for n in names if names is not None else method_names():
        try:
            pkgs = method_info(n).source_packages
        except Exception:  # a broken plug-in: its results are not stored anyway
            continue
        out += [p for p in pkgs if p not in out]
    return out
