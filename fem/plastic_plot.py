"""Deprecated alias of :mod:`coathertz.fem.plastic.plot` (moved there).

The old name is removed in the next release.
"""

# DEPRECATED ALIAS: this module only forwards to the new one (the documentation skips it)
import importlib
import sys
import warnings

warnings.warn("coathertz.fem.plastic_plot moved to coathertz.fem.plastic.plot; "
              "the old name is removed in the next release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("coathertz.fem.plastic.plot")
