"""Build the refit data file from a sweep: fit, validate, bin the validated errors.

:func:`build` is what ``coathertz fit-alpha`` runs. Input: a sweep table
(:mod:`coathertz.fitalpha.sweep`) with training and validation rows of the configurations
``elastic``, ``rigid`` and (optionally) ``ellipse``. Output: the JSON-ready dict stored as
``coathertz/data/alpha_refit.json``: surfaces, fit settings, training and validation errors
(max, 99th percentile, RMS per quantity, next to the paper's rule on the same points), the
binned validated error bounds the predictor prints, and provenance.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Mapping

import numpy as np

from coathertz.closedform.alpha import ELLIPTICAL_RULE, PAPER_RULE, alpha_rigid
from coathertz.closedform.refit import corrected as CF
from coathertz.closedform.refit import ellipse as EL
from coathertz.closedform.refit import model as M
from coathertz.closedform.refit.rule_format import (
    BINS,
    FORMAT,
    NU_MATCHED,
    bin_coords,
    bin_index,
)
from coathertz.closedform.refit.surface import Surface, term_set
from coathertz.errors import CoatHertzError
from coathertz.fitalpha import corrected as CO
from coathertz.fitalpha.fit import FitSettings, error_stats, fit_surface, single_alpha_floor
from coathertz.fitalpha.sweep import select, table_hash

DEFAULT_SETTINGS = {
    "elastic": FitSettings((8, 6, 4), ((4, 3),), reweight=0, iterations=20),
    "rigid": FitSettings((12, 8), (), reweight=0),
    "ellipse": FitSettings((16, 3, 2), ((16, 3),), ridge=1e-8, reweight=0),
    "corrected_elastic": FitSettings((24, 12, 10)),
    "corrected_elastic_patch": FitSettings((40, 8, 8)),
    "corrected_elastic_ring": FitSettings((20, 10, 10)),
    "corrected_rigid": FitSettings((24, 16), (), ridge=1e-12, reweight=0),  # full tensor
    "indenter": FitSettings((20, 6, 3, 6), (), ridge=1e-12, reweight=0),  # full tensor
}

def _bins(config: str, cols, errs: Mapping[str, np.ndarray]) -> dict:
    (n1, e1), (n2, e2) = BINS[config]
    x1, x2 = bin_coords(config, cols)
    i1, i2 = bin_index(e1, x1), bin_index(e2, x2)
    table: dict = {"variables": [n1, n2], "edges": [list(e1), list(e2)], "max": {}, "count": []}
    count = np.zeros((len(e1) - 1, len(e2) - 1), dtype=int)
    np.add.at(count, (i1, i2), 1)
    table["count"] = count.tolist()
    for q, e in errs.items():
        m = np.full(count.shape, np.nan)
        for a in range(count.shape[0]):
            for b in range(count.shape[1]):
                sel = (i1 == a) & (i2 == b)
                if sel.any():
                    m[a, b] = float(np.max(np.abs(e[sel])))
        table["max"][q] = [[None if math.isnan(v) else round(v, 4) for v in row] for row in m]
    return table


def paper_bars(config: str, q: str, cols) -> np.ndarray:
    """The paper's rule on the same points (eq 19 with docs/paper-notes.md fill, Appendix A rigid, eq 21)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if config == "rigid":
            return M.bar_from_alpha(q, alpha_rigid(q, cols["H"]), None, cols["H"], cols["nu_c"], None,
                                    rigid=True)
        if config == "elastic":
            return M.bar_from_alpha(q, PAPER_RULE.alpha(q, cols["E"], cols["H"]), cols["E"], cols["H"],
                                    cols["nu_c"], cols["nu_s"])
        qq = {"r_a": "a", "r_b": "b"}.get(q, q)
        al = ELLIPTICAL_RULE.alpha(qq, cols["E"], cols["H"])
        return M.bar_from_alpha(EL.BASE[q], al, cols["E"], cols["H"], cols["nu_c"], cols["nu_s"])


def _circ_errs(model: M.AlphaModel, cols) -> dict[str, np.ndarray]:
    return {q: 100.0 * (model.bar(q, cols["E"], cols["H"], cols["nu_c"], cols["nu_s"]) / cols[f"{q}_bar"] - 1)
            for q in M.QUANTITIES}


