"""coathertz: verification suite for the contact mechanics of coated bodies.

Four independent methods check the "extended Hertz" theory of the paper *An extension of
the Hertz theory for three-dimensional coated bodies* and each other:

* the closed form (:mod:`coathertz.closedform`: Hertz, the extended theory, the refitted rule),
* the DC-FFT contact solver (:mod:`coathertz.fft`),
* the axisymmetric finite-element model with J2 plasticity (:mod:`coathertz.fem`),
* the exact axisymmetric integral-equation method (:mod:`coathertz.axisym`), the arbiter of
  circular cases.

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
