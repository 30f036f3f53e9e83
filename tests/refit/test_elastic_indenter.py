"""Held-out exact solutions for an ELASTIC indenter (``data/elastic_indenter.json``).

The stored values come from the exact axisymmetric method (``data/make_elastic_indenter.py``);
each carries ``refine_rel``, its difference to the refined quadrature (at most 3e-11). None of
them is a training point of the refit's elastic-indenter form
(:mod:`coathertz.closedform.refit.indenter`, trained on a Chebyshev grid in
(log10 H, log10 E, s, gamma)). Measured with the shipped data file, max |error| of delta, a, p0:
steel ball 0.015 / 0.007 / 0.040 %, tungsten carbide 0.006 / 0.003 / 0.084 %, aluminium
0.009 / 0.006 / 0.019 % (the rigid-indenter rule through eq (18) was off by up to 2.44 / 1.08 /
3.20 % on the steel ball before).
"""

from __future__ import annotations

import importlib.util
import json
import warnings
from pathlib import Path

import numpy as np
import pytest

from coathertz.axisym import AxisymMethod
from coathertz.case import ContactCase
from coathertz.closedform.refit.indenter import gamma_of
from coathertz.closedform.refit.rule import load, predict
from coathertz.errors import CoatHertzError, FittedRangeWarning
from coathertz.materials import RIGID, Body, Coating, Material

_SPEC = importlib.util.spec_from_file_location(
    "make_elastic_indenter", Path(__file__).parent / "data" / "make_elastic_indenter.py")
_MAKER = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_MAKER)
case_of = _MAKER.case_of

DATA = json.loads((Path(__file__).parent / "data" / "elastic_indenter.json").read_text())
CASES = DATA["cases"]
QUANTITIES = ("delta", "a", "p0")
#: Re-solve tolerance: the exact method's documented accuracy is about 1e-9 and the stored
#: refinement differences are <= 3e-11; 1e-8 leaves a factor 10 for other BLAS kernels.
RESOLVE_RTOL = 1e-8
#: The issue's goal [%] for delta, a, p0 on these held-out cases.
GOAL = 0.3
#: gamma -> 0 is Hertz through the base at the homogeneous point (E' = 1, beta' = 0), where the
#: rigid indenter's second form is off by its own fit error at E = 1 (measured: 3.0e-4 on p0 at
#: H = 0.3, 3e-8 on a and delta).
HOMOGENEOUS_RTOL = 1e-3


def test_stored_references_are_converged():
    worst = max(c["refine_rel"] for c in CASES)
    assert worst < 1e-9, f"stored exact solutions differ from the refined quadrature by {worst:.2e}"


@pytest.mark.parametrize("row", CASES[::8], ids=lambda r: f"{r['ball']}-E{r['E']:.3g}-H{r['H']:.3g}")
def test_exact_method_reproduces_stored_values(row):
    res = AxisymMethod().solve(case_of(row["ball"], row["E"], row["H"], row["nu_c"]))
    for q in QUANTITIES:
        rel = abs(getattr(res, q) / row[q] - 1.0)
        assert rel < RESOLVE_RTOL, f"{q}: re-solved differs from stored by {rel:.2e}"


def test_refit_on_elastic_indenter_meets_the_goal_with_a_validated_bound():
    """Every held-out case (none of them a training point) goes through the elastic-indenter
    form with a validated bound, without a warning, within the issue's goal, and within the bound
    it prints."""
    rule = load()
    worst = {q: 0.0 for q in QUANTITIES}
    for row in CASES:
        case = case_of(row["ball"], row["E"], row["H"], row["nu_c"])
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            pred, bound = predict(case, rule)
        assert not [x for x in w if issubclass(x.category, FittedRangeWarning)], f"warning for {row}"
        assert bound.validated and bound.config == "indenter", f"{row}: {bound.describe()}"
        printed = bound.bound_values
        for q, key in zip(QUANTITIES, ("delta", "a", "p"), strict=True):
            err = abs(100.0 * (getattr(pred, q) / row[q] - 1.0))
            worst[q] = max(worst[q], err)
            assert err <= printed[key], f"{row}: {q} error {err:.3g} % above the printed bound {printed}"
    assert max(worst.values()) <= GOAL, f"max |error| % on elastic indenters: {worst}"


def test_gamma_one_is_the_rigid_indenter_rule():
    """gamma = 1 (a rigid indenter): the correction's weight vanishes and E' = E, s' = s."""
    rule = load()
    rng = np.random.default_rng(3)
    E, H = 10 ** rng.uniform(-1, 1, 200), 10 ** rng.uniform(-3, 1, 200)
    nu_c, nu_s = rng.uniform(0, 0.5, 200), rng.uniform(0, 0.5, 200)
    got, ref = rule.indenter_bars(E, H, 1.0, nu_c, nu_s), rule.bars("elastic", E, H, nu_c, nu_s)
    for q in ref:
        np.testing.assert_allclose(got[q], ref[q], rtol=1e-12, atol=0, err_msg=q)


def test_fast_path_equals_the_bars_path():
    """The rule's evaluation passes the rigid form's ``ln`` bars straight to the correction
    (``logs=True``); through the bars and ``ln`` (the form's definition) the values agree to the
    round-off of one exp/ln pair (measured 4.4e-16 relative on 1e5 points)."""
    rule = load()
    rng = np.random.default_rng(11)
    n = 3000
    E, H = 10 ** rng.uniform(-1.2, 1.2, n), 10 ** rng.uniform(-3.5, 1.5, n)
    nu_c, nu_s, gamma = rng.uniform(0, 0.5, n), rng.uniform(0, 0.5, n), rng.uniform(0.001, 1.0, n)
    gamma[:300] = 1.0
    form = rule._indenter
    slow = form.log_bars(rule._bars_function("elastic"), E, H, nu_c, nu_s, gamma)
    fast = rule.indenter_bars(E, H, gamma, nu_c, nu_s)
    for q in slow:
        np.testing.assert_allclose(fast[q], np.exp(slow[q]), rtol=1e-14, atol=0, err_msg=q)


