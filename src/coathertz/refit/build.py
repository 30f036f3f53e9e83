"""Build the refit data file from a sweep: fit, validate, bin the validated errors.

:func:`build` is what ``coathertz fit-alpha`` runs. Input: a sweep table
(:mod:`coathertz.refit.sweep`) with training and validation rows of the configurations
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

from coathertz.alpha import ELLIPTICAL_RULE, PAPER_RULE, alpha_rigid
from coathertz.refit import direct as DI
from coathertz.refit import ellipse as EL
from coathertz.refit import model as M
from coathertz.refit.fit import FitSettings, error_stats, fit_surface, single_alpha_floor
from coathertz.refit.surface import Surface, term_set
from coathertz.refit.sweep import select, table_hash

FORMAT = "coathertz-alpha-refit/1"
#: |nu_c - nu_s| of the "matched Poisson's ratios" validation subset reported separately.
NU_MATCHED = 0.1

DEFAULT_SETTINGS = {
    "elastic": FitSettings((7, 5, 2, 2), ((3, 2), (3, 2)), reweight=0),
    "rigid": FitSettings((12, 8), (), reweight=0),
    "ellipse": FitSettings((4, 3, 2), ((2, 2),), reweight=0),
    "direct": FitSettings((7, 5, 2, 2), ((3, 2), (3, 2)), ridge=1e-10),
    "corrected": FitSettings((9, 6, 3, 3), ((4, 3), (4, 3)), ridge=1e-9),
}

#: Bin edges of the validated error table, per configuration: (variable, edges).
BINS = {
    "elastic": (("log10_H", (-3.0, -2.0, -1.0, 0.0, 1.0)), ("log10_E", (-1.0, -0.5, 0.0, 0.5, 1.0))),
    "rigid": (("log10_H", (-3.0, -2.0, -1.0, 0.0, 1.0)), ("nu_c", (0.0, 0.25, 0.4, 0.45, 0.5))),
    "ellipse": (("log10_H", (-2.0, -1.0, 0.0, math.log10(3.0))),
                ("log10_E", (math.log10(0.25), 0.0, math.log10(4.0)))),
}


def bin_coords(config: str, cols: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Values of the two binning variables of ``config`` from columns E, H, nu_c."""
    (v1, _), (v2, _) = BINS[config]
    get = {"log10_H": lambda: np.log10(cols["H"]), "log10_E": lambda: np.log10(cols["E"]),
           "nu_c": lambda: np.asarray(cols["nu_c"], dtype=float)}
    return get[v1](), get[v2]()


def bin_index(edges, x) -> np.ndarray:
    e = np.asarray(edges)
    return np.clip(np.searchsorted(e, x, side="right") - 1, 0, len(e) - 2)


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
    """The paper's rule on the same points (eq 19 with NOTES.md fill, Appendix A rigid, eq 21)."""
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


def ellipse_bars(elastic: M.AlphaModel, surfaces: Mapping[str, Surface], q: str, cols) -> np.ndarray:
    base = elastic.bar(EL.BASE[q], cols["E"], cols["H"], cols["nu_c"], cols["nu_s"])
    return base * np.exp(EL.log_correction(dict(surfaces), q, cols["E"], cols["H"], cols["rho"]))


