"""Parse quantities with explicit units at the edges (TOML case files, CLI flags).

Inside coathertz everything is SI. A bare number is rejected for dimensional
quantities because "380" could be Pa, MPa or GPa; the message says what to write.
"""

from __future__ import annotations

import math
import re

from coathertz.errors import CoatHertzError

#: Unit symbols accepted for each dimension, with their factor to SI.
UNITS: dict[str, dict[str, float]] = {
    "pressure": {
        "Pa": 1.0,
        "kPa": 1e3,
        "MPa": 1e6,
        "GPa": 1e9,
        "TPa": 1e12,
        "N/m2": 1.0,
        "N/mm2": 1e6,
    },
    "length": {
        "m": 1.0,
        "km": 1e3,
        "cm": 1e-2,
        "mm": 1e-3,
        "um": 1e-6,
        "µm": 1e-6,
        "μm": 1e-6,
        "micron": 1e-6,
        "nm": 1e-9,
    },
    "force": {"N": 1.0, "mN": 1e-3, "uN": 1e-6, "kN": 1e3, "MN": 1e6},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0},
}

_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|inf|infinity)\s*(\S*)\s*$")


def parse_quantity(text: str | float | int, dimension: str, *, name: str = "value") -> float:
    """Return the SI value of ``text`` such as ``"380 GPa"`` or ``"40 um"``.

    Parameters
    ----------
    text
        The quantity. Numbers without a unit are accepted only for ``angle`` (radians)
        and ``"inf"`` (an infinite radius, i.e. a flat surface, or a rigid body).
    dimension
        One of ``pressure``, ``length``, ``force``, ``angle``.
    name
        Parameter name used in error messages.
    """
    if dimension not in UNITS:
        raise CoatHertzError(f"unknown dimension {dimension!r}; expected one of {sorted(UNITS)}")
    table = UNITS[dimension]
    if isinstance(text, bool):
        raise CoatHertzError(f"{name}: expected a quantity like '1 {next(iter(table))}'")
    if isinstance(text, int | float):
        if math.isinf(text) or dimension == "angle":
            return float(text)
        raise CoatHertzError(
            f"{name} = {text!r} has no unit; write it with one of {list(table)}, "
            f"e.g. '{text} {next(iter(table))}'"
        )
    m = _QUANTITY.match(str(text))
    if not m:
        raise CoatHertzError(f"{name}: cannot read {text!r} as a number followed by a unit")
    number, unit = m.groups()
    value = float(number)
    if math.isinf(value) and not number.lstrip("+-").startswith("inf"):
        raise CoatHertzError(f"{name}: {number} is beyond the largest floating-point number (~1.8e308)")
    if unit == "":
        if math.isinf(value) or dimension == "angle":
            return value
        raise CoatHertzError(
            f"{name} = {text!r} has no unit; write it with one of {list(table)}, "
            f"e.g. '{number} {next(iter(table))}'"
        )
    if unit not in table:
        raise CoatHertzError(f"{name}: unit {unit!r} is not a {dimension} unit; use one of {list(table)}")
    si = value * table[unit]
    if math.isinf(si) and not math.isinf(value):
        raise CoatHertzError(f"{name}: {text!r} overflows in SI units (beyond ~1.8e308 {next(iter(table))})")
    return si