def ellipse_base(elastic: M.AlphaModel, corrected: CF.CorrectedForm | None, q: str, cols) -> np.ndarray:
    """Circular bars of the base quantity of elliptical ``q`` (``a`` for both semi-axes): the
    corrected form where given, else the one-alpha refit."""
    b = EL.BASE[q]
    if corrected is not None:
        return np.exp(corrected.log_bar(b, cols["E"], cols["H"], cols["nu_c"], cols["nu_s"], elastic))
    return elastic.bar(b, cols["E"], cols["H"], cols["nu_c"], cols["nu_s"])


def ellipse_bars(elastic: M.AlphaModel, corrected: CF.CorrectedForm | None,
                 surfaces: Mapping[str, Surface], q: str, cols) -> np.ndarray:
    base = ellipse_base(elastic, corrected, q, cols)
    return base * np.exp(EL.log_correction(dict(surfaces), q, cols["E"], cols["H"], cols["rho"]))


def _p_axis(cols) -> np.ndarray:
    """The axis branch of p0 (the largest pressure on ``r <= RING_RHO a``): p0 where the peak is
    there, else the ``p_axis_bar`` column."""
    from coathertz.fitalpha.sweep import RING_RHO

    ring = np.asarray(cols["r_p0_bar"], dtype=float) > RING_RHO
    axis = np.asarray(cols.get("p_axis_bar", np.full(len(ring), np.nan)), dtype=float)
    out = np.where(ring, axis, np.asarray(cols["p_bar"], dtype=float))
    if not np.all(np.isfinite(out)):
        raise CoatHertzError("sweep: rows with the peak off the axis need the p_axis_bar column "
                             "(sweep.axis_and_ring)")
    return out


