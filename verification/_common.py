"""Deprecated: the old single-module study framework, kept as a shim so that a study written
as ``from . import _common as C`` still imports. Use ``from coathertz import verification as C``
(see the package docstring); ``ALL`` / ``CF_FFT`` are now the tiers ``expensive`` / ``moderate``.
"""

from coathertz.verification import *  # noqa: F403
from coathertz.verification import __all__ as _public

ALL = "expensive"
CF_FFT = "moderate"
__all__ = [*_public, "ALL", "CF_FFT"]
