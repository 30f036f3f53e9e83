"""Figures of an elastic-plastic load path: load-approach curve and plastic zone (PNG).

:func:`plot_load_approach` draws ``W(delta)`` with loading, unloading and reloading in their own
colours; :func:`plot_plastic_zone` draws contours of the equivalent plastic strain ``ep`` over
the r-z section (quadrature points of the final state; ``ep`` never decreases, so this is the
largest plastic strain of the path) with the coating/substrate interface drawn.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from coathertz.errors import CoatHertzError

PHASE_STYLE = {"loading": ("C0", "-"), "unloading": ("C3", "--"), "reloading": ("C2", ":")}


def plot_load_approach(result, path: str | Path, title: str = "") -> Path:
    """``W`` [N] against ``delta`` [um] per phase; the origin (unloaded body) is included."""
    import matplotlib.pyplot as plt

    c = result.curves
    W, d, ph = np.array(c["W"]), np.array(c["delta"]) * 1e6, np.array(c["phase"])
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    prev = (0.0, 0.0)
    for name, (col, ls) in PHASE_STYLE.items():
        sel = np.nonzero(ph == name)[0]
        if not sel.size:
            continue
        x, y = np.r_[prev[0], d[sel]], np.r_[prev[1], W[sel]]
        ax.plot(x, y, color=col, ls=ls, marker="o", ms=3, label=name)
        prev = (d[sel[-1]], W[sel[-1]])
    ax.set_xlabel("approach delta [um]")
    ax.set_ylabel("load W [N]")
    ax.set_title(title or "elastic-plastic FE: load-approach path")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", frameon=False)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)


def plot_plastic_zone(result, path: str | Path, title: str = "") -> Path:
    """Filled contours of ``ep`` over ``r`` [um] and depth [um] (final state), interface dashed."""
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    asm, states = result.assembler, result.state.states
    if asm is None or states is None:
        raise CoatHertzError("plot_plastic_zone needs the result of solve_plastic (model kept)")
    r = np.concatenate([asm.rq[els].ravel() for els, _ in asm.regions]) * 1e6
    z = np.concatenate([asm.zq[els].ravel() for els, _ in asm.regions]) * 1e6
    ep = np.concatenate([(st["ep"] if "ep" in st else np.zeros(asm.rq[els].shape)).ravel()
                         for (els, _), st in zip(asm.regions, states, strict=True)])
    zone = result.final["plastic_zone"]
    a_max = float(np.nanmax(np.r_[0.0, np.array(result.curves["a"], dtype=float)])) * 1e6
    r_win = max(1.5 * zone["zone_r"] * 1e6, 1.5 * a_max, 1e-3)
    z_win = max(1.5 * zone["zone_depth"] * 1e6, a_max, 1e-3)
    sel = (r <= r_win) & (z >= -z_win)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    if ep[sel].max(initial=0.0) > 0:
        levels = np.linspace(0.0, ep[sel].max(), 11)
        levels[0] = 1e-12 * levels[-1]  # below: elastic (white)
        cs = ax.tricontourf(Triangulation(r[sel], z[sel]), ep[sel], levels=levels, cmap="viridis")
        fig.colorbar(cs, ax=ax, label="equivalent plastic strain ep [-]")
    else:
        ax.text(0.5, 0.5, "no plastic point", transform=ax.transAxes, ha="center")
    h = result.meta.get("h", 0.0) * 1e6
    if h > 0:
        ax.axhline(-h, color="k", ls="--", lw=1.0, label=f"interface (h = {h:.4g} um)")
        ax.legend(loc="lower right", frameon=False)
    ax.set_xlim(0, r_win)
    ax.set_ylim(-z_win, 0)
    ax.set_aspect("equal")
    ax.set_xlabel("r [um]")
    ax.set_ylabel("z [um]")
    ax.set_title(title or "elastic-plastic FE: plastic zone (largest ep of the path)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return Path(path)
