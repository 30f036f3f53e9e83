"""Strict JSON for results: the one place where inf/nan and numpy scalars are translated.

JSON has no ``inf`` or ``nan``; coathertz writes them as the strings ``"inf"``, ``"-inf"`` and
``"nan"`` (a flat surface has ``R = inf``, a rigid body ``E = inf``) and reads them back.
"""

from __future__ import annotations

import json
import math
from typing import Any

_SPECIAL = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}


def to_jsonable(obj: Any) -> Any:
    """``obj`` with non-finite floats as strings, numpy scalars and arrays as Python values,
    tuples and sets as lists and dict keys as strings."""
    if isinstance(obj, bool) or obj is None or isinstance(obj, int | str):
        return obj
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else str(obj)
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple | set | frozenset):
        return [to_jsonable(v) for v in obj]
    if hasattr(obj, "tolist") and callable(obj.tolist):  # numpy scalars and arrays
        return to_jsonable(obj.tolist())
    if hasattr(obj, "item") and callable(obj.item):
        return to_jsonable(obj.item())
    return obj


def from_jsonable(obj: Any) -> Any:
    """Inverse of :func:`to_jsonable` for numbers: ``"inf"``, ``"-inf"``, ``"nan"`` -> float."""
    if isinstance(obj, str):
        return _SPECIAL.get(obj, obj)
    if isinstance(obj, dict):
        return {k: from_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [from_jsonable(v) for v in obj]
    return obj


def dumps(obj: Any, **kwargs: Any) -> str:
    """Strict JSON text of ``obj`` (see :func:`to_jsonable`); ``kwargs`` go to ``json.dumps``."""
    kwargs.setdefault("default", str)
    return json.dumps(to_jsonable(obj), allow_nan=False, **kwargs)


def loads(text: str | None) -> Any:
    """Parse JSON written by :func:`dumps` (``None`` stays ``None``)."""
    if text is None:
        return None
    return from_jsonable(json.loads(text))
