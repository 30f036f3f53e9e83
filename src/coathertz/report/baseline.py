"""Regression against a stored result set: the claims' numbers with their tolerances.

A baseline is the JSON written by :func:`write_baseline` (``baseline.json`` in every report
folder): for each claim id its value, its tolerance (absolute, in the claim's unit, set by the
study from the run-to-run scatter it expects: deterministic solvers, so small) and whether it held.
:func:`compare` lists every claim that moved beyond its tolerance, changed verdict, or
disappeared; new claims are listed but are not drift.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from coathertz.jsonsafe import to_jsonable as json_safe

FORMAT = 1


def baseline_dict(results: Iterable[Any], provenance: dict | None = None) -> dict:
    """Baseline of study results (objects with ``name``, ``resolution`` and ``claims``)."""
    claims, studies = {}, {}
    for r in results:
        studies[r.name] = r.resolution
        for c in r.claims:
            claims[c.id] = json_safe({"study": r.name, "value": c.value, "tol": c.tol, "unit": c.unit,
                                      "holds": c.holds, "verdict": c.verdict, "text": c.text,
                                      "uncertainty": getattr(c, "uncertainty", math.nan),
                                      "judged_against": getattr(c, "judged_against", "")})
    return {"format": FORMAT, "studies": studies, "claims": claims,
            "provenance": {k: (provenance or {}).get(k) for k in ("version", "git_commit", "date",
                                                                   "resolution")}}


def write_baseline(path: str | Path, results: Iterable[Any], provenance: dict | None = None) -> Path:
    path = Path(path)
    path.write_text(json.dumps(baseline_dict(results, provenance), indent=1, sort_keys=True))
    return path


def load_baseline(path: str | Path) -> dict:
    from coathertz.errors import CoatHertzError

    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as exc:
        raise CoatHertzError(f"--baseline: cannot read {path}: {exc}") from exc
    if not isinstance(data, dict) or data.get("format") != FORMAT or "claims" not in data:
        raise CoatHertzError(f"--baseline: {path} is not a coathertz baseline (format {FORMAT})")
    return data


@dataclass(frozen=True)
class Drift:
    """One claim that differs from the baseline."""

    claim: str
    study: str
    kind: str  # "moved", "verdict", "missing", "new"
    old: Any
    new: Any
    tol: float
    text: str

    @property
    def is_drift(self) -> bool:
        return self.kind != "new"

    def describe(self) -> str:
        if self.kind == "missing":
            return f"{self.claim}: in the baseline ({self.old}) but not produced by this run"
        if self.kind == "new":
            return f"{self.claim}: new claim ({self.new}), not in the baseline"
        if self.kind == "verdict":
            if isinstance(self.old, str):
                return f"{self.claim}: verdict changed ({self.old} -> {self.new})"
            return f"{self.claim}: verdict changed (holds {self.old} -> {self.new})"
        return f"{self.claim}: {self.old:.4g} -> {self.new:.4g} (moved more than {self.tol:g})"


def _f(x: Any) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def compare(baseline: dict, current: dict) -> list[Drift]:
    """Differences between two baseline dicts; only studies present in both are compared."""
    common = set(baseline.get("studies", {})) & set(current.get("studies", {}))
    old, new = baseline["claims"], current["claims"]
    out = []
    for cid, o in sorted(old.items()):
        if o["study"] not in common:
            continue
        n = new.get(cid)
        if n is None:
            out.append(Drift(cid, o["study"], "missing", o["value"], None, o["tol"], o["text"]))
            continue
        ov, nv, tol = _f(o["value"]), _f(n["value"]), float(o.get("tol", 0.0))
        both_nan = math.isnan(ov) and math.isnan(nv)
        if not both_nan and not (abs(nv - ov) <= tol):
            out.append(Drift(cid, o["study"], "moved", ov, nv, tol, o["text"]))
        elif o.get("verdict", o.get("holds")) != n.get("verdict", n.get("holds")) and "verdict" in o:
            out.append(Drift(cid, o["study"], "verdict", o["verdict"], n.get("verdict"), tol, o["text"]))
        elif o.get("holds") != n.get("holds"):
            out.append(Drift(cid, o["study"], "verdict", o.get("holds"), n.get("holds"), tol, o["text"]))
    for cid, n in sorted(new.items()):
        if n["study"] in common and cid not in old:
            out.append(Drift(cid, n["study"], "new", None, n["value"], n["tol"], n["text"]))
    return out
