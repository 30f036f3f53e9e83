"""Extended Hertz, refitted: smooth closed-form alpha fits with validated bounds.

Public API
----------
:func:`~coathertz.closedform.refit.rule.load` / :class:`~coathertz.closedform.refit.rule.RefitRule`
    The packaged rule (``coathertz/data/alpha_refit.json``): ``rule.alpha(q, E, H, nu_c, nu_s)``,
    ``rule.alpha_rigid(q, H, nu_c)``, ``rule.model(config).bar(q, ...)`` (vectorised bars),
    ``rule.bound(config, ...)`` (validated error bound of the inputs).
:func:`~coathertz.closedform.refit.rule.predict`
    ``predict(case) -> (ExtendedPrediction, Bound)``: eqs (1)/(5), (17), (18) with the refit.
:mod:`~coathertz.fitalpha.sweep`, :mod:`~coathertz.fitalpha.build`
    Training/validation sweeps through the result store, and the fit that writes the data file
    (``coathertz fit-alpha``).
"""

from coathertz.closedform.refit.rule import Bound, RefitRule, load, predict

__all__ = ["Bound", "RefitRule", "load", "predict"]