def test_exact_limits_of_the_indenter_form():
    """gamma -> 0 (an infinitely compliant indenter: Hertz with the indenter's modulus), H -> 0
    (substrate Hertz) and H -> inf (coating Hertz, the bars (E')^k of the combined kernel's
    thick-coating limit, E' = 1 + gamma (E - 1))."""
    rule = load()
    E = np.array([0.1, 0.5, 2.0, 10.0])
    nu_c, nu_s = np.array([0.0, 0.3, 0.45, 0.2]), np.array([0.5, 0.3, 0.1, 0.3])
    for q, v in rule.indenter_bars(E, 0.3, 1e-12, nu_c, nu_s).items():
        np.testing.assert_allclose(v, 1.0, rtol=HOMOGENEOUS_RTOL, atol=0, err_msg=f"gamma -> 0, {q}")
    for q, v in rule.indenter_bars(E, 1e-9, 0.4, nu_c, nu_s).items():
        np.testing.assert_allclose(v, 1.0, rtol=1e-6, atol=0, err_msg=f"H -> 0, {q}")
    k = {"a": -1.0 / 3.0, "delta": -2.0 / 3.0, "p": 2.0 / 3.0}
    for q, v in rule.indenter_bars(E, 1e9, 0.4, nu_c, nu_s).items():
        np.testing.assert_allclose(v, (1.0 + 0.4 * (E - 1.0)) ** k[q], rtol=1e-6, atol=0,
                                   err_msg=f"H -> inf, {q}")


def test_gamma_is_the_thick_coating_compliance_share():
    assert float(gamma_of(1.0, np.inf)) == 1.0
    assert float(gamma_of(230e9, 230e9)) == pytest.approx(0.5, rel=1e-15)
    with pytest.raises(CoatHertzError, match="gamma"):
        load().indenter_bars(1.0, 1.0, 0.0)


def test_outside_the_validated_box_warns_with_the_measured_bound():
    """A steel ball on a coating 20 times stiffer than the substrate: outside the indenter's
    validated E range, a warning naming the range and the nearest region's measured error."""
    case = case_of("steel", 20.0, 0.5, 0.3)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        _, bound = predict(case, load())
    msg = " ".join(str(x.message) for x in w if issubclass(x.category, FittedRangeWarning))
    assert "elastic indenter" in msg and "outside the validated range" in msg and "gamma in" in msg
    assert "largest |error|" in msg
    assert not bound.validated and bound.bound_values is None


def _ellipse_case(ball: Material | None, E: float, H: float, nu: float = 0.3) -> ContactCase:
    """A ball (rigid if None) with Rx/Ry = 10 (Section 5's Ry = 3 mm, W = 400 N) on steel coated
    with Ec* = E Es*, h = H a0s."""
    sub = Material(200e9, nu)
    coat = Material(E * sub.E_star * (1.0 - nu**2), nu)
    ind = Body(RIGID if ball is None else ball, None, 30e-3, 3e-3)
    base = ContactCase(ind, Body.half_space(sub, Coating(coat, 0.0)), 400.0)
    return ContactCase(ind, Body.half_space(sub, Coating(coat, H * base.a0s)), 400.0)


def test_elastic_indenter_in_an_elliptical_contact_is_spot_checked_not_validated():
    """A steel ellipsoid (Rx/Ry = 10) on a stiff coating: the elastic-indenter form times the
    ellipticity correction at E' (measured on 8 such cases against the FFT at n = 128, whose own
    error is ~0.13 % on the semi-axes: max 0.88 %, was 18.7 % through eq 18), with a warning and
    no bound. Limit 1 %: the ellipse goal."""
    from coathertz.methods import get_method

    case = _ellipse_case(Material(200e9, 0.3), 4.0, 1.0)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        pred, bound = predict(case, load())
    assert any("elliptical contact" in str(x.message) for x in w)
    assert not bound.validated and bound.bound_values is None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = get_method("fft", n=128, keep_fields=False, workers=1).solve(case)
    errs = {q: 100.0 * abs(getattr(pred, q) / getattr(ref, q) - 1.0) for q in ("r_a", "r_b", "delta", "p0")}
    assert max(errs.values()) < 1.0, errs


def test_ellipse_at_other_poisson_ratios_is_outside_the_validated_range():
    """The ellipticity correction was fitted at nu_c = nu_s = 0.3; at other Poisson's ratios it
    misses (measured on 200 Sobol points, nu_c, nu_s in [0, 1/2], against the FFT at n = 128:
    max |error| r_a 1.44 %, r_b 2.49 %, delta 0.83 %, p0 2.45 %, against 0.17 / 0.34 / 0.014 /
    0.38 % at nu = 0.3), so a rigid ellipsoid there gets a warning and no validated bound."""
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        _, bound = predict(_ellipse_case(None, 2.0, 0.5, nu=0.45), load())
    assert any("outside the validated range" in str(x.message) for x in w)
    assert not bound.validated
    _, bound = predict(_ellipse_case(None, 2.0, 0.5), load(), warn=False)
    assert bound.validated
