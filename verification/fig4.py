r"""Figure 4 (Section 3): the parameter alpha inverted from each numerical fig-3 result.

For every numerical result (FFT, FE) of the fig-3 cases and each quantity q in {a, p, delta},
solve for the alpha with which eqs (1), (17), (18) reproduce the numerical bar
(:func:`coathertz.closedform.extended.invert_alpha`). Where no alpha in [1e-3, 1e3] reproduces it (the
numerical value lies outside the range eq (17) can represent, typically where the bar is
within discretisation error of 1 at thin coatings), the study reports the case instead.

Paper's claim: alpha depends on H and E "in a complicated way"; curves with Ec* > Es* share
one trend and curves with Ec* < Es* another. We report, per method, how many (case, quantity)
pairs admit an alpha, and how far the Appendix A alpha (eq 19, rule ``paper``) lies from the
inverted one (median relative difference), separately for E < 1 and E > 1.

Error bars: each bar is moved by its numerical uncertainty (the spread of the methods that
solved the case, else the study's largest spread for that quantity) and inverted again. At thin
coatings (H <= 0.02, shaded) the bars are within a few percent of 1, where eq (17) is nearly
flat in alpha: a tiny change of the bar moves alpha a lot (d alpha / d bar is large), which is
why the inverted alpha_a is large and scattered there; the claims say so.

E = 1 (coating = substrate) is left out: eq (17) then gives Es* for every alpha.

Cases: those of :mod:`~coathertz.verification.fig3` (shared through the result store, so nothing
is solved twice).
"""

from __future__ import annotations

import math

import numpy as np

from coathertz import verification as C
from coathertz.closedform.alpha import PAPER_RULE
from coathertz.closedform.extended import invert_alpha

from . import fig3

#: The report draws no error maps / pairwise plots here: they would repeat fig3's.
GENERIC_FIGURES = False
NAME = "fig4"
TITLE = "Figure 4: alpha inverted from each numerical result (fig-3 cases)"
CLAIM = "An alpha reproducing each numerical result exists; it depends on H and E (two trends, E<1, E>1)."
#: At and below this H the inversion is ill-conditioned (d alpha / d bar large): said in the claims.
THIN = 0.02


def cases(resolution: str) -> list[C.StudyCase]:
    return fig3.cases(resolution)


def bar_uncertainty(result: C.StudyResult, case: str, q: str) -> float:
    """Relative uncertainty (percent) of a bar: the case's cross-check spread, else the largest
    spread of the study for that quantity, else 0."""
    u = result.uncertainty.get(case, {}).get(q)
    if u is not None:
        return u
    vals = [v[q] for v in result.uncertainty.values() if q in v]
    return max(vals) if vals else 0.0


def inverted(result: C.StudyResult, rows: list[dict] | None = None, rigid: bool = False) -> list[dict]:
    """Inverted alpha of each numerical row and quantity (NaN where none exists), with the interval
    ``[alpha_lo, alpha_hi]`` obtained by inverting the bar moved by its uncertainty (+/-)."""
    out = []
    rows = result.rows if rows is None else rows
    num = [r for r in rows if r["method"] != C.CLOSED and not math.isclose(r.get("E", 0.0), 1.0)]
    if not num:
        return out
    H = np.array([r["H"] for r in num])
    E = np.array([r.get("E", 0.0) for r in num])
    nu_c = np.array([r.get("nu_c", C.NU) for r in num])
    nu_s = np.array([r.get("nu_s", C.NU) for r in num])
    for q in C.QUANTITIES:
        bar = np.array([r[f"{q}_bar"] for r in num])
        u = np.array([bar_uncertainty(result, r["case"], q) for r in num]) / 100.0
        res = [np.atleast_1d(invert_alpha(q, b, E, H, nu_c, nu_s, rigid_substrate=rigid))
               for b in (bar, bar * (1 - u), bar * (1 + u))]
        for k, r in enumerate(num):
            a, lo, hi = (float(x[k]) for x in res)
            lo, hi = min(lo, hi), max(lo, hi)
            out.append({"case": r["case"], "method": r["method"], "E": r.get("E", math.nan), "H": r["H"],
                        "quantity": q, "alpha": a, "alpha_lo": lo, "alpha_hi": hi,
                        "reference": result.reference.get(r["case"]) == r["method"]})
    return out


def rel_halfwidth(d: dict) -> float:
    """Half the alpha interval relative to alpha, percent (inf where the interval leaves the
    invertible range)."""
    if not all(math.isfinite(d[k]) for k in ("alpha", "alpha_lo", "alpha_hi")):
        return math.inf
    return 50.0 * (d["alpha_hi"] - d["alpha_lo"]) / d["alpha"]


def thin_note(d: list[dict]) -> str:
    """What the values at H <= THIN are worth."""
    thin = [x for x in d if x["H"] <= THIN]
    if not thin:
        return ""
    w = max(rel_halfwidth(x) for x in thin)
    return (f"; {C.plural(len(thin), 'value')} at H <= {THIN:g}, where the inversion is ill-conditioned: "
            f"alpha uncertain by up to {'unbounded' if not math.isfinite(w) else f'{w:.0f} %'} there")


