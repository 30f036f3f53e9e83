r"""The refitted extended-Hertz rule against the exact method, next to the paper's rule.

Configurations (rigid indenter, :mod:`coathertz.fitalpha.sweep` cases):

* elastic substrate: E = Ec*/Es* and H = h/a0s over the paper's range (E in [1/4, 4],
  H in [0.01, 3]) and the extended one (E in [1/10, 10], H in [0.001, 10]); nu_c = nu_s = 0.3
  (``full`` adds nu_c = 0.15, 0.45);
* rigid substrate: H = h/a0c in [0.001, 10], nu_c in [0, 0.5];
* elliptical: Rx/Ry in {3, 10}, E in [1/4, 4], H in [0.01, 3] (FFT only: not axisymmetric);
* elastic indenter (config ``indenter``, :mod:`coathertz.closedform.refit.indenter`): a steel
  ball on coated steel (gamma = E_ref/Ec* = 1/(1 + E)), E in [1/4, 4], H in [0.01, 3].

The error of each rule is ``(predicted - exact)/exact`` in percent, against the highest-ranked
numerical method that solved the case (the exact axisymmetric method where registered, else
the FFT, whose contact radius carries ~0.3 % discretisation noise at n = 128).

Claims: refit max |error| <= 0.3 % on delta, a, p0 (circular, rigid or elastic indenter) and <= 1 % on
r_a, r_b, delta, p0 (elliptical). The paper's rule is reported on the same points.
Resolutions: ``tiny`` a handful of cases, ``quick`` ~60 (CI), ``full`` ~700.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from coathertz import verification as C
from coathertz.closedform.refit import load
from coathertz.closedform.refit import predict as refit_predict
from coathertz.fitalpha.sweep import Point, make_case

NAME = "refit"
#: ``verify`` runs this study early: its reference refinements and five figures keep the parent
#: busy for seconds while the workers solve the next studies' cases.
RUN_EARLY = True
TITLE = "Refitted alpha vs the paper's rule, against the exact method"
CLAIM = ("The refitted rule predicts delta, a, p0 within 0.3 % (circular, rigid indenter over E in "
         "[1/10, 10], H in [0.001, 10]; a steel ball over E in [1/4, 4], H in [0.01, 3]) and r_a, r_b, "
         "delta, p0 within 1 % (elliptical).")
QUANTITIES = ("a", "p", "delta")
BOUND_CIRC = 0.3
BOUND_ELL = 1.0
#: smallest |error| drawn on the log axes (an exact limit gives 0)
FLOOR = 1e-4
FIELDS = {"a": "a", "p": "p0", "delta": "delta", "r_a": "r_a", "r_b": "r_b"}


def grid(resolution: str) -> dict:
    C.check_resolution(resolution)
    if resolution == "full":
        return {"E": np.geomspace(0.1, 10, 9), "H": C.h_grid(0.001, 10, 25), "nu": (0.15, 0.3, 0.45),
                "rigid_H": C.h_grid(0.001, 10, 25), "rigid_nu": (0.0, 0.3, 0.45, 0.5),
                "ell_E": (0.25, 0.8, 1.25, 4.0), "ell_H": C.h_grid(0.01, 3, 8), "rho": (3.0, 10.0),
                "ind_E": (0.25, 0.5, 2.0, 4.0), "ind_H": C.h_grid(0.01, 3, 8)}
    if resolution == "quick":  # thin elastic coatings cost the exact method ~1 min: quick starts at 0.01
        return {"E": (0.1, 0.25, 3.0, 10.0), "H": C.h_grid(0.01, 10, 6), "nu": (0.3,),
                "rigid_H": C.h_grid(0.003, 10, 5), "rigid_nu": (0.3, 0.5),
                "ell_E": (0.25, 4.0), "ell_H": (0.1, 0.7), "rho": (10.0,),
                "ind_E": (0.25, 4.0), "ind_H": (0.03, 0.3, 1.0)}
    return {"E": (0.25, 4.0), "H": (0.1, 1.0), "nu": (0.3,), "rigid_H": (0.3,), "rigid_nu": (0.3,),
            "ell_E": (4.0,), "ell_H": (0.7,), "rho": (3.0,), "ind_E": (), "ind_H": ()}


def points(resolution: str) -> list[Point]:
    g = grid(resolution)
    pts = [Point("elastic", float(E), float(H), nu, 0.3) for nu in g["nu"] for E in g["E"] for H in g["H"]]
    pts += [Point("rigid", 1.0, float(H), nu) for nu in g["rigid_nu"] for H in g["rigid_H"]]
    pts += [Point("ellipse", float(E), float(H), rho=r) for r in g["rho"] for E in g["ell_E"]
            for H in g["ell_H"]]
    # a steel ball on coated steel: Ei* = Es*, so gamma = E_ref/Ec* = 1/(1 + E)
    pts += [Point("indenter", float(E), float(H), 0.3, 0.3, gamma=round(1.0 / (1.0 + E), 12))
            for E in g["ind_E"] for H in g["ind_H"]]
    return pts


def _params(p: Point) -> dict:
    paper_range = 0.25 - 1e-9 <= p.E <= 4 + 1e-9 and 0.01 - 1e-9 <= p.H <= 3 + 1e-9
    return {"config": p.config, "E": p.E, "H": p.H, "nu_c": p.nu_c, "nu_s": p.nu_s, "rho": p.rho,
            "gamma": p.gamma, "paper_range": bool(paper_range if p.config != "rigid" else 0.01 <= p.H <= 3)}


def _cid(p: Point) -> str:
    tail = f",gamma={p.gamma:.4g}" if p.config == "indenter" else ""
    return f"{p.config}:E={p.E:.4g},H={p.H:.4g},nu_c={p.nu_c:g},nu_s={p.nu_s:g},rho={p.rho:g}{tail}"


def _spot_checked(pts: list[Point]) -> set[Point]:
    """The circular points worth an expensive method too (FE spot check): per configuration and
    Poisson ratio, the middle of the H range at the largest modulus ratio."""
    out = set()
    groups: dict[tuple, list[Point]] = {}
    for p in pts:
        if p.config != "ellipse":
            groups.setdefault((p.config, p.nu_c), []).append(p)
    for g in groups.values():
        top = max(p.E for p in g)
        sel = sorted((p for p in g if p.E == top), key=lambda p: p.H)
        out.add(sel[len(sel) // 2])
    return out


def cases(resolution: str) -> list[C.StudyCase]:
    """Every point at tier ``moderate`` (closed form, exact method, FFT); a few circular points
    at ``expensive`` (FE spot check as well). Every reference is re-solved at its refined settings:
    the difference is the claims' numerical uncertainty."""
    pts = points(resolution)
    spot = _spot_checked(pts) if resolution != "tiny" else set()
    return [C.StudyCase(_cid(p), make_case(p), _params(p), tier="expensive" if p in spot else "moderate",
                        refine=True)
            for p in pts]


