"""Tidy tables of a study: result rows, errors of the closed form against each case's reference,
cross-checks of the other numerical methods against it, and their summaries.

Everything here is plain data in, plain data out (lists of dicts); the report and the studies
share it. :func:`group_by_case` is the one place rows are grouped by case.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from coathertz.case import bars

__all__ = ["FIELD", "QUANTITIES", "RESULT_KEYS", "SYMBOL", "bars", "crosscheck", "crosscheck_summary",
           "group_by_case", "make_errors", "make_rows", "params_of", "uncertainty_by_case"]

QUANTITIES = ("a", "p", "delta")
#: Result field of each quantity.
FIELD = {"a": "a", "p": "p0", "delta": "delta", "r_a": "r_a", "r_b": "r_b"}
SYMBOL = {"a": r"$\bar a$", "p": r"$\bar p$", "delta": r"$\bar\delta$",
          "r_a": r"$\bar r_a$", "r_b": r"$\bar r_b$"}
#: Row keys that are results, not case parameters.
RESULT_KEYS = frozenset({"method", "delta", "a", "p0", "r_a", "r_b", "a_bar", "p_bar", "delta_bar",
                         "r_a_bar", "r_b_bar", "a_num", "wall_time", "r_p0"})


def group_by_case(rows: Iterable[Mapping[str, Any]]) -> dict[str, dict[str, Mapping[str, Any]]]:
    """``{case id: {method: row}}``, cases in first-seen order."""
    out: dict[str, dict[str, Mapping[str, Any]]] = {}
    for r in rows:
        out.setdefault(r["case"], {})[r["method"]] = r
    return out


def params_of(row: Mapping[str, Any]) -> dict[str, Any]:
    """The case parameters of a row (everything but the results)."""
    return {k: v for k, v in row.items() if k not in RESULT_KEYS}


def make_rows(cases: Sequence[Any], records: Mapping[str, Mapping[str, Mapping]]) -> list[dict]:
    """One tidy row per (study case, method) that produced a result."""
    rows = []
    for sc in cases:
        for m, res in records.get(sc.id, {}).items():
            if res.get("error"):
                continue
            row = {"case": sc.id, **sc.params, "method": m,
                   **{k: res[k] for k in ("delta", "a", "p0", "r_a", "r_b")}, **bars(sc.case, res)}
            meta = res.get("meta", {})
            for k in ("a_num", "wall_time", "r_p0"):
                if k in meta:
                    row[k] = meta[k]
            rows.append(row)
    return rows


def make_errors(rows: Sequence[dict], reference: Mapping[str, str], quantities: Sequence[str] = QUANTITIES,
                predicted: str = "closed-form") -> list[dict]:
    """Errors of ``predicted`` against each case's reference method, in percent:
    ``err = (predicted - numerical)/numerical`` (the paper's definition)."""
    out = []
    for cid, ms in group_by_case(rows).items():
        ref = reference.get(cid)
        if predicted not in ms or ref not in ms:
            continue
        pred, num = ms[predicted], ms[ref]
        for q in quantities:
            f = FIELD[q]
            out.append({**params_of(pred), "case": cid, "reference": ref, "quantity": q,
                        "predicted": pred[f], "numerical": num[f], "err": 100.0 * (pred[f] / num[f] - 1.0)})
    return out


def crosscheck(rows: Sequence[dict], reference: Mapping[str, str], numerical: Iterable[str],
               quantities: Sequence[str] = QUANTITIES) -> list[dict]:
    """Every other ``numerical`` method against each case's reference, per quantity:
    ``diff = (method - reference)/reference`` in percent."""
    numerical = set(numerical)
    out = []
    for cid, ms in group_by_case(rows).items():
        ref = reference.get(cid)
        if ref not in ms:
            continue
        for m in sorted(ms):
            if m == ref or m not in numerical:
                continue
            for q in quantities:
                f = FIELD[q]
                out.append({**params_of(ms[m]), "case": cid, "method": m, "reference": ref, "quantity": q,
                            "pair": f"{m} vs {ref}", "diff": 100.0 * (ms[m][f] / ms[ref][f] - 1.0)})
    return out


def uncertainty_by_case(checks: Iterable[Mapping[str, Any]]) -> dict[str, dict[str, float]]:
    """Case id -> quantity -> our estimate of the reference's numerical uncertainty there (percent):
    the difference from the reference solved again at refined settings (``<method>-refined``, a
    convergence estimate) where the case has one; else the largest |difference| from the other
    methods that solved it (their spread: conservative where the reference is the more accurate)."""
    refined: dict[str, dict[str, float]] = {}
    spread: dict[str, dict[str, float]] = {}
    for d in checks:
        into = refined if d["method"].endswith("-refined") else spread
        q = into.setdefault(d["case"], {})
        q[d["quantity"]] = max(q.get(d["quantity"], 0.0), abs(d["diff"]))
    return {**spread, **refined}


def crosscheck_summary(checks: Sequence[Mapping[str, Any]]) -> list[dict]:
    """Max |difference|, mean and count per (method vs reference, quantity)."""
    acc: dict[tuple[str, str], list[float]] = {}
    for d in checks:
        acc.setdefault((d["pair"], d["quantity"]), []).append(d["diff"])
    out = []
    for (p, q), v in sorted(acc.items()):
        v = [x for x in v if math.isfinite(x)]
        if v:
            out.append({"pair": p, "quantity": q, "n": len(v), "max_abs": float(np.max(np.abs(v))),
                        "mean": float(np.mean(v))})
    return out