def analyse(result: C.StudyResult) -> None:
    # E = 1: coating and substrate alike, eq (17) gives Es* for every alpha: nothing to invert
    inv = inverted(result)
    result.extra["alpha"] = inv
    sel = [d for d in inv if d["reference"]]
    on = C.judged_on(result, {d["case"] for d in sel})
    if not sel:
        result.claims.append(C.Claim("fig4-exists", "alpha exists", math.nan, "", None, "%", 0.5,
                                     "no numerical method ran"))
        return
    ok = [d for d in sel if math.isfinite(d["alpha"])]
    frac = 100.0 * len(ok) / len(sel)
    missing = sorted({(d["quantity"], round(d["E"], 3), round(d["H"], 3)) for d in sel
                      if not math.isfinite(d["alpha"])})
    detail = f"{len(ok)} of {len(sel)}"
    if missing:
        detail += "; none at (q, E, H): " + ", ".join(str(m) for m in missing[:8])
        detail += " ..." if len(missing) > 8 else ""
    result.claims.append(C.Claim("fig4-exists", "(case, quantity) pairs of the fig-3 cases for which an "
                                 "alpha "
                                 "exists", frac, "100 % (implied)", bool(frac == 100.0), "%", 0.5, detail,
                                 judged_against=on))
    for side, cond in (("E<1", lambda e: e < 1), ("E>1", lambda e: e > 1)):
        d = [x for x in ok if cond(x["E"])]
        if not d:
            continue
        app = np.array([float(PAPER_RULE.alpha(x["quantity"], x["E"], x["H"])) for x in d])
        rel = np.abs(app / np.array([x["alpha"] for x in d]) - 1.0) * 100
        widths = np.array([rel_halfwidth(x) for x in d])
        result.claims.append(C.Claim(
            f"fig4-appA-vs-inverted-{side}",
            f"median |alpha(eq 19, Appendix A) / alpha(inverted) - 1|, {side}",
            float(np.median(rel)), "(observation)", None, "%", 0.5,
            f"{C.plural(len(d), 'value')}; median alpha uncertainty {np.median(widths):.2g} %" + thin_note(d),
            float(np.median(widths)), judged_against=C.judged_on(result, {x["case"] for x in d})))


def plot(result: C.StudyResult, outdir) -> list:
    inv = result.extra.get("alpha", [])
    fig, axes = C.figure(3, width=4.4, height=3.6)
    Es = sorted({d["E"] for d in inv})
    methods = sorted({d["method"] for d in inv})
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        for i, E in enumerate(Es):
            col = C.colour(i, len(Es))
            for m in methods:
                pts = sorted((d["H"], d["alpha"], d["alpha_lo"], d["alpha_hi"]) for d in inv
                             if d["method"] == m and d["quantity"] == q and math.isclose(d["E"], E))
                if not pts:
                    continue
                x, y, lo, hi = (np.array(v) for v in zip(*pts, strict=True))
                lo = np.where(np.isfinite(lo), lo, y)
                hi = np.where(np.isfinite(hi), hi, y)
                ax.errorbar(x, y, yerr=[np.maximum(y - lo, 0), np.maximum(hi - y, 0)], elinewidth=0.7,
                            capsize=1.5, **C.method_style(m, col),
                            label=f"E = {E:.3g}" if m == methods[0] and len(Es) <= 8 else None)
        ax.axvspan(0.005, THIN, color="0.92", zorder=0)
        ax.set_xlim(0.008, 3.5)
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        ax.set_ylabel(rf"$\alpha_{{{q if q != 'delta' else chr(92) + 'delta'}}}$ (inverted)")
        ax.grid(alpha=0.3, which="both")
    if len(Es) <= 8:
        # below the panels, off the data (inside the first panel it covered the curves); an Axes
        # legend, so that the tight layout makes room for it (a figure legend fell outside)
        axes[0, 1].legend(*axes[0, 0].get_legend_handles_labels(), fontsize=7, loc="upper center",
                          bbox_to_anchor=(0.5, -0.2), ncol=3, frameon=False)
    axes[0, 2].legend(handles=C.method_handles(methods, closed_form_line=False), fontsize=7,
                      loc="upper left", bbox_to_anchor=(1.01, 1.0))  # off the alpha_delta data
    fig.suptitle("Fig. 4: alpha with which eqs (1), (17), (18) reproduce each numerical result; error bars "
                 "from the bars' uncertainty; grey: H <= 0.02, where a bar within a small fraction of 1 "
                 "makes "
                 "alpha ill-conditioned (large alpha_a)", fontsize=8.5)
    if len(Es) <= 8:
        fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    else:  # too many curves for a legend: a colour bar keyed by E, beside the laid-out panels
        import matplotlib as mpl

        fig.tight_layout()
        sm = mpl.cm.ScalarMappable(norm=mpl.colors.Normalize(0, len(Es) - 1), cmap="viridis")
        shown = (0.25, 1 / 3, 0.8, 1, 2, 3, 4)
        ticks = [i for i, E in enumerate(Es) if any(math.isclose(E, t) for t in shown)]
        cb = fig.colorbar(sm, ax=list(axes[0]), ticks=ticks, fraction=0.02, pad=0.01)
        cb.ax.set_yticklabels([f"{Es[i]:.3g}" for i in ticks])
        cb.set_label(r"$E = E_c^*/E_s^*$")
    return C.save(fig, outdir, "fig4")
