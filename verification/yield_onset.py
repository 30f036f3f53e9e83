r"""Yield onset of coated half-spaces under a rigid sphere: load of first yield and where it occurs.

Not a figure of the paper: an extension. For each coating (modulus ratio
:math:`E = E_c^*/E_s^*`, thickness :math:`H = h/a_{ys}`, yield-stress ratio :math:`Y_c/Y_s`) the
elastic FE solution gives the load :math:`W_y` at which the von Mises stress first reaches the
yield stress of the coating or of the substrate, and where
(:func:`coathertz.fem.plastic.onset.yield_onset`). Normalisation: :math:`W_{ys}` and
:math:`a_{ys}` are the first-yield load and the Hertz contact radius of the uncoated substrate
(:math:`p_0 = 1.61\, Y_s` for :math:`\nu = 0.3`, Johnson 1985, Section 6.2), so
:math:`W_y/W_{ys} < 1` means the coating makes the system yield earlier. Substrate: steel,
:math:`E_s = 200` GPa, :math:`\nu = 0.3`, :math:`Y_s = 1` GPa; coatings :math:`\nu_c = 0.3`;
rigid sphere :math:`R = 10` mm.

Claims checked: the homogeneous limit (first yield at p0 = 1.60 Y, z = 0.48 a, Johnson; judged
against the unrounded Hertz axis values of :func:`~coathertz.fem.plastic.onset.hertz_axis_onset`)
within 1 % (p0) and 3 % (depth, coarse mesh); the map itself is reported as an observation.
Each claim carries a mesh uncertainty: the homogeneous case and the map's worst case are solved
again with twice the elements across a (``mesh_uncertainty``).

Location classes: ``coating`` (inside the coating, including its surface), ``interface`` (on
the interface, either side, within 5 % of h), ``substrate``.

The FE solves do not go through the method registry and the result store (they are not
``ContactResult`` rows): ``analyse`` runs them itself, so the study relies only on
:class:`coathertz.verification.StudyCase`, ``Claim``, ``StudyResult``, ``figure`` and
``save``. Resolutions: ``tiny`` 2 cases (tests), ``quick`` 5 cases (E = 1/4 and 4 at H = 0.3,
Yc/Ys = 1 and 3) at 12 elements across a (~3 s CPU in one process: 2-4 solves per search to
``ONSET_TOL``), ``full``
5 E x 6 H x 3 Yc/Ys = 90 cases at 20 elements across a.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import replace
from typing import Any

import numpy as np

from coathertz import verification as C
from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.materials import Material
from coathertz.verification.study import fork_pool

NAME = "yield_onset"
TITLE = "Yield onset: load of first yield (normalised by the uncoated substrate's) and its location"
CLAIM = ("Extension (not in the paper): homogeneous limit p0 = 1.60 Y at z = 0.48 a (Johnson); map of "
         "W_y/W_ys and of where first yield occurs over E in [1/4, 4], H in [0.01, 3], Yc/Ys.")
R = 10e-3
ES, NU, YS = 200e9, 0.3, 1e9
CLASSES = ("coating", "interface", "substrate")
JUDGED = "the Hertz axis stresses (closed form), FE onset search"
#: (claim id, key, what, Johnson's rounded value, bound [%], bound text, regression tolerance [%])
HOMOGENEOUS_CLAIMS = (
    ("yield-onset-homogeneous-p0", "p0_over_Y", "p0/Y at first yield", "1.60", 1.0, "< 1 %", 0.05),
    ("yield-onset-homogeneous-z", "z_over_a", "depth of first yield z/a", "0.48", 3.0,
     "< 3 % (coarse mesh; the location converges at first order)", 0.5),
)
COLOURS = {"coating": "tab:red", "interface": "tab:purple", "substrate": "tab:blue"}


def substrate_reference() -> tuple[float, float]:
    """``(W_ys, a_ys)``: first-yield load and Hertz radius of the uncoated substrate."""
    from coathertz.fem.plastic.onset import hertz_axis_onset

    p0y, _ = hertz_axis_onset(NU)
    Es_star = Material(ES, NU).E_star
    W = (p0y * YS) ** 3 * math.pi**3 * R**2 / (6.0 * Es_star**2)  # Johnson eq 4.23 inverted
    return W, float(hertz_circular(W, R, Es_star).a0)


def grid(resolution: str) -> tuple[list[float], list[float], list[float]]:
    C.check_resolution(resolution)
    if resolution == "full":
        return [0.25, 0.5, 1.0, 2.0, 4.0], [0.01, 0.03, 0.1, 0.3, 1.0, 3.0], [1.0, 2.0, 4.0]
    if resolution == "quick":
        return [0.25, 4.0], [0.3], [1.0, 3.0]
    return [4.0], [1.0], [1.0]


def fem_settings(resolution: str) -> dict:
    """Elastic FE mesh of the onset solves: 12 elements across a (tiny/quick), 20 (full)."""
    return {"mesh": "coarse", "n_a": 12 if resolution in ("tiny", "quick") else 20}


def refined_fem_settings(resolution: str) -> dict:
    """The mesh of the uncertainty estimate: twice the elements across a of :func:`fem_settings`."""
    s = fem_settings(resolution)
    return {**s, "n_a": 2 * s["n_a"]}


def cases(resolution: str) -> list[C.StudyCase]:
    """The homogeneous reference plus the (E, H, Yc/Ys) grid. The registered methods solve the
    elastic contact at W_ys as well (every method on the homogeneous case, the cheap ones on the
    grid): a cross-check of the elastic state the onset is computed from."""
    Es_star = Material(ES, NU).E_star
    W_ys, a_ys = substrate_reference()
    out = [C.StudyCase("homogeneous", ContactCase.sphere_on_coated_half_space(
        R, W_ys, Material(ES, NU), 0.0, Material(ES, NU), label="homogeneous"),
        {"E": 1.0, "H": 0.0, "Yc_Ys": 1.0}, tier="expensive")]
    if resolution == "tiny":
        out = out[:1]
    Es_, Hs, ratios = grid(resolution)
    for E in Es_:
        coat = Material(E * Es_star * (1.0 - NU**2), NU)
        for H in Hs:
            for q in ratios:
                cid = f"E={E:g},H={H:g},Yc/Ys={q:g}"
                case = ContactCase.sphere_on_coated_half_space(R, W_ys, coat, H * a_ys, Material(ES, NU),
                                                               label=cid)
                out.append(C.StudyCase(cid, case, {"E": E, "H": H, "Yc_Ys": q}, tier="cheap"))
    return out


def analyse(result: C.StudyResult) -> None:
    from coathertz.fem.plastic.onset import hertz_axis_onset

    W_ys, a_ys = substrate_reference()
    settings = fem_settings(result.resolution)
    refined = refined_fem_settings(result.resolution)
    rows, t0 = [], time.perf_counter()
    by_id = {sc.id: sc for sc in cases(result.resolution)}
    # every onset search is independent: the map and the homogeneous case's refined re-solve run
    # side by side on the run's worker processes; the searches of one elastic problem (the same
    # E, H and mesh, other yield stresses) run as one job, sharing their solves
    hom_id = next((i for i in by_id if by_id[i].params["H"] == 0), None)
    # (the refined re-solve, the longest, first)
    jobs = ([(by_id[hom_id], refined)] if hom_id else []) + [(sc, settings) for sc in by_id.values()]
    groups = _groups(jobs)
    with fork_pool(_onset_job, len(groups), result.workers) as submit:
        pending = [submit([jobs[i] for i in g]) for g in groups]
        done: list = [None] * len(jobs)
        for g, f in list(zip(groups, pending, strict=True))[1 if hom_id else 0:]:
            for i, o in zip(g, _each(f.result(), len(g)), strict=True):
                done[i] = o
        solved = done[1:] if hom_id else done
        # the worst coated case's refined re-solve starts as soon as the map is known, beside the
        # homogeneous case's (still running): not after it, alone, in this process
        worst_fine = _worst_refined(by_id, solved, refined, W_ys, submit)
        fine = {hom_id: _each(pending[0].result(), 1)[0]} if hom_id else {}
        worst_fine = _each(worst_fine.result(), 1)[0] if worst_fine is not None else None
    for sc, o in zip(by_id.values(), solved, strict=True):
        p = sc.params
        if isinstance(o, Exception):  # reported, not fatal: one case must not sink the map
            result.failures.append({"case": sc.id, **p, "method": "fem-onset", "error": repr(o)})
            continue
        rows.append({"case": sc.id, **p, "W_y": o.W_y, "W_bar": o.W_y / W_ys, "p0_over_Y": o.p0_over_Y,
                     "where": o.where, "region": o.region, "r_over_a": o.r / o.a_y, "z_over_a": -o.z / o.a_y,
                     "depth_over_h": (-o.z / sc.case.body2.coating.h) if p["H"] > 0 else math.nan,
                     "a_y": o.a_y, "solves": o.solves})
    result.extra["onset"] = rows
    result.extra["W_ys"], result.extra["a_ys"] = W_ys, a_ys
    result.extra["fem_settings"] = fem_settings(result.resolution)
    result.methods = [*result.methods, "fem-onset"]
    result.computed += len(rows)
    p0_cf, z_cf = hertz_axis_onset(NU)
    result.extra["fem_settings_refined"] = refined
    hom = [r for r in rows if r["case"] == "homogeneous"]
    if hom:
        h = hom[0]
        u = mesh_uncertainty(by_id[h["case"]], h, refined, ("p0_over_Y", "z_over_a"), fine.get(h["case"]))
        result.extra["uncertainty"] = {"homogeneous": u}
        n_a = fem_settings(result.resolution)["n_a"]
        exact = {"p0_over_Y": p0_cf, "z_over_a": z_cf}
        details = {
            "p0_over_Y": f"FE p0/Y = {h['p0_over_Y']:.4f}, {n_a} elements across a; at {refined['n_a']}: "
                         f"{u['refined']['p0_over_Y']:.4f}",
            "z_over_a": f"FE z/a = {h['z_over_a']:.4f}, r/a = {h['r_over_a']:.3f}; "
                        f"at {refined['n_a']} elements across a: z/a = {u['refined']['z_over_a']:.4f}",
        }
        for cid, key, what, johnson, bound, bound_text, tol in HOMOGENEOUS_CLAIMS:
            err = 100 * abs(h[key] / exact[key] - 1)
            unc = 100 * u[key] / exact[key]
            holds, inconclusive = C.judge("<", err, bound, unc)
            result.claims.append(C.Claim(
                cid, f"homogeneous half-space: {what} vs the Hertz axis value {exact[key]:.4f} "
                f"(Johnson: {johnson})", err, bound_text, holds, "%", tol, details[key],
                uncertainty=unc, inconclusive=inconclusive, judged_against=JUDGED))
    coated = [r for r in rows if r["H"] > 0]
    if coated:
        counts = {c: sum(r["where"] == c for r in coated) for c in CLASSES}
        worst = min(coated, key=lambda r: r["W_bar"])
        u = mesh_uncertainty(by_id[worst["case"]], worst, refined, ("W_bar",), worst_fine)
        result.extra.setdefault("uncertainty", {})[worst["case"]] = u
        result.claims.append(C.Claim(
            "yield-onset-map", "coated cases: smallest W_y/W_ys (observation)", worst["W_bar"],
            "(observation)", None, "", 0.05,
            f"at {worst['case']} ({worst['where']}; at {refined['n_a']} elements across a: "
            f"{u['refined']['W_bar']:.4f}, {u['refined']['where']}); first yield in coating / "
            f"interface / substrate: {counts['coating']} / {counts['interface']} / {counts['substrate']} "
            f"of {len(coated)}",
            uncertainty=u["W_bar"], judged_against=f"{JUDGED}; {worst['case']}"))
    result.method_time["fem-onset"] = time.perf_counter() - t0  # the refined re-solves included


def mesh_uncertainty(sc: C.StudyCase, row: dict, refined: dict, keys: tuple[str, ...],
                     onset: Any = None) -> dict:
    """Numerical uncertainty of ``row[key]`` from the onset re-solved at ``refined`` FE settings
    (``onset``: that re-solve where it was already done).

    ``2 |v_n - v_2n|``: the Richardson estimate of the error of ``v_n`` for first-order
    convergence (the location of the maximum von Mises stress, sampled at quadrature points,
    converges at first order; p0 and W_y converge faster, so the estimate is conservative
    there). The refined values are returned under ``"refined"``.
    """
    o = onset if onset is not None and not isinstance(onset, Exception) else _onset(sc, refined)
    W_ys, _ = substrate_reference()
    fine = {"p0_over_Y": o.p0_over_Y, "z_over_a": -o.z / o.a_y, "W_bar": o.W_y / W_ys, "where": o.where}
    out: dict = {k: 2.0 * abs(fine[k] - row[k]) for k in keys}
    out["refined"] = fine
    return out


def _worst_refined(by_id: dict, solved: list, refined: dict, W_ys: float, submit):
    """Submit the refined re-solve of the coated case with the smallest ``W_y / W_ys`` (the one
    the map's claim quotes, chosen as :func:`analyse` chooses it); None without such a case.
    Its search starts at the coarser mesh's ``W_y`` (not at ``W_ys``), its first mesh built around
    the coarser mesh's contact radius there: the same criterion
    (:func:`~coathertz.fem.plastic.onset.yield_onset`), two or three solves fewer."""
    coated = [(o.W_y / W_ys, sc, o) for sc, o in zip(by_id.values(), solved, strict=True)
              if not isinstance(o, Exception) and sc.params["H"] > 0]
    if not coated:
        return None
    _, sc, o = min(coated, key=lambda t: t[0])
    return submit([(replace(sc, case=replace(sc.case, W=o.W_y)), refined, o.a_y)])


def _groups(jobs: list) -> list[list[int]]:
    """Indices of ``jobs`` ((study case, FE settings) pairs) grouped by elastic problem: the same
    ``E``, ``H`` and FE settings (the yield stresses may differ), in order of first appearance."""
    out: dict = {}
    for i, (sc, st) in enumerate(jobs):
        out.setdefault((sc.params["E"], sc.params["H"], tuple(sorted(st.items()))), []).append(i)
    return list(out.values())


def _each(value: Any, n: int) -> list:
    """The ``n`` results of a group job (a failed job: its exception for each)."""
    return [value] * n if isinstance(value, Exception) else value


#: ``verify`` runs this study first: its onset searches (``analyse``) run in processes of
#: their own, a few long searches on few processes, and the next studies' cases fill the gaps.
RUN_EARLY = True


def _onset_job(jobs: list[tuple]) -> list:
    """The onsets of (case, FE settings[, contact radius at the case's load]) jobs of one elastic
    problem (:func:`_groups`), sharing their solves (run by
    :func:`~coathertz.verification.study.fork_pool`); a failed search gives its exception."""
    solves: dict = {}
    out = []
    for sc, settings, *a in jobs:
        try:
            out.append(_onset(sc, settings, solves, *a))
        except Exception as exc:  # reported, not fatal: one case must not sink the map
            out.append(exc)
    return out


#: The onset searches stop at ``|max sigma_vM / Y - 1| <`` this. ``W_y`` grows about as the
#: cube of the stress, so the search leaves up to ``3 ONSET_TOL`` relative in ``W_y``; the map's
#: mesh uncertainty (twice the change from 12 to 24 elements across a, about 1.1 % relative for
#: the worst case) must not be made of that: with ``yield_onset``'s default 1e-3 each search
#: could move ``W_y`` by 0.3 %, and the quick map's uncertainty came out 6.8e-4 or 7.7e-4 (of
#: ``W_y/W_ys`` = 0.068) as the refined search started at ``W_ys`` or at the coarse ``W_y``.
ONSET_TOL = 1e-4


def _onset(sc: C.StudyCase, settings: dict, solves: dict | None = None, a_guess: float | None = None):
    from coathertz.fem.method import FEMMethod
    from coathertz.fem.plastic.onset import yield_onset

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return yield_onset(sc.case, FEMMethod(**settings), Yc=sc.params["Yc_Ys"] * YS, Ys=YS, solves=solves,
                           a_guess=a_guess, tol=ONSET_TOL)


def plot(result: C.StudyResult, outdir) -> list:
    rows = [r for r in result.extra.get("onset", []) if r["H"] > 0]
    ratios = sorted({r["Yc_Ys"] for r in rows}) or [1.0]
    fig, axes = C.figure(len(ratios), 1, width=4.6, height=4.0)
    for ax, q in zip(axes[0], ratios, strict=True):
        sel = [r for r in rows if r["Yc_Ys"] == q]
        for cls in CLASSES:
            pts = [(r["H"], r["E"], r["W_bar"]) for r in sel if r["where"] == cls]
            if pts:
                H, E, Wb = np.array(pts).T
                ax.scatter(H, E, s=260, marker="s", c=COLOURS[cls], alpha=0.75, label=f"first yield: {cls}")
                for h_, e_, w_ in zip(H, E, Wb, strict=True):
                    ax.annotate(f"{w_:.2g}", (h_, e_), ha="center", va="center", fontsize=6, color="white")
        ax.set_xscale("log")
        ax.set_yscale("log", base=2)
        ax.set_xlabel(r"$H = h / a_{ys}$")
        ax.set_ylabel(r"$E = E_c^* / E_s^*$")
        ax.set_title(rf"$Y_c/Y_s$ = {q:g}; numbers: $W_y/W_{{ys}}$", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.margins(0.15)
        if ax is axes[0, 0]:
            ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=3, markerscale=0.4)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    return C.save(fig, outdir, "yield_onset")
