"""Literature approximations, eqs (8)-(12): internal consistency and limits."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import special

from coathertz.closedform.hertz import hertz_circular
from coathertz.closedform.literature import (
    keer,
    matthewson_a_bar,
    matthewson_c,
    matthewson_load,
    stevanovic_elastic,
    stevanovic_rigid,
    vorovich_ustinov,
)
from coathertz.errors import FittedRangeWarning


def test_vorovich_tends_to_one_and_keer_rigid_indenter():
    d, a, p = vorovich_ustinov(1e4)
    assert (d, a, p) == pytest.approx((1, 1, 1), abs=1e-4)
    H = np.array([1.6, 2.0, 4.0])
    d8, a8, _ = vorovich_ustinov(H)
    d9, a9 = keer(H, 1.0)
    # eq (9) with C_E = 1 is eq (8) without the H^-6 term of (8a) and the H^-7 term of (8b)
    np.testing.assert_allclose(d9 - d8, 0.197 / H**6, rtol=0, atol=1e-15)
    np.testing.assert_allclose(a9 - a8, 0.004 / H**7, rtol=0, atol=1e-15)


def test_matthewson_two_forms_agree():
    """Eq (10): the load form and the a_bar form are the same relation once a0c is from eq (1a)."""
    Ec, nu, R = 2e9, 0.5, 0.01
    for tau in (0.05, 0.1, 0.3):
        a_bar = matthewson_a_bar(tau, nu)
        # choose a, then W from the load form; a0c for that W from Hertz with Ec* = Ec/(1-nu^2)
        a = 1e-4
        W = matthewson_load(a, R, tau, Ec, nu)
        a0c = hertz_circular(W, R, Ec / (1 - nu**2)).a0
        assert a / a0c == pytest.approx(a_bar, rel=1e-12)


def test_matthewson_c_against_unscaled_bessel():
    x = np.sqrt(6) / (3 * np.array([0.2, 0.5, 1.0, 3.0]))
    c = matthewson_c(np.sqrt(6) / (3 * x))
    np.testing.assert_allclose(c, x * special.k0(x) / special.k1(x), rtol=1e-13)


def test_stevanovic_limits():
    assert stevanovic_rigid(1e6) == pytest.approx(1.0, abs=1e-12)
    assert stevanovic_rigid(1e-12) == pytest.approx(-0.04, abs=1e-6)
    g = 3 ** (1 / 3)
    assert stevanovic_elastic(1e-9, g) == pytest.approx(1.0, abs=1e-6)
    assert stevanovic_elastic(1e3, g) == pytest.approx(g, rel=1e-9)


def test_validity_warnings():
    with pytest.warns(FittedRangeWarning, match="Vorovich"):
        vorovich_ustinov(1.0)
    with pytest.warns(FittedRangeWarning, match="Matthewson"):
        matthewson_a_bar(0.8)
    with pytest.warns(FittedRangeWarning, match="nu_c = 0.5"):
        matthewson_a_bar(0.1, 0.3)
