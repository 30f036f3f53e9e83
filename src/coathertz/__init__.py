"""coathertz: verification suite for the contact mechanics of coated bodies.

Three independent methods are checked against each other and against the
"extended Hertz" theory of the paper *An extension of the Hertz theory for
three-dimensional coated bodies*:

* the closed-form predictor (:mod:`coathertz.hertz`, :mod:`coathertz.extended`),
* the DC-FFT contact solver (:mod:`coathertz.fft`),
* the axisymmetric finite-element model (:mod:`coathertz.fem`).

All quantities are SI (Pa, m, N) inside the package.
"""

from importlib.metadata import PackageNotFoundError, version

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError, ConvergenceError, FittedRangeWarning
from coathertz.materials import RIGID, Body, Coating, Material
from coathertz.results import ContactResult

try:
    __version__ = version("coathertz")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

__all__ = [
    "RIGID",
    "Body",
    "CoatHertzError",
    "Coating",
    "ContactCase",
    "ContactResult",
    "ConvergenceError",
    "FittedRangeWarning",
    "Material",
    "__version__",
]
