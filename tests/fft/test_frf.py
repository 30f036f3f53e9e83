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
