"""The interface every method implements, and the registry that lists them.

A method is an object with a ``name``, a ``settings()`` dict (the knobs that change its
numbers, used as part of the result-store key), ``supports(case) -> bool`` and
``solve(case) -> ContactResult``. Methods register through the ``coathertz.methods``
entry-point group in ``pyproject.toml``, so the CLI and the study runner list them
without a hand-kept table, and a plug-in package can add its own.
"""

from __future__ import annotations

from collections.abc import Mapping
from importlib.metadata import entry_points
from typing import Any, Protocol, runtime_checkable

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.results import ContactResult


@runtime_checkable
class Method(Protocol):
    """A way to compute the contact characteristics of a case."""

    name: str

    def settings(self) -> Mapping[str, Any]:
        """Settings that change the numbers (JSON-serialisable)."""
        ...

    def supports(self, case: ContactCase) -> bool:
        """Whether this method can solve ``case``."""
        ...

    def solve(self, case: ContactCase) -> ContactResult:
        """Solve ``case``; raise :class:`coathertz.ConvergenceError` if it cannot."""
        ...


GROUP = "coathertz.methods"


def method_names() -> list[str]:
    """Names of the registered methods."""
    return sorted(ep.name for ep in entry_points(group=GROUP))


def get_method(name: str, **settings: Any) -> Method:
    """Instantiate the registered method ``name`` with ``settings``."""
    eps = {ep.name: ep for ep in entry_points(group=GROUP)}
    if name not in eps:
        raise CoatHertzError(f"unknown method {name!r}; choose one of {sorted(eps)}")
    factory = eps[name].load()
    return factory(**settings)
