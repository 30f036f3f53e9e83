"""Plot helpers shared by the studies' figures and the report's: figure creation, saving,
colours, series, and each method's marker and legend label (from the method registry).

This module sits below both :mod:`coathertz.verification` and :mod:`coathertz.report` (it imports
neither), so the report can import the study framework at module level without a cycle.
The rules these helpers serve are in ``docs/style-figures.md``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["colour", "figure", "method_handles", "method_style", "save", "series"]


def save(fig, outdir: str | Path, name: str) -> list[Path]:
    """Save ``fig`` as PNG (150 dpi) and SVG in ``outdir``; close it. Byte-for-byte reproducible:
    no date in the SVG, fixed SVG ids (a rerun with equal numbers leaves a published report unchanged)."""
    import matplotlib
    import matplotlib.pyplot as plt

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = []
    with matplotlib.rc_context({"svg.hashsalt": "coathertz"}):
        for ext in ("png", "svg"):
            p = outdir / f"{name}.{ext}"
            fig.savefig(p, dpi=150 if ext == "png" else None, bbox_inches="tight",
                        metadata={"Date": None} if ext == "svg" else None)
            paths.append(p)
    plt.close(fig)
    return paths


def figure(ncols: int, nrows: int = 1, width: float = 4.2, height: float = 3.4, sharey: bool = False):
    """A grid of ``nrows`` x ``ncols`` panels (``axes[row, col]``); ``sharey`` for panels comparing
    the same quantity (docs/style-figures.md)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False,
                             sharey=sharey)
    return fig, axes


def colour(i: int, n: int):
    import matplotlib

    return matplotlib.colormaps["viridis"](i / max(n - 1, 1))


def series(rows: Sequence[dict], method: str, key: str, value: float, x: str, y: str):
    """(x, y) arrays of ``rows`` of ``method`` with ``row[key] == value``, sorted by x."""
    sel = sorted((r[x], r[y]) for r in rows if r["method"] == method and math.isclose(r[key], value))
    if not sel:
        return np.array([]), np.array([])
    xs, ys = zip(*sel, strict=True)
    return np.array(xs), np.array(ys)


def method_style(name: str, colour: Any = None) -> dict[str, Any]:
    """Matplotlib keywords for a method's markers: its registered marker; the reference-ranked
    methods filled and small, lower-ranked ones open and larger (so both show where they overlap)."""
    from coathertz.methods import method_info

    info = method_info(name)
    filled = info.reference_rank >= 20
    kw: dict[str, Any] = {"marker": info.marker if info.marker not in ("-", "") else "None",
                          "ms": 4 if filled else 7, "ls": "none"}
    if colour is not None:
        kw["color"] = colour
        kw["mfc"] = colour if filled else "none"
    elif not filled:
        kw["mfc"] = "none"
    return kw


def method_handles(names: Iterable[str], closed_form_line: bool = True) -> list:
    """Legend handles, one per method, in black: the closed form as a line, the others as their
    registered markers, labelled with their registered labels."""
    from matplotlib.lines import Line2D

    from coathertz.methods import method_info, rank_order

    out = []
    for n in rank_order(set(names)):
        info = method_info(n)
        if info.reference_rank <= 0:
            if closed_form_line:
                out.append(Line2D([], [], color="k", lw=1.2, label=info.label))
            continue
        out.append(Line2D([], [], label=info.label, **method_style(n, "k")))
    return out