def analyse(result: C.StudyResult) -> None:
    rule = load()
    by_case: dict[str, dict[str, dict]] = {}
    for r in result.rows:
        by_case.setdefault(r["case"], {})[r["method"]] = r
    recs = []
    for cid, ms in by_case.items():
        ref = result.reference.get(cid)  # the arbiter: top-ranked method that solved the case
        if ref is None or C.CLOSED not in ms:
            continue
        row = ms[ref]
        p = Point(row["config"], row["E"], row["H"], row["nu_c"], row["nu_s"], row["rho"],
                  gamma=row.get("gamma", 1.0))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            pred, _ = refit_predict(make_case(p), rule, warn=False)
        qs = ("r_a", "r_b", "delta", "p") if p.config == "ellipse" else QUANTITIES
        for q in qs:
            f = FIELDS[q]
            exact = row[f]
            recs.append({"case": cid, "config": p.config, "E": p.E, "H": p.H, "nu_c": p.nu_c,
                         "rho": p.rho, "gamma": p.gamma, "paper_range": row["paper_range"], "quantity": q,
                         "reference": ref,
                         "paper": 100.0 * (ms[C.CLOSED][f] / exact - 1.0),
                         "refit": 100.0 * (getattr(pred, f) / exact - 1.0)})
    result.extra["refit_errors"] = recs
    # spot checks of the reference by the other numerical methods on the same circular cases
    others = sorted({m for ms in by_case.values() for m in ms} - {C.CLOSED})
    for cfg in ("elastic", "rigid", "indenter"):
        for m in others:
            d = {q: [] for q in QUANTITIES}
            refs = set()
            for cid, ms in by_case.items():
                ref = result.reference.get(cid)
                if ref and ref != m and m in ms and ms[ref]["config"] == cfg:
                    refs.add(ref)
                    for q in QUANTITIES:
                        d[q].append(abs(ms[m][FIELDS[q]] / ms[ref][FIELDS[q]] - 1) * 100)
            if d["a"]:
                v = {q: max(x) for q, x in d.items()}
                against = "/".join(sorted(refs)).upper()
                result.claims.append(C.Claim(
                    f"refit-{cfg}-{m}-vs-{against.lower()}",
                    f"{cfg}: {m.upper()} spot check of the reference ({against}), max |diff|",
                    max(v.values()), "(observation)", None, "%", 0.05,
                    f"{len(d['a'])} cases; " + ", ".join(f"{q} {x:.3g} %" for q, x in v.items())))
    result.extra["data_file"] = {k: rule.data["provenance"].get(k) for k in
                                 ("code_version", "circular_method", "sweep_sha256", "created_utc")}
    for cfg, bound in (("elastic", BOUND_CIRC), ("rigid", BOUND_CIRC), ("ellipse", BOUND_ELL),
                       ("indenter", BOUND_CIRC)):
        for rng, sel in (("paper range", True), ("extended range", None)):
            rs = [r for r in recs if r["config"] == cfg and (sel is None or r["paper_range"])]
            if not rs or (cfg == "indenter" and sel is None):  # the steel ball: the paper's range only
                continue
            ref = rs[0]["reference"]
            for rule_name in ("refit", "paper"):
                v = np.abs([r[rule_name] for r in rs])
                k = int(np.argmax(v))
                w = rs[k]
                detail = (f"{len({r['case'] for r in rs})} cases, p99 {np.percentile(v, 99):.3g} %; worst "
                          f"{w['quantity']} at E = {w['E']:.3g}, H = {w['H']:.3g}, nu_c = {w['nu_c']:g}"
                          + (f", Rx/Ry = {w['rho']:g}" if cfg == "ellipse" else "")
                          + f" ({w[rule_name]:+.2f} %)")
                u, src = C.uncertainty_for(result, {r["case"] for r in rs})
                holds, unsure = (C.judge("<", float(v.max()), bound, u) if rule_name == "refit"
                                 else (None, False))
                if rule_name == "refit" and ref == "fft" and cfg != "ellipse" and not holds:
                    detail += "; reference is the FFT (radius noise ~0.3 %): inconclusive on a"
                result.claims.append(C.Claim(
                    f"refit-{cfg}-{'paper' if sel else 'extended'}-{rule_name}-{ref}",
                    f"{cfg}, {rng}: max |err| of the {rule_name} rule against {ref.upper()}",
                    float(v.max()), f"<= {bound:g} %" if rule_name == "refit" else "(paper's rule, observed)",
                    holds, "%", 0.05, f"{detail}; reference uncertainty: {src}", uncertainty=u,
                    inconclusive=unsure))


