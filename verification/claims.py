"""Claims against the arbiter, with the numerical uncertainty that decides inconclusive verdicts.

Every claim of a study is computed from :attr:`~coathertz.verification.study.StudyResult.errors`
(the closed form against each case's reference: the top-ranked method that solved it). Its
uncertainty is, in this order: the reference re-solved at refined settings on the cases a study
marks ``refine`` (a convergence estimate of the reference itself, ``<method>-refined``), over the
claim's own cases, else over the study's refined cases; else the spread between the methods that
solved the same cases (:attr:`~coathertz.verification.study.StudyResult.uncertainty`, the largest
|cross-check difference|: conservative, since it measures the less accurate method's error too),
over the claim's cases, else the study's; else not estimated. The detail says which.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence

from coathertz.methods import method_info

from .study import Claim, StudyResult, judge
from .tables import QUANTITIES

__all__ = ["bound_claim", "judged_on", "max_abs", "plural", "uncertainty_for"]


def plural(n: int, word: str, many: str | None = None) -> str:
    """``"1 case"``, ``"2 cases"``."""
    return f"{n} {word if n == 1 else (many or word + 's')}"


def max_abs(errors: Iterable[dict], quantities: Sequence[str] = QUANTITIES,
            where: Callable[[dict], bool] | None = None) -> tuple[float, int, dict | None]:
    """Largest |err| (and the row where it occurs) and the number of cases, over the errors
    of the quantities ``quantities`` that pass ``where``."""
    sel = [e for e in errors if e["quantity"] in quantities and (where is None or where(e))]
    if not sel:
        return math.nan, 0, None
    worst = max(sel, key=lambda e: abs(e["err"]))
    return abs(worst["err"]), len({e["case"] for e in sel}), worst


def judged_on(result: StudyResult, cases: Iterable[str], references: dict[str, str] | None = None) -> str:
    """``"FFT (72 cases)"`` or ``"AXISYM (68), FFT (4)"``: the references of a set of cases (the
    study's, or ``references``: case -> method, where a claim uses another reference)."""
    count: dict[str, int] = {}
    refs = result.reference if references is None else references
    for c in cases:
        ref = refs.get(c)
        if ref:
            count[ref] = count.get(ref, 0) + 1
    if not count:
        return "no reference"
    order = sorted(count, key=lambda m: (-method_info(m).reference_rank, m))
    if len(order) == 1:
        return f"{order[0].upper()} ({plural(count[order[0]], 'case')})"
    return ", ".join(f"{m.upper()} ({count[m]})" for m in order)


def uncertainty_for(result: StudyResult, cases: Iterable[str], quantities: Sequence[str] = QUANTITIES,
                    ) -> tuple[float, str]:
    """Numerical uncertainty (percent) of a figure computed over ``cases`` and ``quantities``,
    and where it comes from (see the module docstring)."""
    cases = set(cases)
    qs = [q for q in quantities]

    def spread(ids):
        vals = [result.uncertainty[c][q] for c in ids if c in result.uncertainty
                for q in qs if q in result.uncertainty[c]]
        return (max(vals), len({c for c in ids if c in result.uncertainty})) if vals else (math.nan, 0)

    # A reference re-solved at refined settings measures the reference's own error; the spread to
    # the other methods measures theirs as much (conservative). Prefer the convergence estimate.
    refined = set(result.extra.get("refined", {}))
    u, n = spread(cases & refined)
    if n:
        return u, (f"reference re-solved at refined settings on {plural(n, 'case')} of this set "
                   "(convergence estimate)")
    u, n = spread(refined)
    if n:
        return u, (f"reference re-solved at refined settings on the study's {plural(n, 'case')} "
                   "(none in this set; convergence estimate)")
    u, n = spread(cases)
    if n:
        return u, f"largest cross-check difference on {plural(n, 'cross-checked case')} of this set"
    u, n = spread(result.uncertainty)
    if n:
        return u, (f"largest cross-check difference on the study's {plural(n, 'cross-checked case')} "
                   "(none in this set)")
    return math.nan, "not estimated (no case cross-checked by another method or a refined grid)"


def bound_claim(cid: str, text: str, result: StudyResult, bound: float,
                quantities: Sequence[str] = QUANTITIES, where: Callable[[dict], bool] | None = None,
                tol: float = 0.05, errors: Sequence[dict] | None = None) -> Claim:
    """Claim ``max |err| < bound`` (percent) over the errors against each case's reference that
    pass ``where``; its uncertainty from the cross-checks on the same cases."""
    errs = result.errors if errors is None else errors
    sel = [e for e in errs if e["quantity"] in quantities and (where is None or where(e))]
    value, n, worst = max_abs(sel, quantities)
    ids = {e["case"] for e in sel}
    on = judged_on(result, ids, {e["case"]: e["reference"] for e in sel})
    if worst is None:
        return Claim(cid, text, math.nan, f"< {bound:g} %", None, "%", tol, "no case in this set",
                     judged_against=on)
    u, src = uncertainty_for(result, ids, (worst["quantity"],))  # of the quantity that decides
    holds, inconclusive = judge("<", value, bound, u)
    keys = [k for k in ("E", "H", "nu_c", "Ec_GPa", "example") if k in worst]
    detail = (f"{plural(n, 'case')}; worst: {worst['quantity']} at "
              + ", ".join(f"{k} = {worst[k]:.4g}" if isinstance(worst[k], float) else f"{k} = {worst[k]}"
                          for k in keys)
              + f" ({worst['err']:+.2f} % against {worst['reference'].upper()}); uncertainty: {src}")
    return Claim(cid, f"{text} ({plural(n, 'case')})", value, f"< {bound:g} %", holds, "%", tol, detail,
                 u, inconclusive, on)