def fit_corrected_form(config: str, table: Mapping, model: M.AlphaModel,
                       settings: Mapping[str, FitSettings]) -> CF.CorrectedForm:
    """Fit the corrected form of ``config`` (:mod:`coathertz.closedform.refit.corrected`).

    Rigid substrate: base the one-alpha refit, correction by linear least squares on the training
    rows. Elastic substrate: base eq (17) at alpha = 1; full tensor corrections fitted on the
    complete training grid one variable at a time (:func:`coathertz.fitalpha.corrected.fit_tensor`);
    p0's axis branch on the training grid (the pressure on the axis) and on the stiff-coating
    patch grid (set ``patch``), its ring branch on the ring grid (set ``ring``).
    """
    from coathertz.fitalpha.sweep import PATCH_BOX, RING_BOX

    tr = select(table, config=config, set="train")
    if config == "rigid":
        s = settings["corrected_rigid"]
        X = M.variables("rigid", None, tr["H"], tr["nu_c"])
        v = CF.correction_weight("rigid", tr["H"])
        surfaces = {}
        for q in M.QUANTITIES:
            base = np.log(model.bar(q, None, tr["H"], tr["nu_c"]))
            try:  # a complete grid: one variable at a time
                surfaces[q] = CO.tensor_surface(M.VARIABLES["rigid"], M.BOXES["rigid"], s.degrees, X,
                                                np.log(tr[f"{q}_bar"]) - base, v)
            except CoatHertzError:  # an incomplete grid (failed cases): general least squares
                surfaces[q] = CO.fit_corrected(q, tr, base, s, config="rigid")[0]
        return CF.CorrectedForm("rigid", {q: None for q in M.QUANTITIES}, surfaces)
    base = {q: 1.0 for q in M.QUANTITIES}
    form0 = CF.CorrectedForm("elastic", base, {})
    s = settings["corrected_elastic"]
    X = M.variables("elastic", tr["E"], tr["H"], tr["nu_c"], tr["nu_s"])
    v = CF.correction_weight("elastic", tr["H"])
    surfaces, patch, ring = {}, {}, {}
    for q in M.QUANTITIES:
        target = _p_axis(tr) if q == "p" else tr[f"{q}_bar"]
        y = np.log(target) - form0.base_log_bar(q, None, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"])
        surfaces[q] = CO.tensor_surface(M.VARIABLES["elastic"], M.BOXES["elastic"], s.degrees, X, y, v)
    pa = select(table, config="elastic", set="patch")
    if len(pa["H"]):
        s_pa = M.variables("elastic", pa["E"], pa["H"], pa["nu_c"], pa["nu_s"])[2]
        Xp = np.vstack([M.xi_H(pa["H"]), np.log10(pa["E"]), s_pa])
        y = np.log(_p_axis(pa)) - form0.base_log_bar("p", None, pa["E"], pa["H"], pa["nu_c"], pa["nu_s"])
        box = (M.XI_H, PATCH_BOX["log10_E"], PATCH_BOX["s"])
        patch["p"] = CO.tensor_surface(("xi_H", "log10_E", "s"), box,
                                       settings["corrected_elastic_patch"].degrees, Xp, y,
                                       CF.correction_weight("elastic", pa["H"]))
    rg = select(table, config="elastic", set="ring")
    if len(rg["H"]):
        Xr = M.variables("elastic", rg["E"], rg["H"], rg["nu_c"], rg["nu_s"])
        y = np.log(rg["p_ring_bar"]) - form0.base_log_bar("p", None, rg["E"], rg["H"], rg["nu_c"], rg["nu_s"])
        ring["p"] = CO.tensor_surface(M.VARIABLES["elastic"], tuple(RING_BOX.values()),
                                      settings["corrected_elastic_ring"].degrees, Xr, y, np.ones(len(y)))
    return CF.CorrectedForm("elastic", base, surfaces, patch, ring)


def _validate(config: str, out: dict, key: str, errs: Mapping[str, np.ndarray], va) -> None:
    """Store the validation error statistics and bins of one form (``key``: ``alpha``/``corrected``)."""
    out["validation_error"] = {q: error_stats(e) for q, e in errs.items()}
    out["bounds"] = _bins(config, va, errs)


def build(table: Mapping, *, settings: Mapping[str, FitSettings] | None = None,
          provenance: Mapping | None = None) -> dict:
    """Fit every configuration present in ``table`` and return the data-file dict.

    Per circular configuration: the one-alpha refit (``surfaces``, ``validation_error``,
    ``bounds``) and the corrected form (``corrected``: the refit alpha times a smooth factor,
    :mod:`coathertz.closedform.refit.corrected`); ``best_form`` names the form with the smaller largest
    validation error, which the predictor uses. Ellipses: a correction on top of the best
    circular form of the elastic substrate.
    """
    settings = {**DEFAULT_SETTINGS, **(settings or {})}
    out: dict = {"format": FORMAT, "provenance": dict(provenance or {}), "ranges": {}, "settings": {},
                 "surfaces": {}, "fit_error": {}, "validation_error": {}, "paper_error": {}, "bounds": {},
                 "single_alpha_floor": {}, "corrected": {}, "best_form": {}}
    out["provenance"]["sweep_sha256"] = table_hash(table)
    t0 = time.perf_counter()
    circular: dict[str, object] = {}
    for config in M.CONFIGS:
        tr, va = select(table, config=config, set="train"), select(table, config=config, set="valid")
        if len(tr["H"]) == 0:
            continue
        s = settings[config]
        rigid = config == "rigid"
        surfs, fit_err = {}, {}
        X = M.variables(config, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"])
        for q in M.QUANTITIES:
            def f(al, q=q, tr=tr, rigid=rigid):
                return M.bar_from_alpha(q, al, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"], rigid=rigid)

            res = fit_surface(M.VARIABLES[config], M.BOXES[config], X, np.log(tr[f"{q}_bar"]), f, s)
            surfs[q] = res.surface
            fit_err[q] = error_stats(100.0 * np.expm1(res.residual))
        model = M.AlphaModel(config, surfs)
        out["single_alpha_floor"][config] = _floor(config, {k: np.concatenate([tr[k], va[k]]) for k in tr})
        out["surfaces"][config] = {q: sf.to_dict() for q, sf in surfs.items()}
        out["settings"][config] = s.to_dict()
        out["fit_error"][config] = fit_err
        out["ranges"][config] = _ranges(config, select(table, config=config))
        form = fit_corrected_form(config, table, model, settings)
        corr: dict = {**form.to_dict(), "settings": {k: s_.to_dict() for k, s_ in settings.items()
                                                     if k.startswith(f"corrected_{config}")}}
        corr["fit_error"] = {q: error_stats(100.0 * np.expm1(
            form.log_bar(q, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"], model) - np.log(tr[f"{q}_bar"])))
            for q in M.QUANTITIES}
        circular[config] = (model, form)
        best = "alpha"
        if len(va["H"]):
            errs = _circ_errs(model, va)
            out["validation_error"][config] = {q: error_stats(e) for q, e in errs.items()}
            out["paper_error"][config] = {
                q: error_stats(100.0 * (paper_bars(config, q, va) / va[f"{q}_bar"] - 1))
                for q in M.QUANTITIES}
            out["bounds"][config] = _bins(config, va, errs)
            cerrs = {q: 100.0 * np.expm1(form.log_bar(q, va["E"], va["H"], va["nu_c"], va["nu_s"], model)
                                          - np.log(va[f"{q}_bar"])) for q in M.QUANTITIES}
            _validate(config, corr, "corrected", cerrs, va)
            worst = {k: max(v["max"] for v in d.values()) for k, d in
                     (("alpha", out["validation_error"][config]), ("corrected", corr["validation_error"]))}
            best = min(worst, key=worst.get)
            inside = (va["H"] >= 0.01) & (va["H"] <= 3.0)
            if config == "elastic":
                inside &= (va["E"] >= 0.25) & (va["E"] <= 4.0)
            out.setdefault("validation_error_paper_range", {})[config] = {
                "range": "H in [0.01, 3]" + (", E in [1/4, 4]" if config == "elastic" else ""),
                "refit": {q: error_stats(e[inside]) for q, e in errs.items()},
                "corrected": {q: error_stats(e[inside]) for q, e in cerrs.items()},
                "paper": {q: error_stats(100.0 * (paper_bars(config, q, va)[inside]
                                                  / va[f"{q}_bar"][inside] - 1)) for q in M.QUANTITIES}}
            if config == "elastic":
                near = np.abs(va["nu_c"] - va["nu_s"]) <= NU_MATCHED
                out.setdefault("validation_error_nu_matched", {})[config] = {
                    "max_abs_nu_c_minus_nu_s": NU_MATCHED,
                    **{q: error_stats(e[near]) for q, e in errs.items()}}
        out["corrected"][config] = corr
        out["best_form"][config] = best
    tr, va = select(table, config="indenter", set="train"), select(table, config="indenter", set="valid")
    if len(tr["H"]) and "elastic" in circular:
        _build_indenter(out, circular["elastic"], tr, va, settings["indenter"],
                        out["best_form"]["elastic"] == "corrected")
    tr, va = select(table, config="ellipse", set="train"), select(table, config="ellipse", set="valid")
    if len(tr["H"]) and "elastic" in circular:
        model, form = circular["elastic"]  # type: ignore[misc]
        use_corr = out["best_form"]["elastic"] == "corrected"
        s = settings["ellipse"]
        terms = term_set(s.degrees, s.cross or None)
        lo, hi = tuple(b[0] for b in EL.BOX), tuple(b[1] for b in EL.BOX)
        proto = Surface(EL.VARIABLES, lo, hi, terms, tuple(0.0 for _ in terms))
        Phi = proto.design(EL.variables(tr["E"], tr["H"], tr["rho"]))
        pre = EL.prefactor(tr["E"], tr["H"], tr["rho"])
        surfs, fit_err = {}, {}
        for q in EL.QUANTITIES:
            base = ellipse_base(model, form if use_corr else None, q, tr)
            y = np.log(tr[f"{q}_bar"] / base)
            A = pre[:, None] * Phi
            c = np.linalg.solve(A.T @ A + s.ridge * np.eye(len(terms)), A.T @ y)
            surfs[q] = Surface(EL.VARIABLES, lo, hi, terms, tuple(float(x) for x in c))
            fit_err[q] = error_stats(100.0 * np.expm1(A @ c - y))
        out["surfaces"]["ellipse"] = {q: sf.to_dict() for q, sf in surfs.items()}
        out["settings"]["ellipse"] = s.to_dict()
        out["fit_error"]["ellipse"] = fit_err
        out["ranges"]["ellipse"] = _ranges("ellipse", select(table, config="ellipse"))
        out["best_form"]["ellipse"] = "corrected" if use_corr else "alpha"
        if len(va["H"]):
            errs = {q: 100.0 * (ellipse_bars(model, form if use_corr else None, surfs, q, va)
                                / va[f"{q}_bar"] - 1) for q in EL.QUANTITIES}
            out["validation_error"]["ellipse"] = {q: error_stats(e) for q, e in errs.items()}
            out["paper_error"]["ellipse"] = {
                q: error_stats(100.0 * (paper_bars("ellipse", q, va) / va[f"{q}_bar"] - 1))
                for q in EL.QUANTITIES}
            out["bounds"]["ellipse"] = _bins("ellipse", va, errs)
    out["provenance"]["fit_seconds"] = round(time.perf_counter() - t0, 2)
    out["provenance"]["counts"] = {
        c: {w: len(select(table, config=c, set=w)["H"]) for w in ("train", "valid")}
        for c in ("elastic", "rigid", "ellipse", "indenter")}
    return out


def rigid_bars_function(model: M.AlphaModel, form: CF.CorrectedForm, corrected: bool):
    """``(E, H, nu_c, nu_s) -> bars`` of the rigid indenter's elastic-substrate form the predictor
    uses (the base of the elastic-indenter form)."""
    if not corrected:
        return model.bars

    def bars(E, H, nu_c, nu_s):
        return {q: np.exp(v) for q, v in form.log_bars(E, H, nu_c, nu_s, model).items()}

    return bars


def _build_indenter(out: dict, circular, tr, va, s: FitSettings, corrected: bool) -> None:
    """Fit, validate and bin the elastic-indenter form (:mod:`coathertz.closedform.refit.indenter`)."""
    from coathertz.fitalpha import indenter as FI

    model, form = circular
    rigid = rigid_bars_function(model, form, corrected)
    ind = FI.fit_indenter_form(tr, rigid, s)
    out["indenter"] = ind.to_dict()
    out["settings"]["indenter"] = s.to_dict()
    out["fit_error"]["indenter"] = {q: error_stats(e) for q, e in FI.errors(ind, rigid, tr).items()}
    out["ranges"]["indenter"] = {**_ranges("elastic", {k: np.concatenate([tr[k], va[k]]) for k in tr}),
                                 "gamma": [float(min(np.min(tr["gamma"]), np.min(va["gamma"], initial=1.0))),
                                           1.0]}
    out["best_form"]["indenter"] = "indenter"
    if len(va["H"]):
        errs = FI.errors(ind, rigid, va)
        out["validation_error"]["indenter"] = {q: error_stats(e) for q, e in errs.items()}
        out["bounds"]["indenter"] = _bins("indenter", va, errs)


def _ranges(config: str, cols) -> dict:
    r = {"H": [float(np.min(cols["H"])), float(np.max(cols["H"]))]}
    if config != "rigid":
        r["E"] = [float(np.min(cols["E"])), float(np.max(cols["E"]))]
    r["nu_c"] = [float(np.min(cols["nu_c"])), float(np.max(cols["nu_c"]))]
    if config in ("elastic", "ellipse"):  # the ellipse correction was fitted at nu_c = nu_s = 0.3 only
        r["nu_s"] = [float(np.min(cols["nu_s"])), float(np.max(cols["nu_s"]))]
    if config == "ellipse":
        r["rho"] = [float(np.min(cols["rho"])), float(np.max(cols["rho"]))]
    return r


def _floor(config: str, cols, target: float = 0.3) -> dict:
    """Where no single alpha reaches ``target`` % (all points of ``config``), per quantity."""
    rigid = config == "rigid"
    res = {}
    for q in M.QUANTITIES:
        def f(al, q=q):
            c = {k: np.asarray(cols[k], dtype=float)[:, None] for k in ("E", "H", "nu_c", "nu_s")}
            return M.bar_from_alpha(q, al, c["E"], c["H"], c["nu_c"], c["nu_s"], rigid=rigid)

        fl = single_alpha_floor(f, np.log(np.asarray(cols[f"{q}_bar"], dtype=float)))
        bad = fl > target
        k = int(np.argmax(fl))
        res[q] = {"target_percent": target, "n": int(fl.size), "n_above_target": int(bad.sum()),
                  "max_percent": round(float(fl.max()), 4),
                  "worst": {v: float(np.asarray(cols[v])[k]) for v in ("E", "H", "nu_c", "nu_s")},
                  "points_above_target": [
                      {v: round(float(np.asarray(cols[v])[i]), 6) for v in ("E", "H", "nu_c", "nu_s")}
                      | {"floor_percent": round(float(fl[i]), 4)} for i in np.flatnonzero(bad)[:200]]}
    return res
