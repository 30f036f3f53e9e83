"""The report's one JSON sanitiser (non-finite floats as strings, numpy scalars as Python ones).

The hardening branch adds a package-wide sanitiser; when both are merged, this module should
become an import of it (one place to change).
"""

from __future__ import annotations

import math
from typing import Any


def json_safe(v: Any) -> Any:
    """``v`` with every non-finite float written as a string (``"nan"``, ``"inf"``), tuples as
    lists, dict keys as strings and numpy scalars as Python numbers."""
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    if isinstance(v, dict):
        return {str(k): json_safe(x) for k, x in v.items()}
    if isinstance(v, list | tuple | set | frozenset):
        return [json_safe(x) for x in v]
    if hasattr(v, "item") and callable(v.item):
        return json_safe(v.item())
    return v
