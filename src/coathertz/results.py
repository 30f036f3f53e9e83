"""The result every method returns: :class:`ContactResult`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from dataclasses import fields as dc_fields
from typing import Any

import numpy as np


@dataclass(frozen=True)
class ContactResult:
    """Contact characteristics of one case computed by one method (SI units).

    Parameters
    ----------
    method
        Method name (``closed-form``, ``fft``, ``fem``, ...).
    delta
        Rigid-body approach [m] relative to points far away in the substrate(s).
    a
        Contact radius [m]; for ellipses the equivalent radius ``sqrt(r_a r_b)``.
    p0
        Maximum contact pressure [Pa].
    r_a, r_b
        Major and minor semi-axes [m] (equal to ``a`` for circular contacts).
    W
        Normal load [N].
    meta
        Method-specific scalars and strings (settings, iterations, wall time, DOFs, ...).
        Must be JSON-serialisable.
    fields
        Optional arrays (pressure field, profiles); not compared, not stored by default.
    """

    method: str
    delta: float
    a: float
    p0: float
    W: float
    r_a: float = math.nan
    r_b: float = math.nan
    meta: Mapping[str, Any] = field(default_factory=dict)
    fields: Mapping[str, np.ndarray] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        for name in ("delta", "a", "p0", "W", "r_a", "r_b"):
            object.__setattr__(self, name, float(getattr(self, name)))
        if math.isnan(self.r_a):
            object.__setattr__(self, "r_a", self.a)
        if math.isnan(self.r_b):
            object.__setattr__(self, "r_b", self.a)

    def scalars(self) -> dict[str, Any]:
        """JSON-ready dict of everything but ``fields``."""
        # the fields directly (numbers and strings): ``asdict`` would deep-copy ``fields`` (the
        # arrays) only to drop them, and ``meta`` only to replace it by a shallow copy
        d = {f.name: getattr(self, f.name) for f in dc_fields(self) if f.name != "fields"}
        d["meta"] = dict(self.meta)
        return d
