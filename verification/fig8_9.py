r"""Figures 8 and 9 (Section 4): rigid substrate, 13 coating moduli collapse on one curve; alpha.

Configuration: rigid sphere, coating (:math:`\nu_c = 0.3`, 13 moduli Ec from 50 to 800 GPa,
evenly spaced) bonded to a rigid substrate (the paper: Es > 1e4 Ec; we take the substrate
rigid, mu = 0 in eq 13); bars are ratios to the coating-half-space Hertz values (eq 7b),
:math:`H = h/a_{0c}`.

Paper's claims: the bars are *independent of Ec* and fall on one curve (fig 8); with the
representative alpha curves of figure 9 (Appendix A, rigid substrate) eqs (1), (17), (18)
predict every case *within 1 %*. We also invert alpha from each numerical result (fig 9).

Resolutions: ``full`` 13 Ec x 101 H (FE at the Ec nearest 200 GPa, 3 H); ``quick`` 3 Ec x 10 H
(FE at 200 GPa, 2 H); ``tiny`` 2 Ec x 2 H.
"""

from __future__ import annotations

import math

import numpy as np

from coathertz.alpha import CURVES
from coathertz.extended import invert_alpha, predict_bar

from . import _common as C

NAME = "fig8_9"
TITLE = "Figures 8 and 9: rigid substrate, 13 coating moduli; collapse and alpha"
CLAIM = ("Bars are independent of Ec; the rigid-substrate alpha curves predict every case within 1 % "
         "(Section 4).")
BOUND = 1.0


def grid(resolution: str):
    C.check_resolution(resolution)
    if resolution == "full":
        return list(np.linspace(50e9, 800e9, 13)), C.h_grid(0.01, 3.0, 101), {0.1, 0.3, 1.0}
    if resolution == "quick":
        return [50e9, 200e9, 800e9], C.h_grid(0.01, 3.0, 10), {0.3, 1.0}
    return [50e9, 800e9], np.array([0.1, 1.0]), set()


def cases(resolution: str) -> list[C.StudyCase]:
    Ecs, Hs, fem = grid(resolution)
    fem = C.nearest(Hs, sorted(fem)) if fem else set()
    ec_fem = min(Ecs, key=lambda e: abs(e - 200e9))  # FE at the modulus nearest 200 GPa (steel, fig 9)
    out = []
    for Ec in Ecs:
        for H in Hs:
            m = C.ALL if (Ec == ec_fem and round(float(H), 9) in fem) else C.CF_FFT
            cid = f"Ec={Ec / 1e9:g}GPa,H={H:.4g}"
            out.append(C.StudyCase(cid, C.rigid_substrate_case(Ec, float(H), C.NU, cid),
                                   {"Ec_GPa": Ec / 1e9, "H": float(H), "nu_c": C.NU}, m))
    return out


