"""Model validity of a result: the one check every method's result passes through.

Hertz, the extended theory, the FFT solver and the FE model all assume small strains and a
contact small against the bodies (half-space assumption): ``a / R`` small. Above
``A_OVER_R_MAX = 0.1`` their numbers are still computed, but they no longer describe the
physical contact. :func:`check` warns (:class:`~coathertz.errors.ModelValidityWarning`) and
records the reason in ``result.meta["validity"]``.

The CLI subcommands (``coathertz.cli._common.finish``) and the study runner
(``coathertz.runner.solve_chunk``) pass every result through it; a method may call it at the end
of its own ``solve`` too (the exact method and the FE do, so that a caller of the Python API is
warned), and a result checked once is not warned about again. No method keeps its own copy of
the rule.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

from coathertz.case import ContactCase
from coathertz.errors import ModelValidityWarning
from coathertz.results import ContactResult

#: Largest contact radius over equivalent radius for which the half-space, small-strain
#: assumptions are taken to hold (Johnson, Contact Mechanics, Section 4.2).
A_OVER_R_MAX = 0.1


def problems(case: ContactCase, result: ContactResult) -> list[str]:
    """Reasons why ``result`` lies outside the model's assumptions (empty if none)."""
    out = []
    R = case.R
    if math.isfinite(R) and R > 0 and math.isfinite(result.a):
        ratio = result.a / R
        if ratio > A_OVER_R_MAX:
            out.append(
                f"a/R = {ratio:.3g} > {A_OVER_R_MAX:g} (a = {result.a:.4g} m, R = {R:.4g} m): "
                "the half-space and small-strain assumptions of the model fail; "
                "the numbers do not describe the physical contact"
            )
    return out


def check(case: ContactCase, result: ContactResult, *, warn: bool = True) -> ContactResult:
    """``result``, with ``meta["validity"]`` set and a :class:`~coathertz.errors.ModelValidityWarning` issued
    (unless ``warn`` is false) when it lies outside the model's assumptions."""
    msgs = problems(case, result)
    if not msgs:
        return result
    text = "; ".join(msgs)
    if result.meta.get("validity") == text:  # already checked (by the method itself): warn once
        return result
    if warn:
        warnings.warn(f"{result.method}: {text}", ModelValidityWarning, stacklevel=2)
    return replace(result, meta={**dict(result.meta), "validity": text})
