r"""The Poisson check (Section 3): coating Poisson's ratio away from 0.3.

Configuration: rigid sphere, elastic substrate with :math:`\nu_s = 0.3`; coating
:math:`\nu_c = 0.15 + (i-1)\,0.03`, i = 1..6 (the copy's "0.3" step is a typo, docs/paper-notes.md),
modulus ratios E in {4, 1.25, 0.8, 0.25}, 101 values of H: 2424 cases. The alpha curves were
fitted at :math:`\nu_c = \nu_s = 0.3`; eq (17) carries :math:`\nu_c` through lambda and kappa.

Paper's claim: the absolute error of eqs (1), (17)-(19) stays *below 3 %*, the largest for
E = 0.25 and :math:`\nu_c = 0.15`.

The claim is also judged over the cases with nu_c != 0.3 alone (the nu_c = 0.3 cases are
fig-3 cases: their error is eq (19)'s at nu_c = 0.3, not a Poisson effect).

Resolutions (expensive methods, i.e. the FE, only where named): ``full`` 6 nu_c x 4 E x 101 H (FE on
4 cases); ``quick`` 3 nu_c x 4 E x 8 H (FE on
2 cases); ``tiny`` 2 nu_c x 2 E x 2 H.
"""

from __future__ import annotations

import math

import numpy as np

from coathertz import verification as C

NAME = "poisson"
TITLE = "Poisson check: nu_c from 0.15 to 0.30 (nu_s = 0.3), E in {4, 1.25, 0.8, 0.25}"
CLAIM = "Eqs (1), (17)-(19) predict the Poisson-check cases (2424 in the paper) within 3 % (Section 3)."
BOUND = 3.0
RATIOS = (4.0, 1.25, 0.8, 0.25)


def grid(resolution: str):
    C.check_resolution(resolution)
    if resolution == "full":
        nus = [round(0.15 + i * 0.03, 2) for i in range(6)]
        return nus, RATIOS, C.h_grid(0.01, 3.0, 101), {(0.15, 0.25, 0.3), (0.15, 0.25, 1.0),
                                                       (0.15, 4.0, 0.3), (0.15, 4.0, 1.0)}
    if resolution == "quick":
        return [0.15, 0.21, 0.3], RATIOS, C.h_grid(0.01, 3.0, 8), {(0.15, 0.25, 1.0)}
    return [0.15, 0.3], (0.25, 4.0), np.array([0.1, 1.0]), set()


def cases(resolution: str) -> list[C.StudyCase]:
    nus, Es, Hs, fem = grid(resolution)
    fem = {(nu, E, next(iter(C.nearest(Hs, [H])))) for nu, E, H in fem}
    out = []
    for nu_c in nus:
        for E in Es:
            for H in Hs:
                tier = "expensive" if (nu_c, E, round(float(H), 9)) in fem else "moderate"
                cid = f"nu_c={nu_c:g},E={E:g},H={H:.4g}"
                out.append(C.StudyCase(cid, C.elastic_case(E, float(H), nu_c, C.NU, cid),
                                       {"E": float(E), "H": float(H), "nu_c": nu_c, "nu_s": C.NU}, tier))
    return out


def analyse(result: C.StudyResult) -> None:
    result.claims.append(C.bound_claim(
        "poisson-max-err", "max |err| of eqs (1), (17)-(19) over the Poisson-check cases of this run", result,
        BOUND))
    result.claims.append(C.bound_claim(
        "poisson-max-err-nu-not-0.3", "max |err| of eqs (1), (17)-(19) over the cases with nu_c != 0.3 alone "
        "(the Poisson effect on its own)", result, BOUND, where=lambda e: not math.isclose(e["nu_c"], 0.3)))
    worst: dict[tuple[float, float], float] = {}
    for e in result.errors:
        k = (e["nu_c"], e["E"])
        worst[k] = max(worst.get(k, 0.0), abs(e["err"]))
    if worst:
        k = max(worst, key=worst.get)
        result.claims.append(C.Claim(
            "poisson-worst-combination", "(nu_c, E) with the largest error (paper: nu_c = 0.15, E = 0.25)",
            worst[k], "(observation)", None, "%", 0.05, f"nu_c = {k[0]:g}, E = {k[1]:g}",
            judged_against=C.judged_on(result, {e["case"] for e in result.errors})))


def plot(result: C.StudyResult, outdir) -> list:
    Es = sorted({e["E"] for e in result.errors})
    nus = sorted({e["nu_c"] for e in result.errors})
    fig, axes = C.figure(max(len(Es), 1), width=3.6, height=3.2, sharey=True)  # one error scale
    refs = sorted({e["reference"] for e in result.errors})
    for j, E in enumerate(Es):
        ax = axes[0, j]
        for i, nu in enumerate(nus):
            for ref in refs:
                pts: dict[float, float] = {}
                for e in result.errors:
                    if e["reference"] == ref and math.isclose(e["E"], E) and math.isclose(e["nu_c"], nu):
                        pts[e["H"]] = max(pts.get(e["H"], 0.0), abs(e["err"]))
                if pts:
                    x = sorted(pts)
                    style = {**C.method_style(ref, C.colour(i, len(nus))), "ls": "-", "lw": 1}
                    ax.plot(x, [pts[h] for h in x], label=rf"$\nu_c$ = {nu:g}" if ref == refs[0] else None,
                            **style)
        ax.axhline(BOUND, color="k", ls="--", lw=0.8, label="paper: 3 %")
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        if j == 0:
            ax.set_ylabel(r"max$_q$ |error| of eqs (1), (17)-(19) [%]")
        ax.set_title(f"E = {E:g}", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0, -1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # off the data
    fig.suptitle(r"Poisson check: $\nu_s = 0.3$; error over a, p, $\delta$ against each case's reference ("
                 + ", ".join(C.method_info(r).label for r in refs) + ")", fontsize=10)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    return C.save(fig, outdir, "poisson")