def analyse(result: C.StudyResult) -> None:
    for ref in C.NUMERICAL:
        rows = result.rows_of(ref)
        if not rows:
            continue
        spread = 0.0
        for H in {r["H"] for r in rows}:
            for q in C.QUANTITIES:
                v = [r[f"{q}_bar"] for r in rows if r["H"] == H]
                if len(v) > 1:
                    spread = max(spread, 100 * (max(v) - min(v)) / np.mean(v))
        n_ec = len({r["Ec_GPa"] for r in rows})
        result.claims.append(C.Claim(
            f"fig8-collapse-{ref}", f"largest spread of the bars across {n_ec} coating moduli at equal H "
            f"({ref.upper()})", spread, "independent of Ec (taken as < 0.1 %)", bool(spread < 0.1), "%", 0.05,
            f"{len(rows)} cases"))
        result.claims.append(C.bound_claim(
            "fig8-max-err", "max |err| of eqs (1), (17), (18) with the rigid-substrate alpha curves",
            result.errors, ref, BOUND))
    inv = []
    for r in result.rows:
        if r["method"] not in C.NUMERICAL:
            continue
        for q in C.QUANTITIES:
            a = invert_alpha(q, r[f"{q}_bar"], 0.0, r["H"], C.NU, C.NU, rigid_substrate=True)
            inv.append({"case": r["case"], "method": r["method"], "Ec_GPa": r["Ec_GPa"], "H": r["H"],
                        "quantity": q, "alpha": float(a)})
    result.extra["alpha"] = inv
    for ref in C.NUMERICAL:
        for q in C.QUANTITIES:
            d = [x for x in inv if x["method"] == ref and x["quantity"] == q and math.isfinite(x["alpha"])]
            if not d:
                continue
            H = np.array([x["H"] for x in d])
            rel = np.abs(CURVES[(q, "rigid")](H) / np.array([x["alpha"] for x in d]) - 1) * 100
            k = int(np.argmax(rel))
            n_all = len([x for x in inv if x["method"] == ref and x["quantity"] == q])
            result.claims.append(C.Claim(
                f"fig9-alpha-{q}-{ref}", f"fig 9: alpha_{q} (Appendix A, rigid) vs inverted from "
                f"{ref.upper()}: median |rel. diff|", float(np.median(rel)), "(observation)", None, "%", 0.5,
                f"{len(d)} of {n_all} invertible; largest {rel[k]:.1f} % at H = {H[k]:.3g}"))


def plot(result: C.StudyResult, outdir) -> list:
    paths = []
    fig, axes = C.figure(3, width=4.4, height=3.6)
    Ecs = sorted({r["Ec_GPa"] for r in result.rows})
    H_line = np.geomspace(0.01, 3.0, 300)
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        ax.plot(H_line, predict_bar(q, 0.0, H_line, rigid_substrate=True, warn=False), "k-", lw=1.3,
                label="eqs (1), (17), (18), rigid alpha")
        for i, Ec in enumerate(Ecs):
            for m in C.NUMERICAL:
                x, y = C.series(result.rows, m, "Ec_GPa", Ec, "H", f"{q}_bar")
                if len(x):
                    ax.plot(x, y, C.MARKERS[m], color=C.colour(i, len(Ecs)), ms=4 if m == "fft" else 8,
                            mfc="none" if m == "fem" else C.colour(i, len(Ecs)),
                            label=f"{m.upper()}, Ec = {Ec:g} GPa")
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0c}$")
        ax.set_ylabel(C.SYMBOL[q] + {"a": r" $= a/a_{0c}$", "p": r" $= p_0/p_{0c}$",
                                     "delta": r" $= \delta/\delta_{0c}$"}[q])
        ax.grid(alpha=0.3, which="both")
    axes[0, 1].legend(fontsize=6.5)
    fig.suptitle(r"Fig. 8: rigid substrate, $\nu_c = 0.3$; bars against H for several coating moduli",
                 fontsize=10)
    fig.tight_layout()
    paths += C.save(fig, outdir, "fig8")
    inv = result.extra.get("alpha", [])
    fig, axes = C.figure(3, width=4.4, height=3.6)
    for j, q in enumerate(C.QUANTITIES):
        ax = axes[0, j]
        ax.plot(H_line, CURVES[(q, "rigid")](H_line), "k-", lw=1.3, label="Appendix A (fig 9)")
        for m in C.NUMERICAL:
            pts = sorted((x["H"], x["alpha"]) for x in inv if x["method"] == m and x["quantity"] == q)
            if pts:
                x, y = np.array(pts).T
                ax.plot(x, y, C.MARKERS[m], ms=4 if m == "fft" else 8, mfc="none" if m == "fem" else None,
                        label=f"inverted from {m.upper()}")
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0c}$")
        sym = r"\delta" if q == "delta" else q
        ax.set_ylabel(rf"$\alpha_{{{sym}}}$")
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Fig. 9: rigid-substrate alpha curves and alpha inverted from our results", fontsize=10)
    fig.tight_layout()
    paths += C.save(fig, outdir, "fig9")
    return paths
