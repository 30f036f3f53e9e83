"""Strict JSON for results: the one place where inf/nan and numpy scalars are translated.

JSON has no ``inf`` or ``nan``; coathertz writes them as the strings ``"inf"``, ``"-inf"`` and
``"nan"`` (a flat surface has ``R = inf``, a rigid body ``E = inf``) and reads them back.
"""

from __future__ import annotations

import json
import math
from typing import Any

_SPECIAL = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}


#: Values that :func:`to_jsonable` returns as they are (exact types; subclasses such as numpy's
#: float64 take the general path).
_KEPT = frozenset({str, int, bool, type(None)})
_isfinite = math.isfinite
#: Values that :func:`from_jsonable` returns as they are.
_NUMBERS = frozenset({int, float, bool, type(None)})


def to_jsonable(obj: Any) -> Any:
    """``obj`` with non-finite floats as strings, numpy scalars and arrays as Python values,
    tuples and sets as lists and dict keys as strings."""
    # the common case first, without a call per number or string (a run converts some 10^5
    # values): plain dicts and lists of str, int, bool, None and finite floats
    t = type(obj)
    if t is float:
        return obj if _isfinite(obj) else str(obj)
    if t in _KEPT:
        return obj
    if t is dict:
        return {(k if type(k) is str else str(k)):
                (v if (tv := type(v)) in _KEPT or (tv is float and _isfinite(v)) else to_jsonable(v))
                for k, v in obj.items()}
    if t is list or t is tuple:
        return [v if (tv := type(v)) in _KEPT or (tv is float and _isfinite(v)) else to_jsonable(v)
                for v in obj]
    return _to_jsonable(obj)


def _to_jsonable(obj: Any) -> Any:
    """:func:`to_jsonable` of anything (subclasses, sets, numpy values)."""
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
    t = type(obj)  # what json.loads makes first, without a call per value
    if t is dict:
        return {k: (_SPECIAL.get(v, v) if (tv := type(v)) is str
                    else v if tv in _NUMBERS else from_jsonable(v)) for k, v in obj.items()}
    if t is list:
        return [_SPECIAL.get(v, v) if (tv := type(v)) is str else v if tv in _NUMBERS else from_jsonable(v)
                for v in obj]
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
    if '"inf"' not in text and '"-inf"' not in text and '"nan"' not in text:
        return json.loads(text)  # no string that from_jsonable would turn into a float
    return from_jsonable(json.loads(text))
