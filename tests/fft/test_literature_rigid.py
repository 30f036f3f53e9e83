"""Rigid substrate against the literature: Matthewson eq (10) and Vorovich-Ustinov eq (8).

Nothing is tuned to these solutions; the tests pin what the comparison shows:

* Matthewson's thin incompressible layer (eq 10) is the **bonded** layer: the bonded FFT radius
  approaches it as tau = h/a -> 0 (difference about -0.37 tau), the frictionless one does not.
* The Vorovich-Ustinov series (eq 8) matches the layer resting **without friction** on the
  base: a and p agree to < 1e-3 for tau >= 2 and delta's difference falls like H^-3 or faster;
  the bonded layer's delta differs by a few percent, O(1/H) (its 1/H coefficient is 0.751
  against the series' 0.504; the frictionless FRF gives 0.496).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.closedform import literature as lit
from coathertz.errors import FittedRangeWarning
from coathertz.fft.method import FFTMethod
from coathertz.materials import RIGID, Material

INCOMPRESSIBLE = Material(200e9, 0.5)
BASE = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, INCOMPRESSIBLE, 1.0, RIGID)


def _solve(H, interface, n=128):
    case = BASE.with_thickness(H * BASE.a0c)
    r = FFTMethod(n=n, interface=interface).solve(case)
    return r, case


def _matthewson_diff(H, interface, n=128):
    r, case = _solve(H, interface, n)
    tau = case.body2.coating.h / r.a
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FittedRangeWarning)
        am = lit.matthewson_a_bar(tau)
    return tau, r.a / case.a0c / am - 1


def test_matthewson_is_the_bonded_limit():
    rows = [_matthewson_diff(H, "bonded") for H in (0.1, 0.05, 0.02)]
    taus, diffs = np.array(rows).T
    msg = f"tau {taus}, a/a_Matthewson - 1 {diffs}"
    assert np.all(np.diff(np.abs(diffs)) < 0), msg  # shrinks as tau -> 0
    assert abs(diffs[-1]) < 0.04, msg
    assert np.all(np.abs(diffs / taus) < 0.5), msg  # O(tau)
    _, dfric = _matthewson_diff(0.02, "frictionless")
    assert abs(dfric) > 10 * abs(diffs[-1])


def _vu_diffs(H, interface):
    r, case = _solve(H, interface)
    d, a, p = lit.vorovich_ustinov(H, warn=False)
    return np.array([r.delta / case.delta0c - d, r.a / case.a0c - a, r.p0 / case.p0c - p])


def test_vorovich_ustinov_is_the_frictionless_layer():
    f3, f5 = _vu_diffs(3.0, "frictionless"), _vu_diffs(5.0, "frictionless")
    b5 = _vu_diffs(5.0, "bonded")
    msg = f"(delta, a, p) diffs: frictionless H=3 {f3}, H=5 {f5}; bonded H=5 {b5}"
    assert np.all(np.abs(f3[1:]) < 1e-3) and np.all(np.abs(f5[1:]) < 1e-3), msg
    assert abs(f5[0]) < abs(f3[0]) / 2.5, msg  # delta's difference falls at least like H^-2
    assert abs(b5[0]) > 5 * abs(f5[0]), msg


@pytest.mark.slow
def test_matthewson_difference_is_not_a_grid_artefact():
    d128 = _matthewson_diff(0.02, "bonded", 128)[1]
    d256 = _matthewson_diff(0.02, "bonded", 256)[1]
    assert d256 == pytest.approx(d128, abs=2e-3)