def plot(result: C.StudyResult, outdir) -> list:
    recs = result.extra.get("refit_errors", [])
    paths: list = []
    el = [r for r in recs if r["config"] == "elastic" and math.isclose(r["nu_c"], 0.3)]
    if el:
        paths += _elastic_error_maps(el, outdir, result.uncertainty)
    panels = tuple(c for c in ("rigid", "ellipse", "indenter") if any(r["config"] == c for r in recs))
    other = [r for r in recs if r["config"] in panels]
    if other:
        fig, axes = C.figure(len(panels), 1, width=5.0, height=3.6)
        for j, cfg in enumerate(panels):
            ax = axes[0, j]
            for rule_name, mk in (("paper", "x"), ("refit", "o")):
                rs = [r for r in other if r["config"] == cfg]
                if rs:
                    ax.plot([r["H"] for r in rs], [max(abs(r[rule_name]), FLOOR) for r in rs], mk, ms=4,
                            label=rule_name)
            ax.axhline(BOUND_ELL if cfg == "ellipse" else BOUND_CIRC, color="k", lw=0.8, ls="--")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("H")
            ax.set_ylabel(f"|error| [%] (floored at {FLOOR:g} %)")
            ax.set_title(PANEL_TITLES[cfg], fontsize=9)
            ax.legend(fontsize=7)
        fig.set_layout_engine("tight")  # laid out when drawn, in the render process
        paths += C.save(fig, outdir, "refit_rigid_ellipse")
    return paths


#: Titles of the ``refit_rigid_ellipse`` panels (error of both rules against the study's reference).
PANEL_TITLES = {"rigid": "rigid substrate: a, delta, p0", "ellipse": "ellipse: r_a, r_b, delta, p0",
                "indenter": "steel ball on coated steel: a, delta, p0"}


#: How the refit figure names each rule (rows of ``refit_elastic``).
RULE_TITLES = {"paper": "paper's rule (eqs 17-19, Appendix A)", "refit": "refitted rule (--alpha-rule refit)"}
QUANTITY_LABELS = {"a": "a", "p": "$p_0$", "delta": r"$\delta$"}


