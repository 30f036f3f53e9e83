"""Extended Hertz, eqs (17)-(18): limits, consistency of the scalar and vectorised paths, inversion."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from coathertz import RIGID, Body, Coating, ContactCase, Material
from coathertz.closedform.alpha import Alphas
from coathertz.closedform.extended import (
    E1_over_Ec,
    E1_star,
    constants_from_ratio,
    invert_alpha,
    predict,
    predict_bar,
)
from coathertz.errors import FittedRangeWarning
from coathertz.materials import coating_constants


def test_E1_limits_eq14_eq15():
    c, s = Material(380e9, 0.17), Material(200e9, 0.3)
    k = coating_constants(c, s)
    assert E1_star(c.E_star, k.lam, k.kappa, 2.0, 0.0) == pytest.approx(s.E_star, rel=1e-13)  # eq (14)
    assert E1_star(c.E_star, k.lam, k.kappa, 2.0, 50.0) == pytest.approx(c.E_star, rel=1e-13)  # eq (15)
    kr = coating_constants(c, RIGID)
    assert np.isinf(E1_over_Ec(kr.lam, kr.kappa, 2.0, 0.0))
    assert E1_over_Ec(kr.lam, kr.kappa, 2.0, 1e-3) > 100


def test_constants_from_ratio_match_materials():
    c, s = Material(380e9, 0.17), Material(200e9, 0.3)
    k = coating_constants(c, s)
    lam, kappa = constants_from_ratio(c.E_star / s.E_star, 0.17, 0.3)
    assert (lam, kappa) == pytest.approx((k.lam, k.kappa), rel=1e-13)


def test_predict_bar_matches_case_prediction():
    s = Material(210e9, 0.3)
    for E, H in ((1 / 3, 0.2), (3.0, 1.1), (0.8, 0.05)):
        c = Material(E * 210e9, 0.3)
        case = ContactCase.sphere_on_coated_half_space(0.01, 50.0, c, 1.0, s)
        case = case.with_thickness(H * case.a0s)
        r = predict(case)
        assert predict_bar("a", E, H) == pytest.approx(r.a / case.a0s, rel=1e-12)
        assert predict_bar("delta", E, H) == pytest.approx(r.delta / case.delta0s, rel=1e-12)
        assert predict_bar("p", E, H) == pytest.approx(r.p0 / case.p0s, rel=1e-12)


def test_invert_alpha_roundtrip_and_none():
    E = np.array([0.25, 1 / 3, 0.8, 1.25, 3.0, 4.0])[:, None]
    H = np.array([0.05, 0.3, 1.0, 2.5])[None, :]
    for q in ("a", "delta", "p"):
        alpha = np.full(np.broadcast(E, H).shape, 1.7)
        bar = predict_bar(q, E, H, alpha=alpha)
        back = invert_alpha(q, bar, E, H)
        np.testing.assert_allclose(predict_bar(q, E, H, alpha=back), bar, rtol=1e-10)
    # a_bar below the coating-Hertz limit E^(-1/3) cannot be represented for E = 3
    assert np.isnan(invert_alpha("a", 0.5, 3.0, 1.0))


def test_rigid_substrate_bars():
    case = ContactCase.sphere_on_coated_half_space(0.01, 100.0, Material(200e9, 0.3), 1.0, RIGID)
    case = case.with_thickness(0.4 * case.a0c)
    r = predict(case)
    assert r.rule == "rigid"
    assert predict_bar("p", None, 0.4, rigid_substrate=True) == pytest.approx(r.p0 / case.p0c, rel=1e-12)
    assert r.p0 > case.p0c and r.a < case.a0c  # thin layer on a rigid base is stiffer


def test_fitted_range_warnings():
    s = Material(210e9, 0.3)
    case = ContactCase.sphere_on_coated_half_space(0.01, 50.0, Material(6 * 210e9, 0.3), 1e-3, s)
    with pytest.warns(FittedRangeWarning) as rec:
        predict(case)
    text = " ".join(str(w.message) for w in rec)
    assert "[0.01, 3]" in text and "[1/4, 4]" in text
    soft_nu = ContactCase.sphere_on_coated_half_space(0.01, 50.0, Material(210e9, 0.45), 10e-6, s)
    with pytest.warns(FittedRangeWarning, match="nu_c = 0.45"):
        predict(soft_nu)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        predict(case, Alphas(1, 1, 1))  # explicit alphas: nothing to warn about


def test_elliptical_identical_coating_is_hertz():
    m = Material(150e9, 0.28)
    case = ContactCase(Body(RIGID, None, 17.4e-3, 3e-3), Body.half_space(m, Coating(m, 50e-6)), 400.0)
    r = predict(case)
    h = case.hertz_s
    assert (r.r_a, r.r_b, r.delta, r.p0) == pytest.approx((h.r_a0, h.r_b0, h.delta0, h.p0), rel=1e-13)
    assert set(r.alpha) == {"a", "b", "delta", "p"}
