"""Report figures common to every study: E x H error maps and pairwise method differences.

The study modules draw the paper's figures themselves (``plot``); these are the views the report
adds to each study: where in the (E, H) plane the closed form errs against each case's reference
(the top-ranked method that solved it), and how far every other method lies from that reference
on the cases they share (the cross-checks).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from coathertz.figstyle import save

QLABEL = {"a": "a", "p": "$p_0$", "delta": r"$\delta$", "r_a": "$r_a$", "r_b": "$r_b$"}


def _save(fig, outdir: Path, name: str) -> list[Path]:
    return save(fig, outdir, name)


def error_heatmaps(result, outdir: str | Path) -> list[Path]:
    """One figure per reference method: error of the closed form over (E, H), one panel per quantity.

    Where a study has further parameters (the Poisson check's nu_c), each cell shows the error of
    largest magnitude over them (sign kept).
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.colors import SymLogNorm
    from matplotlib.patches import Patch

    errors = [e for e in result.errors if "E" in e and "H" in e]
    # a rigid substrate has no modulus ratio (its cases carry E = 1): only elastic cases are mapped
    configs = {e.get("config", "elastic") for e in errors}
    if len(configs) > 1:
        errors = [e for e in errors if e.get("config", "elastic") != "rigid"]
    paths: list[Path] = []
    for ref in sorted({e["reference"] for e in errors}):
        sel = [e for e in errors if e["reference"] == ref]
        qs = [q for q in ("a", "r_a", "r_b", "p", "delta") if any(e["quantity"] == q for e in sel)]
        Es = sorted({round(e["E"], 9) for e in sel})
        Hs = sorted({round(e["H"], 9) for e in sel})
        if len(Es) < 2 or len(Hs) < 2:
            continue
        vmax = max(abs(e["err"]) for e in sel) or 1.0
        # one colour scale for every panel (vmax over all): one colour bar, in a slim last column;
        # one E axis: labelled on the first panel
        fig, axes = plt.subplots(1, len(qs) + 1, figsize=(3.1 * len(qs) + 0.9, 3.3), squeeze=False,
                                 gridspec_kw={"width_ratios": [1.0] * len(qs) + [0.06]})
        for ax in axes[0, 1:-1]:
            ax.sharey(axes[0, 0])
        for j, q in enumerate(qs):
            Z = np.full((len(Es), len(Hs)), np.nan)
            for e in sel:
                if e["quantity"] != q:
                    continue
                i, k = Es.index(round(e["E"], 9)), Hs.index(round(e["H"], 9))
                if not math.isfinite(Z[i, k]) or abs(e["err"]) > abs(Z[i, k]):
                    Z[i, k] = e["err"]
            ax = axes[0, j]
            # missing cells: hatched grey (white means 0 % on this diverging scale); errors span
            # decades, so a symmetric-log scale linear below 0.1 % (docs/style-figures.md)
            ax.patch.set_facecolor("0.85")
            ax.patch.set_hatch("///")
            ax.patch.set_edgecolor("0.6")
            im = ax.pcolormesh(np.arange(len(Hs) + 1), np.arange(len(Es) + 1), Z, cmap="RdBu_r",
                               norm=SymLogNorm(min(0.1, vmax), vmin=-vmax, vmax=vmax, base=10),
                               shading="flat")
            if np.isnan(Z).any():
                ax.legend(handles=[Patch(facecolor="0.85", edgecolor="0.6", hatch="///",
                                         label="not computed")],
                          loc="upper center", bbox_to_anchor=(0.5, -0.32), fontsize=7, frameon=False)
            step_h = max(1, len(Hs) // 6)
            ax.set_xticks(np.arange(len(Hs))[::step_h] + 0.5, [f"{h:.2g}" for h in Hs[::step_h]], fontsize=7,
                          rotation=45)
            step_e = max(1, len(Es) // 8)
            ax.set_xlabel("H (eq 7)")
            if j == 0:
                ax.set_yticks(np.arange(len(Es))[::step_e] + 0.5, [f"{E:.3g}" for E in Es[::step_e]],
                              fontsize=7)
                ax.set_ylabel(r"E = $E_c^*/E_s^*$")
            else:
                ax.tick_params(axis="y", labelleft=False)
            ax.set_title(f"{QLABEL[q]}: max |err| {np.nanmax(np.abs(Z)):.2f} %", fontsize=9)
        cb = fig.colorbar(im, cax=axes[0, -1], label="error [%] (every panel)")
        cb.ax.tick_params(labelsize=7)
        ncase = len({e.get("case") for e in sel})
        fig.suptitle(f"{result.name}: paper's closed-form rule vs reference {ref.upper()}, "
                     f"{ncase} {'elastic-substrate ' if 'rigid' in configs else ''}cases on the (E, H) grid: "
                     "(predicted - reference)/reference, "
                     "symmetric-log scale", fontsize=10)
        fig.set_layout_engine("tight")  # laid out when drawn, in the render process
        paths += _save(fig, Path(outdir), f"{result.name}_errmap_{ref}")
    return paths


def pairwise_plot(result, outdir: str | Path, quantities: Sequence[str] | None = None) -> list[Path]:
    """Cross-checks: every other method's difference from the case's reference, per quantity."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    diffs = [d for d in result.crosscheck if quantities is None or d["quantity"] in quantities]
    if not diffs:
        return []
    qs = [q for q in ("a", "r_a", "r_b", "p", "delta") if any(d["quantity"] == q for d in diffs)]
    pairs = sorted({d["pair"] for d in diffs})
    use_h = all("H" in d and d["H"] > 0 for d in diffs)  # a log axis of H (H = 0: uncoated)
    fig, axes = plt.subplots(1, len(pairs), figsize=(4.4 * len(pairs), 3.4), squeeze=False)
    markers = dict(zip(qs, "os^vD", strict=False))
    colours = {q: f"C{i}" for i, q in enumerate(qs)}  # a quantity's colour in every panel
    for j, pair in enumerate(pairs):
        ax = axes[0, j]
        # without H the cases are categories: positions 0, 1, ... labelled with the case ids
        cases = list(dict.fromkeys(str(d["case"]) for d in diffs if d["pair"] == pair))
        for q in qs:
            sel = [d for d in diffs if d["pair"] == pair and d["quantity"] == q]
            if not sel:
                continue
            x = [d["H"] for d in sel] if use_h else [cases.index(str(d["case"])) for d in sel]
            ax.plot(x, [d["diff"] for d in sel], markers[q], ms=4, alpha=0.7, mfc="none", color=colours[q])
        if use_h:
            ax.set_xscale("log")
            # labels at 1, 2, 5 per decade in plain numbers; the default minor labels overlapped
            hs = [d["H"] for d in diffs if d["pair"] == pair]
            narrow = math.log10(max(hs) / min(hs)) < 2.0
            ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0) if narrow else (1.0,)))
            ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.tick_params(axis="x", labelsize=7)
            ax.set_xlabel("H (eq 7)")
        else:
            step = max(1, math.ceil(len(cases) / 20))
            few = len(cases) <= 6
            ax.set_xticks(range(0, len(cases), step), cases[::step], rotation=0 if few else 90,
                          fontsize=8 if few else 5.5)
            ax.set_xlim(-0.5, len(cases) - 0.5)
            ax.set_xlabel("case (categorical)")
        ax.axhline(0, color="k", lw=0.6)
        m, ref = pair.split(" vs ")
        ax.set_ylabel(f"{m} / {ref} - 1 [%]")
        ax.set_title(f"{pair} (reference)", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    # one legend for every panel (the same quantities, markers and colours), right of the last
    axes[0, -1].legend(handles=[Line2D([], [], ls="none", marker=markers[q], ms=4, alpha=0.7, mfc="none",
                                       color=colours[q], label=QLABEL[q]) for q in qs],
                       fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # off the data
    fig.suptitle(f"{result.name}: cross-checks, each method's difference from the case's reference "
                 "(the spread is the claims' numerical uncertainty)", fontsize=9)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    return _save(fig, Path(outdir), f"{result.name}_pairwise")