def _elastic_error_maps(el: list[dict], outdir, uncertainty: dict | None = None) -> list:
    """``refit_elastic``: the error of each rule over the (H, E) cells of the elastic, nu = 0.3
    cases, one row per rule with its own symmetric-log colour scale (the paper's errors reach
    tens of percent, the refit's hundredths), each cell's value written in it, cells without a
    case hatched, the paper's fitted H range marked."""
    from matplotlib.colors import SymLogNorm
    from matplotlib.patches import Patch

    Hs = sorted({r["H"] for r in el})
    Es = sorted({r["E"] for r in el})
    refs = sorted({r["reference"] for r in el})
    # one (H, E) grid: the bottom row labels H, the first column E
    fig, axes = C.figure(len(QUANTITIES), 2, width=4.3, height=3.2, sharex=True, sharey=True)
    missing = False
    for i, rule_name in enumerate(("paper", "refit")):
        vmax = max(abs(r[rule_name]) for r in el) or 1.0
        norm = SymLogNorm(linthresh=min(0.01, vmax), vmin=-vmax, vmax=vmax, base=10)
        for j, q in enumerate(QUANTITIES):
            ax = axes[i, j]
            Z = np.full((len(Es), len(Hs)), np.nan)
            for r in el:
                if r["quantity"] == q:
                    Z[Es.index(r["E"]), Hs.index(r["H"])] = r[rule_name]
            missing |= bool(np.isnan(Z).any())
            ax.patch.set_facecolor("0.85")  # missing cells: hatched grey (white is 0 %)
            ax.patch.set_hatch("///")
            ax.patch.set_edgecolor("0.6")
            im = ax.pcolormesh(np.arange(len(Hs) + 1), np.arange(len(Es) + 1), Z, cmap="RdBu_r", norm=norm)
            for (e, h), v in np.ndenumerate(Z):
                if np.isfinite(v):
                    dark = abs(norm(v) - 0.5) > 0.3
                    ax.text(h + 0.5, e + 0.5, f"{v:.2g}", ha="center", va="center", fontsize=6,
                            color="white" if dark else "black")
            for k in range(1, len(Hs)):  # the ends of the paper's fitted H range [0.01, 3]
                if (Hs[k - 1] < 0.01 <= Hs[k]) or (Hs[k - 1] <= 3 < Hs[k]):
                    ax.axvline(k, color="k", lw=1.2, ls="--")
            ax.set_xticks(np.arange(len(Hs)) + 0.5, [f"{H:.2g}" for H in Hs], fontsize=7)
            ax.set_yticks(np.arange(len(Es)) + 0.5, [f"{E:g}" for E in Es], fontsize=7)
            if i == 1:
                ax.set_xlabel("H = h/a0s (dashed: end of the paper's range 0.01-3)", fontsize=7.5)
            if j == 0:
                ax.set_ylabel(f"{RULE_TITLES[rule_name].split(' (')[0]}\nE = Ec*/Es*", fontsize=8)
            finite = Z[np.isfinite(Z)]
            worst = float(np.max(np.abs(finite))) if finite.size else math.nan
            ax.set_title(f"{QUANTITY_LABELS[q]}: max |err| {worst:.3g} %", fontsize=8.5)
        cb = fig.colorbar(im, ax=list(axes[i]), fraction=0.025, pad=0.01)
        cb.set_label(f"error [%], {rule_name} (symmetric log)", fontsize=7.5)
        cb.ax.tick_params(labelsize=7)
    if missing:
        fig.legend(handles=[Patch(facecolor="0.85", edgecolor="0.6", hatch="///", label="no case")],
                   loc="lower left", fontsize=7, frameon=False)
    cases = {r["case"] for r in el}
    unc = [v for c in cases for v in (uncertainty or {}).get(c, {}).values() if math.isfinite(v)]
    unc_text = (f"; reference uncertainty <= {max(unc):.1g} %" if unc
                else "; reference uncertainty not estimated")
    fig.suptitle(f"Refit study, elastic substrate, nu_c = nu_s = 0.3 ({len(cases)} held-out cases): error of "
                 f"the paper's and the refitted alpha rule against {', '.join(refs).upper()}{unc_text}",
                 fontsize=9)
    fig.set_layout_engine("constrained")  # the colour bars beside their rows; laid out when drawn
    return C.save(fig, outdir, "refit_elastic")
