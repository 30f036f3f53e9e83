r"""Figure 5 and Appendix A: the representative alpha curves at E = 1/3 and E = 3.

Appendix A fits :math:`\alpha_a, \alpha_\delta, \alpha_p` at the modulus ratios E = 1/3 and 3
(elastic substrate, :math:`\nu_c = \nu_s = 0.3`) as piecewise polynomials in H. We compare them
with the alpha inverted from our numerical results (:mod:`~coathertz.verification.fig4`) at the
same E, report the jumps of the printed pieces at their breakpoints (the paper says they need not
join), and the error in the predicted bars that the difference causes (what matters to a user).

Paper's claims: the curves represent the numerical alpha at E = 1/3 and 3; the pieces'
mismatch at H = 0.01 "hardly changes the predictions".

Cases: the fig-3 cases with E = 1/3 and E = 3 (shared through the result store).
"""

from __future__ import annotations

import math

import numpy as np

from coathertz import verification as C
from coathertz.closedform.alpha import CURVES, breakpoint_jumps

from . import fig3, fig4

#: The report draws no error maps / pairwise plots here: they would repeat fig3's.
GENERIC_FIGURES = False
NAME = "fig5"
TITLE = "Figure 5 / Appendix A: representative alpha curves at E = 1/3 and 3 vs inverted alpha"
CLAIM = "Appendix A's curves represent alpha at E = 1/3 and 3; their breakpoint jumps hardly matter."
RATIOS = {"1/3": 1 / 3, "3": 3.0}


def cases(resolution: str) -> list[C.StudyCase]:
    return [sc for sc in fig3.cases(resolution)
            if any(math.isclose(sc.params["E"], v) for v in RATIOS.values())]


def analyse(result: C.StudyResult) -> None:
    inv = fig4.inverted(result)
    result.extra["alpha"] = inv
    jumps = breakpoint_jumps()
    result.extra["jumps"] = jumps
    elastic = [j for j in jumps if j["curve"] in RATIOS]
    worst = max(elastic, key=lambda j: abs(j["jump"]) / max(abs(j["left"]), 1e-12))
    result.claims.append(C.Claim(
        "fig5-appA-jumps", "largest relative jump of an Appendix A piece at its breakpoint (E = 1/3, 3)",
        100 * abs(worst["jump"]) / abs(worst["left"]), "(observation: pieces need not join)", None, "%", 0.01,
        f"alpha_{worst['quantity']}({worst['curve']}) at H = {worst['H']:g}: {worst['left']:.4g} -> "
        f"{worst['right']:.4g}", judged_against="Appendix A (no method)"))
    for label, E in RATIOS.items():
        for q in C.QUANTITIES:
            d = [x for x in inv if x["reference"] and x["quantity"] == q and math.isclose(x["E"], E)
                 and math.isfinite(x["alpha"])]
            if not d:
                continue
            H = np.array([x["H"] for x in d])
            a_inv = np.array([x["alpha"] for x in d])
            a_fit = CURVES[(q, label)](H)
            rel = np.abs(a_fit / a_inv - 1) * 100
            widths = np.array([fig4.rel_halfwidth(x) for x in d])
            inside = sum(1 for x, f in zip(d, a_fit, strict=True) if x["alpha_lo"] <= f <= x["alpha_hi"])
            k = int(np.argmax(rel))
            result.claims.append(C.Claim(
                f"fig5-alpha-{q}-{label.replace('/', '_')}",
                f"alpha_{q}({label}) Appendix A vs inverted: median |rel. diff|",
                float(np.median(rel)), "(observation)", None, "%", 0.5,
                f"{C.plural(len(d), 'H value')}; largest {rel[k]:.1f} % at H = {H[k]:.3g}; Appendix A "
                f"inside the "
                f"inverted alpha's error bar at {inside} of {len(d)}" + fig4.thin_note(d),
                float(np.median(widths)), judged_against=C.judged_on(result, {x["case"] for x in d})))
    # what the difference does to the prediction: the fig-3 errors at E = 1/3 and 3
    result.claims.append(C.bound_claim("fig5-err", "max |err| of the prediction at E = 1/3 and 3", result,
                                       fig3.BOUND))


def plot(result: C.StudyResult, outdir) -> list:
    inv = result.extra.get("alpha", [])
    fig, axes = C.figure(3, width=4.4, height=3.6)
    H_line = np.geomspace(0.01, 3.0, 400)
    colours = {"1/3": "tab:blue", "3": "tab:red"}
    methods = sorted({x["method"] for x in inv})
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        for label, E in RATIOS.items():
            ax.plot(H_line, CURVES[(q, label)](H_line), color=colours[label], lw=1.3,
                    label=f"Appendix A, E = {label}")
            for m in methods:
                pts = sorted((x["H"], x["alpha"], x["alpha_lo"], x["alpha_hi"]) for x in inv
                             if x["method"] == m and x["quantity"] == q and math.isclose(x["E"], E))
                if pts:
                    x, y, lo, hi = (np.array(v) for v in zip(*pts, strict=True))
                    lo = np.where(np.isfinite(lo), lo, y)
                    hi = np.where(np.isfinite(hi), hi, y)
                    ax.errorbar(x, y, yerr=[np.maximum(y - lo, 0), np.maximum(hi - y, 0)], elinewidth=0.7,
                                capsize=1.5, **C.method_style(m, colours[label]),
                                label=f"{C.method_info(m).label} inverted, E = {label}")
        ax.axvspan(0.005, fig4.THIN, color="0.92", zorder=0)
        ax.set_xlim(0.008, 3.5)
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        sym = r"\delta" if q == "delta" else q
        ax.set_ylabel(rf"$\alpha_{{{sym}}}$")
        ax.grid(alpha=0.3, which="both")
    # every panel draws the same series: one legend, right of the last panel (off the data)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    axes[0, -1].legend(handles, labels, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle("Fig. 5: Appendix A alpha curves (lines) and alpha inverted from our results (markers, "
                 "error "
                 "bars from the bars' uncertainty; grey: H <= 0.02, ill-conditioned)", fontsize=9)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    return C.save(fig, outdir, "fig5")
