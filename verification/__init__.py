"""The paper's studies, one module per figure or table (``coathertz.verification``).

Every public module of this package that defines ``NAME``, ``cases``, ``analyse`` and ``plot``
is a study (see :mod:`coathertz.verification._common` for the protocol); :func:`studies`
discovers them with :mod:`pkgutil`, so adding a module adds a study to
``coathertz verify --study``. No hand-kept table.
"""

from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType

from coathertz.errors import CoatHertzError

_REQUIRED = ("NAME", "TITLE", "CLAIM", "cases", "analyse", "plot")
#: Order in the report (the paper's order); studies not listed come after, by name.
ORDER = ("fig3", "fig4", "fig5", "poisson", "fig6", "fig7", "fig8_9", "fig10", "section6")


def studies() -> dict[str, ModuleType]:
    """Study modules by ``NAME``, in the paper's order."""
    found = {}
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
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
