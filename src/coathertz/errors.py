"""Exceptions and warnings shared by every part of coathertz.

Every error a user can cause is a :class:`~coathertz.errors.CoatHertzError` (the CLI prints its
message and exits with status 2); :class:`~coathertz.errors.ConvergenceError` and
:class:`~coathertz.errors.StoreError` are the other two kinds the CLI reports without a traceback.
"""

from __future__ import annotations


class CoatHertzError(ValueError):
    """Invalid input: the message names the body, the parameter and its valid range."""


class ConvergenceError(RuntimeError):
    """An iterative solver did not reach its tolerance within its iteration cap."""


class StoreError(CoatHertzError):
    """The result store cannot be used (damaged, unwritable, or in use by another run)."""


class FittedRangeWarning(UserWarning):
    """A predictor was evaluated outside the range its fitted curves cover."""


class ModelValidityWarning(UserWarning):
    """A result lies outside the assumptions of the model (half-space, small strain: a/R <= 0.1).

    The number is still returned; the warning's text is also recorded in
    ``result.meta["validity"]`` (see :mod:`coathertz.validity`).
    """


def check_positive(name: str, value: float, *, allow_inf: bool = False) -> None:
    """Raise :class:`~coathertz.errors.CoatHertzError` unless ``0 < value`` (finite unless ``allow_inf``).

    ``name`` may carry words before the symbol ("radius R"); the range uses the symbol.
    """
    import math

    try:
        v = float(value)
    except (TypeError, ValueError) as exc:
        raise CoatHertzError(f"{name} must be a number > 0, got {value!r}") from exc
    if math.isnan(v) or v <= 0 or (math.isinf(v) and not allow_inf):
        sym = name.split()[-1]
        rng = f"0 < {sym} <= inf" if allow_inf else f"0 < {sym} < inf"
        raise CoatHertzError(f"{name} must satisfy {rng}, got {value!r}")
