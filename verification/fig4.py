r"""Figure 4 (Section 3): the parameter alpha inverted from each numerical fig-3 result.

For every numerical result (FFT, FE) of the fig-3 cases and each quantity q in {a, p, delta},
solve for the alpha with which eqs (1), (17), (18) reproduce the numerical bar
(:func:`coathertz.extended.invert_alpha`). Where no alpha in [1e-3, 1e3] reproduces it (the
numerical value lies outside the range eq (17) can represent, typically where the bar is
within discretisation error of 1 at thin coatings), the study reports the case instead.

Paper's claim: alpha depends on H and E "in a complicated way"; curves with Ec* > Es* share
one trend and curves with Ec* < Es* another. We report, per method, how many (case, quantity)
pairs admit an alpha, and how far the Appendix A alpha (eq 19, rule ``paper``) lies from the
inverted one (median relative difference), separately for E < 1 and E > 1.

E = 1 (coating = substrate) is left out: eq (17) then gives Es* for every alpha.

Cases: those of :mod:`fig3` (shared through the result store, so nothing is solved twice).
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.alpha import PAPER_RULE
from coathertz.extended import invert_alpha

from . import _common as C
from . import fig3

#: The report draws no error maps / pairwise plots here: they would repeat fig3's.
GENERIC_FIGURES = False
NAME = "fig4"
TITLE = "Figure 4: alpha inverted from each numerical result (fig-3 cases)"
CLAIM = "An alpha reproducing each numerical result exists; it depends on H and E (two trends, E<1, E>1)."


def cases(resolution: str) -> list[C.StudyCase]:
    return fig3.cases(resolution)


def inverted(rows: list[dict], rigid: bool = False) -> list[dict]:
    """Inverted alpha of each numerical row and quantity (NaN where none exists)."""
    out = []
    num = [r for r in rows if r["method"] in C.NUMERICAL]
    if not num:
        return out
    H = np.array([r["H"] for r in num])
    E = np.array([r.get("E", 1.0) for r in num])
    nu_c = np.array([r.get("nu_c", C.NU) for r in num])
    nu_s = np.array([r.get("nu_s", C.NU) for r in num])
    for q in C.QUANTITIES:
        bar = np.array([r[f"{q}_bar"] for r in num])
        alpha = np.atleast_1d(invert_alpha(q, bar, E, H, nu_c, nu_s, rigid_substrate=rigid))
        for r, a in zip(num, alpha, strict=True):
            out.append({"case": r["case"], "method": r["method"], "E": r.get("E", math.nan), "H": r["H"],
                        "quantity": q, "alpha": float(a)})
    return out


def analyse(result: C.StudyResult) -> None:
    # E = 1: coating and substrate alike, eq (17) gives Es* for every alpha: nothing to invert
    inv = inverted([r for r in result.rows if not math.isclose(r["E"], 1.0)])
    result.extra["alpha"] = inv
    for ref in C.NUMERICAL:
        sel = [d for d in inv if d["method"] == ref]
        if not sel:
            result.claims.append(C.Claim(f"fig4-exists-{ref}", f"alpha exists ({ref.upper()})", math.nan,
                                         "", None, "%", 0.5, "method not run"))
            continue
        ok = [d for d in sel if math.isfinite(d["alpha"])]
        frac = 100.0 * len(ok) / len(sel)
        missing = sorted({(d["quantity"], round(d["E"], 3), round(d["H"], 3)) for d in sel
                          if not math.isfinite(d["alpha"])})
        detail = f"{len(ok)} of {len(sel)}"
        if missing:
            detail += "; none at (q, E, H): " + ", ".join(str(m) for m in missing[:8])
            detail += " ..." if len(missing) > 8 else ""
        result.claims.append(C.Claim(f"fig4-exists-{ref}",
                                     f"(case, quantity) pairs for which an alpha exists ({ref.upper()})",
                                     frac, "100 % (implied)", bool(frac == 100.0), "%", 0.5, detail))
        for side, cond in (("E<1", lambda e: e < 1), ("E>1", lambda e: e > 1)):
            d = [x for x in ok if cond(x["E"])]
            if not d:
                continue
            app = np.array([float(PAPER_RULE.alpha(x["quantity"], x["E"], x["H"])) for x in d])
            rel = np.abs(app / np.array([x["alpha"] for x in d]) - 1.0) * 100
            result.claims.append(C.Claim(
                f"fig4-appA-vs-inverted-{side}-{ref}",
                f"median |alpha(eq 19, Appendix A) / alpha(inverted) - 1|, {side} ({ref.upper()})",
                float(np.median(rel)), "(observation)", None, "%", 0.5, f"{len(d)} values"))


def plot(result: C.StudyResult, outdir) -> list:
    inv = result.extra.get("alpha", [])
    fig, axes = C.figure(3, width=4.4, height=3.6)
    Es = sorted({d["E"] for d in inv})
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        for i, E in enumerate(Es):
            col = C.colour(i, len(Es))
            for m in C.NUMERICAL:
                pts = sorted((d["H"], d["alpha"]) for d in inv
                             if d["method"] == m and d["quantity"] == q and math.isclose(d["E"], E))
                if not pts:
                    continue
                x, y = np.array(pts).T
                ax.plot(x, y, C.MARKERS[m] + ("-" if m == "fft" else ""), color=col,
                        ms=3.5 if m == "fft" else 7, lw=0.8, mfc="none" if m == "fem" else col,
                        label=f"E = {E:.3g}" if m == "fft" and len(Es) <= 8 else None)
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        ax.set_ylabel(rf"$\alpha_{{{q if q != 'delta' else chr(92) + 'delta'}}}$ (inverted)")
        ax.grid(alpha=0.3, which="both")
    if len(Es) <= 8:
        axes[0, 0].legend(fontsize=7, ncol=2, title="FFT (o), FE (□)", title_fontsize=7)
    fig.suptitle("Fig. 4: alpha with which eqs (1), (17), (18) reproduce each numerical result", fontsize=10)
    fig.tight_layout()
    if len(Es) > 8:  # too many curves for a legend: a colour bar keyed by E (FFT o, FE □)
        import matplotlib as mpl

        sm = mpl.cm.ScalarMappable(norm=mpl.colors.Normalize(0, len(Es) - 1), cmap="viridis")
        shown = (0.25, 1 / 3, 0.8, 1, 2, 3, 4)
        ticks = [i for i, E in enumerate(Es) if any(math.isclose(E, t) for t in shown)]
        cb = fig.colorbar(sm, ax=list(axes[0]), ticks=ticks, fraction=0.02, pad=0.01)
        cb.ax.set_yticklabels([f"{Es[i]:.3g}" for i in ticks])
        cb.set_label(r"$E = E_c^*/E_s^*$ (FFT o, FE □)")
    return C.save(fig, outdir, "fig4")
