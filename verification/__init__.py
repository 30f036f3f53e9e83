"""The paper's studies, one module per figure or table (``coathertz.verification``).

A study is a public module of this package that defines

``NAME``, ``TITLE``
    Registry name (``coathertz verify --study NAME``) and a one-line title.
``CLAIM``
    The paper's claim the study checks, in words (the module docstring gives the details).
``cases(resolution) -> list[StudyCase]``
    The cases at resolution ``tiny`` (tests), ``quick`` (CI, the README main job) or ``full``
    (the paper's grids), each with its ``tier``: the most expensive method cost worth running
    on it. Every registered method that supports a case and whose cost its tier admits runs it
    (:mod:`coathertz.methods`); no study names a method.
``analyse(result) -> None``
    Fills ``result.claims`` (and ``result.extra``) from the rows, the errors of the closed form
    against each case's reference and the cross-checks (:class:`StudyResult`).
``plot(result, outdir) -> list[Path]``
    Writes its figures (PNG and SVG) and returns their paths.

Optional: ``QUANTITIES``, ``VARIANTS`` (study-specific method variants: name -> (registered
method, extra settings)), ``PREDICTED`` (default ``closed-form``), ``GENERIC_FIGURES = False``,
``RUN_EARLY = True`` (``verify`` runs it before the others, the report keeps the paper's order:
for a study that keeps this process or processes of its own busy for long, solving in
``analyse`` or refining its references, so that the workers solve the next studies' cases
meanwhile, and the run does not end on it with idle workers).

:func:`studies` discovers the modules with ``pkgutil``, so adding a module adds a study.
This package's namespace is the public API the studies, the report and the CLI use.
"""

from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType

from coathertz.errors import CoatHertzError
from coathertz.figstyle import colour, figure, method_handles, method_style, save, series
from coathertz.methods import method_info, method_names, reference_for

from .claims import bound_claim, judged_on, max_abs, plural, uncertainty_for
from .paper import (
    E_SUBSTRATE,
    NU,
    R_SPHERE,
    W_LOAD,
    elastic_case,
    fig3_ratios,
    h_grid,
    nearest,
    rigid_substrate_case,
)
from .running import build_methods, plan, run_study, variants_of
from .study import (
    CLOSED,
    COSTS,
    INCONCLUSIVE,
    RESOLUTIONS,
    VERDICTS,
    Claim,
    StudyCase,
    StudyResult,
    check_resolution,
    judge,
)
from .tables import (
    FIELD,
    QUANTITIES,
    SYMBOL,
    bars,
    crosscheck,
    crosscheck_summary,
    group_by_case,
    make_errors,
    make_rows,
    params_of,
    uncertainty_by_case,
)

__all__ = [
    "CLOSED", "COSTS", "E_SUBSTRATE", "FIELD", "INCONCLUSIVE", "NU", "ORDER", "QUANTITIES", "RESOLUTIONS",
    "R_SPHERE", "SYMBOL", "VERDICTS", "W_LOAD", "Claim", "StudyCase", "StudyResult", "bars", "bound_claim",
    "build_methods", "check_resolution", "colour", "crosscheck", "crosscheck_summary", "elastic_case",
    "fig3_ratios", "figure", "get_study", "group_by_case", "h_grid", "judge", "judged_on", "make_errors",
    "make_rows", "max_abs", "method_handles", "method_info", "method_names", "method_style", "nearest",
    "params_of", "plan", "plural", "reference_for",
    "rigid_substrate_case", "run_study", "save", "series", "studies", "uncertainty_by_case",
    "uncertainty_for", "variants_of",
]

_REQUIRED = ("NAME", "TITLE", "CLAIM", "cases", "analyse", "plot")
#: Modules of this package that are framework, not studies.
_FRAMEWORK = {"claims", "paper", "running", "study", "tables"}
#: Order in the report (the paper's order); studies not listed come after, by name.
ORDER = ("fig3", "fig4", "fig5", "poisson", "fig6", "fig7", "fig8_9", "fig10", "section6", "refit")


def studies() -> dict[str, ModuleType]:
    """Study modules by ``NAME``, in the paper's order."""
    found = {}
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_") or info.name in _FRAMEWORK:
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        if all(hasattr(mod, a) for a in _REQUIRED):
            found[mod.NAME] = mod
    rank = {n: i for i, n in enumerate(ORDER)}
    return dict(sorted(found.items(), key=lambda kv: (rank.get(kv[0], len(rank)), kv[0])))


def get_study(name: str) -> ModuleType:
    all_ = studies()
    if name not in all_:
        raise CoatHertzError(f"unknown study {name!r}; choose from {list(all_)}")
    return all_[name]
