r"""Figure 5 and Appendix A: the representative alpha curves at E = 1/3 and E = 3.

Appendix A fits :math:`\alpha_a, \alpha_\delta, \alpha_p` at the modulus ratios E = 1/3 and 3
(elastic substrate, :math:`\nu_c = \nu_s = 0.3`) as piecewise polynomials in H. We compare them
with the alpha inverted from our numerical results (:mod:`fig4`) at the same E, report the
jumps of the printed pieces at their breakpoints (the paper says they need not join), and the
error in the predicted bars that the difference causes (what matters to a user).

Paper's claims: the curves represent the numerical alpha at E = 1/3 and 3; the pieces'
mismatch at H = 0.01 "hardly changes the predictions".

Cases: the fig-3 cases with E = 1/3 and E = 3 (shared through the result store).
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.alpha import CURVES, breakpoint_jumps

from . import _common as C
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
    inv = fig4.inverted(result.rows)
    result.extra["alpha"] = inv
    jumps = breakpoint_jumps()
    result.extra["jumps"] = jumps
    elastic = [j for j in jumps if j["curve"] in RATIOS]
    worst = max(elastic, key=lambda j: abs(j["jump"]) / max(abs(j["left"]), 1e-12))
    result.claims.append(C.Claim(
        "fig5-appA-jumps", "largest relative jump of an Appendix A piece at its breakpoint (E = 1/3, 3)",
        100 * abs(worst["jump"]) / abs(worst["left"]), "(observation: pieces need not join)", None, "%", 0.01,
        f"alpha_{worst['quantity']}({worst['curve']}) at H = {worst['H']:g}: {worst['left']:.4g} -> "
        f"{worst['right']:.4g}"))
    for ref in C.NUMERICAL:
        for label, E in RATIOS.items():
            for q in C.QUANTITIES:
                d = [x for x in inv if x["method"] == ref and x["quantity"] == q and math.isclose(x["E"], E)
                     and math.isfinite(x["alpha"])]
                if not d:
                    continue
                H = np.array([x["H"] for x in d])
                a_inv = np.array([x["alpha"] for x in d])
                a_fit = CURVES[(q, label)](H)
                rel = np.abs(a_fit / a_inv - 1) * 100
                k = int(np.argmax(rel))
                result.claims.append(C.Claim(
                    f"fig5-alpha-{q}-{label.replace('/', '_')}-{ref}",
                    f"alpha_{q}({label}) Appendix A vs inverted from {ref.upper()}: median |rel. diff|",
                    float(np.median(rel)), "(observation)", None, "%", 0.5,
                    f"{len(d)} H values; largest {rel[k]:.1f} % at H = {H[k]:.3g}"))
    # what the difference does to the prediction: the fig-3 errors at E = 1/3 and 3
    for ref in C.NUMERICAL:
        v, n, _ = C.max_abs(result.errors, ref)
        if n:
            result.claims.append(C.Claim(
                f"fig5-err-{ref}", f"max |err| of the prediction at E = 1/3 and 3 against {ref.upper()}",
                v, f"< {fig3.BOUND:g} %", bool(v < fig3.BOUND), "%", 0.05, f"{n} cases"))


def plot(result: C.StudyResult, outdir) -> list:
    inv = result.extra.get("alpha", [])
    fig, axes = C.figure(3, width=4.4, height=3.6)
    H_line = np.geomspace(0.01, 3.0, 400)
    colours = {"1/3": "tab:blue", "3": "tab:red"}
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        for label, E in RATIOS.items():
            ax.plot(H_line, CURVES[(q, label)](H_line), color=colours[label], lw=1.3,
                    label=f"Appendix A, E = {label}")
            for m in C.NUMERICAL:
                pts = sorted((x["H"], x["alpha"]) for x in inv
                             if x["method"] == m and x["quantity"] == q and math.isclose(x["E"], E))
                if pts:
                    x, y = np.array(pts).T
                    ax.plot(x, y, C.MARKERS[m], color=colours[label], ms=4 if m == "fft" else 7,
                            mfc="none" if m == "fem" else colours[label],
                            label=f"{m.upper()} inverted, E = {label}")
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        sym = r"\delta" if q == "delta" else q
        ax.set_ylabel(rf"$\alpha_{{{sym}}}$")
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Fig. 5: Appendix A alpha curves (lines) and alpha inverted from our results (markers)",
                 fontsize=10)
    fig.tight_layout()
    return C.save(fig, outdir, "fig5")
