"""The shipped refit data's format, shared by the rule that reads it
(:mod:`coathertz.closedform.refit.rule`) and the fit that writes it (:mod:`coathertz.fitalpha`):
the format tag, the bins of the validated error tables and the box of the pressure's ring branch.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

FORMAT = "coathertz-alpha-refit/2"
#: |nu_c - nu_s| of the "matched Poisson's ratios" validation subset reported separately.
NU_MATCHED = 0.1

#: Bin edges of the validated error table, per configuration: (variable, edges).
BINS = {
    "elastic": (("log10_H", (-3.0, -2.0, -1.0, 0.0, 1.0)), ("log10_E", (-1.0, -0.5, 0.0, 0.5, 1.0))),
    "rigid": (("log10_H", (-3.0, -2.0, -1.0, 0.0, 1.0)), ("nu_c", (0.0, 0.25, 0.4, 0.45, 0.5))),
    "ellipse": (("log10_H", (-2.0, -1.0, 0.0, math.log10(3.0))),
                ("log10_E", (math.log10(0.25), 0.0, math.log10(4.0)))),
    #: E edges 0.1, 0.32, 1, 2, 4.5, 10: the paper's E <= 4 apart from the stiff coatings where the
    #: peak pressure leaves the axis (E' = 1 + gamma (E - 1) >~ 3; the largest p0 errors)
    "indenter": (("log10_H", (-3.0, -2.0, -1.0, 0.0, 1.0)),
                 ("log10_E", (-1.0, -0.5, 0.0, math.log10(2.0), math.log10(4.5), 1.0))),
}


def bin_coords(config: str, cols: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Values of the two binning variables of ``config`` from columns E, H, nu_c, gamma."""
    (v1, _), (v2, _) = BINS[config]
    get = {"log10_H": lambda: np.log10(cols["H"]), "log10_E": lambda: np.log10(cols["E"]),
           "nu_c": lambda: np.asarray(cols["nu_c"], dtype=float),
           "gamma": lambda: np.asarray(cols["gamma"], dtype=float)}
    return get[v1](), get[v2]()


def bin_index(edges, x) -> np.ndarray:
    e = np.asarray(edges)
    return np.clip(np.searchsorted(e, x, side="right") - 1, 0, len(e) - 2)


#: Where the maximum pressure can leave the axis (stiff coatings at moderate H; measured on every
#: elastic row of the shipped sweep: E >= 3.3, H in [0.17, 0.50], peak up to 0.86 a off the axis and
#: up to 21 % above the pressure on the axis): the box of the ring branch
#: of p0 (:mod:`coathertz.closedform.refit.corrected`), in (log10 H, log10 E); s spans [0, 1]. E above 10 is
#: inside too (the branch is clamped there like every surface).
RING_BOX = {"log10_H": (-1.0, math.log10(0.8)), "log10_E": (math.log10(2.0), 1.0), "s": (0.0, 1.0)}
