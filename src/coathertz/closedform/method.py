"""The closed-form method: classical Hertz for uncoated cases, extended Hertz otherwise."""

from __future__ import annotations

import time
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from coathertz.case import ContactCase, refuse_stack
from coathertz.closedform.alpha import EQ21_RULE, PAPER_RULE, AlphaRule, Alphas
from coathertz.closedform.extended import predict, refuse_frictionless
from coathertz.errors import CoatHertzError
from coathertz.materials import INTERFACES
from coathertz.methods import require_case
from coathertz.results import ContactResult

RULES = {r.name: r for r in (PAPER_RULE, EQ21_RULE)}
#: Every ``alpha_rule`` name: the paper's rules plus ``refit`` (:mod:`coathertz.closedform.refit`).
RULE_NAMES = (*RULES, "refit")


@dataclass(frozen=True)
class ClosedFormMethod:
    """Extended Hertz predictor as a :class:`~coathertz.methods.Method`.

    Parameters
    ----------
    alpha_rule
        Name of the alpha rule for circular elastic-substrate cases (``paper``: eq 19 with the
        docs/paper-notes.md assumptions; ``eq21-fill``: eq 21's rows for the parts missing from eq 19).
        Elliptical cases always use eq (21), rigid substrates the rigid Appendix A curves.
        ``refit``: the refitted smooth alpha of :mod:`coathertz.closedform.refit` for every configuration
        (circular, rigid substrate, elliptical), with its validated error bound in
        ``meta["refit_bound"]``.
    alphas
        Explicit alpha values overriding the curves.
    warn
        Issue FittedRangeWarning outside the fitted ranges (studies sweep past them on purpose).
    interface
        ``bonded`` (the only interface the closed form models) or ``frictionless``: a coated case
        with a frictionless interface (here or in the case's coating) is refused with a
        :class:`~coathertz.errors.CoatHertzError` naming the methods that model it, never answered as bonded;
        :meth:`supports` is False for it, so studies leave it to the other methods.
    """

    # method metadata (coathertz.methods.Method): class variables, not dataclass fields
    inline: ClassVar[bool] = True  # microseconds per case: the runner solves it in the calling process
    cost: ClassVar[str] = "cheap"
    marker: ClassVar[str] = "-"
    label: ClassVar[str] = "closed form (eqs 1, 17-19, 21)"
    reference_rank: ClassVar[int] = 0  # the thing judged, never a reference
    source_packages: ClassVar[tuple[str, ...]] = ("coathertz.closedform",)

    @classmethod
    def settings_for(cls, resolution: str) -> dict[str, Any]:
        """Studies sweep past the fitted ranges on purpose: no range warnings."""
        return {"warn": False}


    alpha_rule: str = "paper"
    alphas: Alphas | None = None
    warn: bool = True
    name: str = "closed-form"
    interface: str = "bonded"

    def __post_init__(self) -> None:
        if self.alpha_rule not in RULE_NAMES:
            raise CoatHertzError(f"alpha_rule must be one of {sorted(RULE_NAMES)}, got {self.alpha_rule!r}")
        if self.interface not in INTERFACES:
            raise CoatHertzError(f"interface must be one of {list(INTERFACES)}, got {self.interface!r}")

    def settings(self) -> Mapping[str, Any]:
        return {"alpha_rule": self.alpha_rule,
                "alphas": None if self.alphas is None else [self.alphas.a, self.alphas.delta,
                                                            self.alphas.p, self.alphas.b]}

    def supports(self, case: ContactCase) -> bool:
        if case.is_stacked:  # eqs (17)-(19) know one coating
            return False
        return not (case.is_coated and case.interface_for(self.interface) == "frictionless")

    def solve(self, case: ContactCase) -> ContactResult:
        require_case(case, self.name)
        refuse_stack(case, "closed form")
        refuse_frictionless(case, self.interface)
        t0 = time.perf_counter()
        bound = None
        with warnings.catch_warnings():
            if not self.warn:
                warnings.simplefilter("ignore")
            if self.alpha_rule == "refit" and self.alphas is None:
                from coathertz.closedform import refit

                pred, bound = refit.predict(case)
            else:
                rule: AlphaRule | None = RULES.get(self.alpha_rule) if case.is_circular else None
                pred = predict(case, self.alphas, rule)
        meta = {
            "H": list(pred.H),
            "E": list(pred.E),
            "alpha": {k: list(v) for k, v in pred.alpha.items()},
            "E_star": dict(pred.E_star),
            "rule": pred.rule,
            "wall_time": time.perf_counter() - t0,
        }
        if bound is not None:
            from coathertz.closedform.refit.rule import BOUND_MARGIN

            meta["refit_bound"] = {"config": bound.config, "validated": bound.validated,
                                   # None where there is no validated bound (outside the region
                                   # measured, or a configuration that was not fitted)
                                   "bound_percent": bound.bound_values, "margin": BOUND_MARGIN,
                                   "max_abs_err_percent": dict(bound.values),
                                   "region": bound.region, "n_validation": bound.n_points,
                                   "in_range": bound.in_range, "fitted": bound.fitted,
                                   "notes": list(bound.notes), "form": bound.form,
                                   "text": bound.describe()}
        return ContactResult(self.name, pred.delta, pred.a, pred.p0, case.W, pred.r_a, pred.r_b, meta)
