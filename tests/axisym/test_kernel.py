"""Layer factors F(t) of the axisym kernel: limits, thin-layer asymptotics, high-precision values,
and a cross-check against the FFT's independent transfer-matrix FRF (definition only)."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from coathertz.axisym.kernel import layer_factor_bonded, layer_factor_frictionless, pair_compliance
from coathertz.materials import RIGID, Material

T = np.geomspace(1e-5, 40.0, 120)
PAIRS = [
    (Material(400e9, 0.3), Material(200e9, 0.3)),
    (Material(50e9, 0.17), Material(200e9, 0.45)),
    (Material(200e9, 0.0), Material(1e9, 0.5)),
    (Material(200e9, 0.3), RIGID),
    (Material(200e9, 0.5), RIGID),
]


@pytest.mark.parametrize("factory", [layer_factor_bonded, layer_factor_frictionless])
@pytest.mark.parametrize("pair", PAIRS)
def test_limits(factory, pair):
    coat, sub = pair
    F = factory(coat, sub)(T)
    F0 = 0.0 if sub.is_rigid else coat.E_star / sub.E_star  # eq (14)
    assert np.all(np.isfinite(F))
    assert abs(F[-1] - 1.0) < 1e-14  # eq (15)
    assert abs(F[0] - F0) < 1e-3 * max(F0, 1e-2)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45, 0.5])
def test_bonded_rigid_base_high_precision(nu):
    """Against the hyperbolic form evaluated with 50 digits (thin layers included, nu = 0.5 too)."""
    mp.mp.dps = 50
    eps = mp.mpf(3) - 4 * mp.mpf(nu)
    ref = np.array([float((2 * eps * mp.sinh(2 * mp.mpf(x)) - 4 * mp.mpf(x))
                          / (2 * eps * mp.cosh(2 * mp.mpf(x)) + 1 + eps**2 + 4 * mp.mpf(x) ** 2)) for x in T])
    F = layer_factor_bonded(Material(200e9, nu), RIGID)(T)
    assert np.max(np.abs(F / ref - 1)) < 1e-12


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_bonded_rigid_thin_layer_is_constrained_winkler(nu):
    """F ~ (1 - 2 nu) t / (2 (1 - nu)^2): u = p h / M_c, M_c = 2 G (1 - nu)/(1 - 2 nu)."""
    t = np.array([1e-6, 1e-5])
    F = layer_factor_bonded(Material(200e9, nu), RIGID)(t)
    assert np.allclose(F / t, (1 - 2 * nu) / (2 * (1 - nu) ** 2), rtol=1e-4)


def test_incompressible_thin_layer_cubic():
    t = np.array([1e-4, 1e-3])
    F = layer_factor_bonded(Material(200e9, 0.5), RIGID)(t)
    assert np.allclose(F / t**3, 2.0 / 3.0, rtol=1e-5)


def test_frictionless_rigid_thin_layer_is_free_winkler():
    t = np.array([1e-6, 1e-5])
    for nu in (0.0, 0.3, 0.5):
        F = layer_factor_frictionless(Material(200e9, nu), RIGID)(t)
        assert np.allclose(F / t, 0.5, rtol=1e-4)


@pytest.mark.parametrize("pair", PAIRS)
@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_matches_fft_transfer_matrix(pair, interface):
    """Closed forms (this package) against the FFT's 6x6 transfer-matrix solve (an independent
    derivation). The 6x6 solve works with entries of order one, so its absolute round-off is a
    few hundred eps whatever F is (measured: 2e-16 at F = 1.4e-6 on OpenBLAS Haswell kernels,
    which is 1.4e-10 relative); the bound is 1e-10 relative plus an absolute floor of 1000 eps,
    checked where F > 1e-6 (below that the relative comparison says nothing)."""
    from coathertz.fft.frf import layer_factor_tm

    coat, sub = pair
    mine = (layer_factor_bonded if interface == "bonded" else layer_factor_frictionless)(coat, sub)(T)
    tm = layer_factor_tm(T, coat, sub, interface)
    big = np.abs(tm) > 1e-6
    err = np.abs(mine[big] - tm[big])
    bound = 1e-10 * np.abs(tm[big]) + 1000 * np.finfo(float).eps
    assert np.all(err <= bound), f"max err/bound {np.max(err / bound):.3g}"


def test_pair_compliance_decays():
    from coathertz.case import ContactCase

    case = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(400e9, 0.3), 10e-6,
                                                   Material(200e9, 0.3), indenter=Material(200e9, 0.3))
    pc = pair_compliance(case)
    # E_ref: indenter and coating as half-spaces (eq 2)
    assert np.isclose(1 / pc.E_ref, case.body1.material.compliance + case.body2.coating.material.compliance)
    k = np.array([0.0, 24.0 / 10e-6])
    M = pc.M(k)
    # M(0): substrate compliance instead of the coating's
    assert np.isclose(M[0], pc.E_ref * (case.E_star_s**-1) - 1.0)
    assert abs(M[1]) < 1e-17
