"""``coathertz predict``: classical and extended Hertz predictions of one case."""

from __future__ import annotations

import argparse
import math
import sys
import warnings

from coathertz.cli._common import (
    add_case_arguments,
    case_from_args,
    finish,
    format_table,
    list_examples,
    to_json,
)

NAME = "predict"
HELP = "closed-form predictions: Hertz without coating, coating-only Hertz, extended Hertz"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_case_arguments(parser)
    parser.add_argument(
        "--alpha", help="explicit alpha values 'a=..,p=..,delta=..' (e.g. read from figure 5)"
    )
    parser.add_argument("--alpha-rule", default="paper", choices=_alpha_rules(),
                        help="alpha rule: 'paper' or 'eq21-fill' (how the parts of eq (19) missing from "
                             "the copy are filled, docs/paper-notes.md), or 'refit' (smooth refitted "
                             "alpha with a validated error bound, coathertz.closedform.refit)")
    parser.add_argument("--json", action="store_true", help="machine-readable output")


def _alpha_rules() -> list[str]:
    """The rules the predictor knows (its registry), so the choices are not kept by hand."""
    from coathertz.closedform import method as predictor

    return sorted(getattr(predictor, "RULE_NAMES", predictor.RULES))


def _um(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x * 1e6:.5g}"


def _mpa(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x / 1e6:.5g}"


def run(args: argparse.Namespace) -> int:
    from coathertz.closedform.alpha import Alphas
    from coathertz.closedform.method import ClosedFormMethod
    from coathertz.errors import FittedRangeWarning, ModelValidityWarning

    if args.list_examples:
        return list_examples()
    case = case_from_args(args)
    alphas = Alphas.parse(args.alpha) if args.alpha else None
    kinds = (FittedRangeWarning, ModelValidityWarning)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", FittedRangeWarning)
        warnings.simplefilter("always", ModelValidityWarning)
        res = finish(case, ClosedFormMethod(args.alpha_rule, alphas).solve(case))
    msgs = [str(w.message) for w in caught if issubclass(w.category, kinds)]
    others = [w for w in caught if not issubclass(w.category, kinds)]
    for w in others:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    hs, hc = case.hertz_s, case.hertz_c
    rows = {
        "hertz_substrate": {"delta": float(hs.delta0), "a": float(hs.a0), "p0": float(hs.p0),
                            "r_a": float(hs.r_a0), "r_b": float(hs.r_b0)},
        "hertz_coating": {"delta": float(hc.delta0), "a": float(hc.a0), "p0": float(hc.p0),
                          "r_a": float(hc.r_a0), "r_b": float(hc.r_b0)},
        "extended": {"delta": res.delta, "a": res.a, "p0": res.p0, "r_a": res.r_a, "r_b": res.r_b},
    }
    info = {
        "case": case.describe(),
        "Rx": case.Rx, "Ry": case.Ry, "R": case.R,
        "normalisation": case.normalisers.kind,
        "H": res.meta["H"], "E": res.meta["E"],
        "alpha": res.meta["alpha"], "alpha_source": res.meta["rule"],
        "E_star": res.meta["E_star"],
        "validity": res.meta.get("validity"),
        "warnings": msgs,
    }
    if "refit_bound" in res.meta:
        info["refit_bound"] = res.meta["refit_bound"]
    for m in msgs:
        print(f"coathertz predict: warning: {m}", file=sys.stderr)
    if args.json:
        print(to_json({"units": "SI (m, Pa, N)", **info, **rows}))
        return 0
    print(f"case: {case.label or '(unnamed)'}\n  {case.describe()}")
    if case.is_coated:
        print(f"  H = {', '.join(f'{h:.4g}' for h in res.meta['H'])} (h/a0{case.normalisers.kind}), "
              f"E = Ec*/Es* = {', '.join(f'{e:.4g}' for e in res.meta['E'])}")
        al = res.meta["alpha"]
        print("  alpha (" + res.meta["rule"] + "): "
              + ", ".join(f"alpha_{k} = {', '.join(f'{x:.4g}' for x in v)}" for k, v in al.items()))
    ell = not case.is_circular
    header = ["", "delta [um]", "a [um]", "p0 [MPa]"] + (["r_a [um]", "r_b [um]"] if ell else [])
    names = {"hertz_substrate": "Hertz, coating removed", "hertz_coating": "Hertz, coating half-space",
             "extended": "extended Hertz" if case.is_coated else "Hertz"}
    table = []
    for key, r in rows.items():
        if key != "extended" and not case.is_coated:
            continue
        row = [names[key], _um(r["delta"]), _um(r["a"]), _mpa(r["p0"])]
        if ell:
            row += [_um(r["r_a"]), _um(r["r_b"])]
        table.append(row)
    print(format_table(header, table))
    if "refit_bound" in res.meta:
        print(res.meta["refit_bound"]["text"])
    return 0
