"""Deprecated alias of :mod:`coathertz.fem.plastic.edge` (moved there).

The old name is removed in the next release.
"""

# DEPRECATED ALIAS: this module only forwards to the new one (the documentation skips it)
import importlib
import sys
import warnings

warnings.warn("coathertz.fem.plastic_edge moved to coathertz.fem.plastic.edge; "
              "the old name is removed in the next release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("coathertz.fem.plastic.edge")