def build(table: Mapping, *, settings: Mapping[str, FitSettings] | None = None,
          provenance: Mapping | None = None) -> dict:
    """Fit every configuration present in ``table`` and return the data-file dict."""
    settings = {**DEFAULT_SETTINGS, **(settings or {})}
    out: dict = {"format": FORMAT, "provenance": dict(provenance or {}), "ranges": {}, "settings": {},
                 "surfaces": {}, "fit_error": {}, "validation_error": {}, "paper_error": {}, "bounds": {},
                 "single_alpha_floor": {}}
    out["provenance"]["sweep_sha256"] = table_hash(table)
    t0 = time.perf_counter()
    models: dict[str, M.AlphaModel] = {}
    for config in M.CONFIGS:
        tr, va = select(table, config=config, set="train"), select(table, config=config, set="valid")
        if len(tr["H"]) == 0:
            continue
        s = settings[config]
        surfs, fit_err = {}, {}
        for q in M.QUANTITIES:
            X = M.variables(config, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"])
            rigid = config == "rigid"

            def f(al, q=q, tr=tr, rigid=rigid):
                return M.bar_from_alpha(q, al, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"], rigid=rigid)

            res = fit_surface(M.VARIABLES[config], M.BOXES[config], X, np.log(tr[f"{q}_bar"]), f, s)
            surfs[q] = res.surface
            fit_err[q] = error_stats(100.0 * np.expm1(res.residual))
        model = models[config] = M.AlphaModel(config, surfs)
        out["single_alpha_floor"][config] = _floor(config, select(table, config=config))
        out["surfaces"][config] = {q: sf.to_dict() for q, sf in surfs.items()}
        out["settings"][config] = s.to_dict()
        out["fit_error"][config] = fit_err
        out["ranges"][config] = _ranges(config, select(table, config=config))
        if len(va["H"]):
            errs = _circ_errs(model, va)
            out["validation_error"][config] = {q: error_stats(e) for q, e in errs.items()}
            out["paper_error"][config] = {
                q: error_stats(100.0 * (paper_bars(config, q, va) / va[f"{q}_bar"] - 1))
                for q in M.QUANTITIES}
            out["bounds"][config] = _bins(config, va, errs)
            inside = (va["H"] >= 0.01) & (va["H"] <= 3.0)
            if config == "elastic":
                inside &= (va["E"] >= 0.25) & (va["E"] <= 4.0)
            out.setdefault("validation_error_paper_range", {})[config] = {
                "range": "H in [0.01, 3]" + (", E in [1/4, 4]" if config == "elastic" else ""),
                "refit": {q: error_stats(e[inside]) for q, e in errs.items()},
                "paper": {q: error_stats(100.0 * (paper_bars(config, q, va)[inside]
                                                  / va[f"{q}_bar"][inside] - 1)) for q in M.QUANTITIES}}
            if config == "elastic":
                near = np.abs(va["nu_c"] - va["nu_s"]) <= NU_MATCHED
                out.setdefault("validation_error_nu_matched", {})[config] = {
                    "max_abs_nu_c_minus_nu_s": NU_MATCHED,
                    **{q: error_stats(e[near]) for q, e in errs.items()}}
    tr, va = select(table, config="elastic", set="train"), select(table, config="elastic", set="valid")
    if len(tr["H"]):
        s = settings["direct"]
        dsurf, derr = {}, {}
        for q in M.QUANTITIES:
            dsurf[q], derr[q] = DI.fit(q, tr, s)
        d: dict = {"surfaces": {q: sf.to_dict() for q, sf in dsurf.items()}, "settings": s.to_dict(),
                   "fit_error": derr}
        if len(va["H"]):
            errs = {q: 100.0 * np.expm1(DI.log_bar(dsurf[q], q, va["E"], va["H"], va["nu_c"], va["nu_s"])
                                        - np.log(va[f"{q}_bar"])) for q in M.QUANTITIES}
            d["validation_error"] = {q: error_stats(e) for q, e in errs.items()}
            d["bounds"] = _bins("elastic", va, errs)
        out["direct"] = d
        s = settings["corrected"]
        el = models["elastic"]
        csurf, cerr = {}, {}
        for q in M.QUANTITIES:
            base = np.log(el.bar(q, tr["E"], tr["H"], tr["nu_c"], tr["nu_s"]))
            csurf[q], cerr[q] = DI.fit_corrected(q, tr, base, s)
        d = {"surfaces": {q: sf.to_dict() for q, sf in csurf.items()}, "settings": s.to_dict(),
             "fit_error": cerr}
        if len(va["H"]):
            errs = {}
            for q in M.QUANTITIES:
                lb = np.log(el.bar(q, va["E"], va["H"], va["nu_c"], va["nu_s"]))
                lb += DI.log_correction(csurf[q], va["E"], va["H"], va["nu_c"], va["nu_s"])
                errs[q] = 100.0 * np.expm1(lb - np.log(va[f"{q}_bar"]))
            d["validation_error"] = {q: error_stats(e) for q, e in errs.items()}
            d["bounds"] = _bins("elastic", va, errs)
        out["corrected"] = d
    tr, va = select(table, config="ellipse", set="train"), select(table, config="ellipse", set="valid")
    if len(tr["H"]) and "elastic" in models:
        s = settings["ellipse"]
        terms = term_set(s.degrees, s.cross or None)
        lo, hi = tuple(b[0] for b in EL.BOX), tuple(b[1] for b in EL.BOX)
        proto = Surface(EL.VARIABLES, lo, hi, terms, tuple(0.0 for _ in terms))
        Phi = proto.design(EL.variables(tr["E"], tr["H"], tr["rho"]))
        pre = EL.prefactor(tr["E"], tr["H"], tr["rho"])
        surfs, fit_err = {}, {}
        for q in EL.QUANTITIES:
            base = models["elastic"].bar(EL.BASE[q], tr["E"], tr["H"], tr["nu_c"], tr["nu_s"])
            y = np.log(tr[f"{q}_bar"] / base)
            A = pre[:, None] * Phi
            c = np.linalg.solve(A.T @ A + s.ridge * np.eye(len(terms)), A.T @ y)
            surfs[q] = Surface(EL.VARIABLES, lo, hi, terms, tuple(float(x) for x in c))
            fit_err[q] = error_stats(100.0 * np.expm1(A @ c - y))
        out["surfaces"]["ellipse"] = {q: sf.to_dict() for q, sf in surfs.items()}
        out["settings"]["ellipse"] = s.to_dict()
        out["fit_error"]["ellipse"] = fit_err
        out["ranges"]["ellipse"] = _ranges("ellipse", select(table, config="ellipse"))
        if len(va["H"]):
            errs = {q: 100.0 * (ellipse_bars(models["elastic"], surfs, q, va) / va[f"{q}_bar"] - 1)
                    for q in EL.QUANTITIES}
            out["validation_error"]["ellipse"] = {q: error_stats(e) for q, e in errs.items()}
            out["paper_error"]["ellipse"] = {
                q: error_stats(100.0 * (paper_bars("ellipse", q, va) / va[f"{q}_bar"] - 1))
                for q in EL.QUANTITIES}
            out["bounds"]["ellipse"] = _bins("ellipse", va, errs)
    out["provenance"]["fit_seconds"] = round(time.perf_counter() - t0, 2)
    out["provenance"]["counts"] = {
        c: {w: len(select(table, config=c, set=w)["H"]) for w in ("train", "valid")}
        for c in ("elastic", "rigid", "ellipse")}
    return out


def _ranges(config: str, cols) -> dict:
    r = {"H": [float(np.min(cols["H"])), float(np.max(cols["H"]))]}
    if config != "rigid":
        r["E"] = [float(np.min(cols["E"])), float(np.max(cols["E"]))]
    r["nu_c"] = [float(np.min(cols["nu_c"])), float(np.max(cols["nu_c"]))]
    if config == "elastic":
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
