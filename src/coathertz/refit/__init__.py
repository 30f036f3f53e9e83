"""Deprecated: the refitted rule moved to :mod:`coathertz.closedform.refit` and its offline fit
to :mod:`coathertz.fitalpha`; this package and its modules forward there and are removed in the
next release."""

# DEPRECATED ALIAS: this package only forwards to the new ones (the documentation skips it)
import warnings

from coathertz.closedform.refit import Bound, RefitRule, load, predict

warnings.warn("coathertz.refit moved to coathertz.closedform.refit (the rule) and coathertz.fitalpha "
              "(the fit); the old name is removed in the next release", DeprecationWarning, stacklevel=2)

__all__ = ["Bound", "RefitRule", "load", "predict"]
