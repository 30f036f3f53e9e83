"""The layer FRF: eq (13) against the independent transfer-matrix solution."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.errors import CoatHertzError
from coathertz.fft.frf import Layer, layer_factor_eq13, layer_factor_tm, taylor_coefficients
from coathertz.materials import RIGID, Material

T = np.concatenate([[1e-8], np.geomspace(1e-3, 30, 60)])
PAIRS = [
    (Material(380e9, 0.17), Material(200e9, 0.3)),  # B4C on steel (Section 6)
    (Material(50e9, 0.3), Material(200e9, 0.3)),  # soft coating
    (Material(406.25e9, 0.3), Material(200e9, 0.28)),  # Keer et al.
    (Material(200e9, 0.5), Material(70e9, 0.2)),  # incompressible coating
    (Material(200e9, 0.3), RIGID),
    (Material(200e9, 0.5), RIGID),
]


@pytest.mark.parametrize(("coating", "substrate"), PAIRS)
def test_eq13_equals_transfer_matrix_bonded(coating, substrate):
    a = layer_factor_eq13(T, coating, substrate)
    b = layer_factor_tm(T, coating, substrate, "bonded")
    np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize(("coating", "substrate"), PAIRS)
@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_limits(coating, substrate, interface):
    """F(0) = Ec*/Es* (eq 14; 0 on a rigid base) and F(inf) = 1 (eq 15)."""
    layer = Layer(coating, substrate, interface)
    F = layer.factor(np.array([1e-9, 40.0]))
    assert F[0] == pytest.approx(layer.F0, rel=1e-6, abs=1e-8)
    assert F[1] == pytest.approx(1.0, abs=1e-12)


def test_frictionless_on_rigid_base_closed_form():
    """Frictionless rigid base: F = (cosh 2t - 1)/(sinh 2t + 2t), independent of nu."""
    t = np.geomspace(1e-3, 15, 40)
    ref = (np.cosh(2 * t) - 1) / (np.sinh(2 * t) + 2 * t)
    for nu in (0.0, 0.3, 0.5):
        F = layer_factor_tm(t, Material(1e9, nu), RIGID, "frictionless")
        np.testing.assert_allclose(F, ref, rtol=1e-11, atol=1e-13)


def test_frictionless_differs_from_bonded_and_thin_incompressible_limit():
    co = Material(200e9, 0.5)
    t = np.array([0.01, 0.1, 1.0])
    fb = layer_factor_tm(t, co, RIGID, "bonded")
    ff = layer_factor_tm(t, co, RIGID, "frictionless")
    assert np.all(ff > fb)
    # thin incompressible bonded layer: compliance ~ (2/3) t^3 (Matthewson's regime)
    c = taylor_coefficients(lambda z: layer_factor_eq13(z, co, RIGID), n=4)
    np.testing.assert_allclose(c, [0, 0, 0, 2 / 3], atol=1e-12)


def test_same_material_bonded_is_half_space():
    m = Material(200e9, 0.3)
    np.testing.assert_allclose(layer_factor_tm(T, m, m), 1.0, rtol=1e-13)
    assert not np.allclose(layer_factor_tm(T[1:], m, m, "frictionless"), 1.0)


def test_bad_interface():
    with pytest.raises(CoatHertzError, match="interface"):
        Layer(Material(1e9, 0.3), RIGID, "glued")
    with pytest.raises(CoatHertzError, match="interface"):
        layer_factor_tm(T, Material(1e9, 0.3), RIGID, "glued")


@pytest.mark.parametrize("E_ratio", [4.0, 10.0])
def test_taylor_coefficients_of_a_stiff_coating_with_a_pole_near_zero(E_ratio):
    """The layer factor of a stiff coating has a pole at t = -0.13 (E = 4) or -0.05 (E = 10):
    a fixed Cauchy radius of 0.1 gave F(0) = 9.18 for 10. The halving radius must give
    F(0) = Ec*/Es* and a series that matches F on the real axis to O(t^3)."""
    from coathertz.fft.influence import LayerSplit

    s = Material(200e9, 0.3)
    co = Material(E_ratio * s.E_star * (1 - 0.09), 0.3)
    layer = Layer(co, s)
    c = taylor_coefficients(layer.factor, n=3, radius=0.1, m=48)
    assert c[0] == pytest.approx(E_ratio, rel=1e-12)
    t = np.array([1e-3, 2e-3])
    resid = layer.factor(t) - (c[0] + c[1] * t + c[2] * t * t)
    ratio = resid[1] / resid[0]  # O(t^3): 8
    assert ratio == pytest.approx(8.0, rel=0.05), (resid, ratio)
    # the split's remainder is O(t^2) (it was -16 at t -> 0 for E = 10)
    sp = LayerSplit.of(layer)
    r = sp.remainder(np.array([1e-4, 2e-4])) / np.array([1e-4, 2e-4]) ** 2
    assert r[1] == pytest.approx(r[0], rel=0.05), r


@pytest.mark.parametrize("pole", [0.02, 0.004])
def test_taylor_coefficients_see_a_pole_inside_the_first_circle(pole):
    """A pole well inside the circle (both 0.1 and 0.05 enclose 0.02) leaves the Cauchy
    integrals of successive circles in agreement but wrong; the series check catches it."""
    c = taylor_coefficients(lambda z: 1.0 / (z + pole), n=3, radius=0.1)
    np.testing.assert_allclose(c, [1 / pole, -1 / pole**2, 1 / pole**3], rtol=1e-9)


def test_taylor_coefficients_refuse_a_singularity_at_the_origin():
    with pytest.raises(CoatHertzError, match="did not converge"):
        taylor_coefficients(lambda z: 1.0 / (z + 1e-6), n=2)
