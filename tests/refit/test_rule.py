"""The packaged refit rule: limits, continuity, symmetry under swapping the bodies, ranges.

Tolerances: the H -> 0 and H -> inf limits are approached like alpha H (eq 17), so at
H = 1e-9 (resp. 1e7) the bars are within ~1e-7 of their limits (alpha < 30 everywhere).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.closedform.alpha import breakpoint_jumps
from coathertz.closedform.method import ClosedFormMethod
from coathertz.closedform.refit import ellipse as EL
from coathertz.closedform.refit import load
from coathertz.errors import FittedRangeWarning
from coathertz.fitalpha import sweep
from coathertz.materials import RIGID, Body, Coating, Material

RULE = load()
E_GRID = np.geomspace(0.1, 10, 7)
NU_GRID = (0.0, 0.3, 0.49)


@pytest.mark.parametrize("q,k", [("a", -1 / 3), ("delta", -2 / 3), ("p", 2 / 3)])
def test_elastic_limits(q, k):
    m = RULE.model("elastic")
    for nu_c in NU_GRID:
        thin = m.bar(q, E_GRID, 1e-9, nu_c, 0.3)
        thick = m.bar(q, E_GRID, 1e7, nu_c, 0.3)
        np.testing.assert_allclose(thin, 1.0, atol=1e-6, err_msg="H -> 0: substrate Hertz")
        np.testing.assert_allclose(thick, E_GRID**k, rtol=1e-6, err_msg="H -> inf: coating Hertz")


def test_rigid_limits():
    m = RULE.model("rigid")
    nu = np.array([0.0, 0.3, 0.5])
    np.testing.assert_allclose(m.bar("a", None, 1e7, nu), 1.0, rtol=1e-6)
    np.testing.assert_allclose(m.bar("p", None, 1e7, nu), 1.0, rtol=1e-6)
    # thin layer on a rigid base: much stiffer than the coating half-space
    assert np.all(m.bar("p", None, 1e-4, nu) > 3) and np.all(m.bar("delta", None, 1e-4, nu) < 0.3)


def _max_jump(f, lo, hi, n=4001, eps=1e-10):
    x = np.linspace(lo, hi, n)
    return float(np.max(np.abs(f(x + eps) - f(x))))


def test_alpha_bounded():
    """alpha stays in [1e-4, 1e4] (soft cap, model.LN_ALPHA_CAP) over and beyond the box (the
    elastic alpha_p reaches the cap where p0 hardly depends on alpha)."""
    H = np.geomspace(1e-5, 1e3, 200)[:, None, None]
    E = np.geomspace(0.05, 20, 15)[None, :, None]
    nu = np.linspace(0, 0.5, 11)[None, None, :]
    for q in ("a", "delta", "p"):
        for al in (RULE.alpha(q, E, H, nu, 0.3), RULE.alpha(q, E, H, 0.3, nu), RULE.alpha_rigid(q, H, nu)):
            ok = np.all(np.isfinite(al)) and np.all((al >= 1e-4 * (1 - 1e-9)) & (al <= 1e4 * (1 + 1e-9)))
            assert ok, (q, float(al.min()), float(al.max()))


def test_continuity_no_jumps():
    """|ln alpha(x + 1e-10) - ln alpha(x)| < 1e-6 along every variable, across the clamped box edges
    (and the same for the elliptical log-corrections)."""
    el, rg = RULE.model("elastic"), RULE.model("rigid")
    worst = 0.0
    for q in ("a", "delta", "p"):
        for E in (0.1, 0.5, 1.0, 3.0, 10.0):
            worst = max(worst, _max_jump(lambda lh, E=E, q=q: np.log(el.alpha(q, E, 10**lh, 0.3, 0.3)),
                                         -5, 3))
        worst = max(worst, _max_jump(lambda le, q=q: np.log(el.alpha(q, 10**le, 0.5, 0.3, 0.3)), -2, 2))
        worst = max(worst, _max_jump(lambda nu, q=q: np.log(el.alpha(q, 2.0, 0.5, nu, 0.3)), 0.0, 0.5 - 1e-9))
        worst = max(worst, _max_jump(lambda nu, q=q: np.log(rg.alpha(q, None, 0.5, nu)), 0.0, 0.5 - 1e-9))
        worst = max(worst, _max_jump(lambda lh, q=q: np.log(rg.alpha(q, None, 10**lh, 0.3)), -5, 3))
    surfs = RULE.ellipse_surfaces()
    for q in EL.QUANTITIES:
        worst = max(worst, _max_jump(lambda lh, q=q: EL.log_correction(surfs, q, 4.0, 10**lh, 5.0), -4, 2))
        worst = max(worst, _max_jump(lambda lr, q=q: EL.log_correction(surfs, q, 4.0, 0.5, 10**lr), 0, 2))
        worst = max(worst, _max_jump(lambda le, q=q: EL.log_correction(surfs, q, 10**le, 0.5, 5.0), -1, 1))
    assert worst < 1e-6, f"largest jump {worst:.2e}"
    # the same measure flags the paper's Appendix A pieces (the test can fail)
    assert max(abs(np.log(j["right"] / j["left"])) for j in breakpoint_jumps()) > 1e-3


def _pair(swap: bool, indenter=RIGID, coated_rigid=False, Rx=10e-3, Ry=10e-3):
    sub = RIGID if coated_rigid else Material(200e9, 0.25)
    coated = Body.half_space(sub, Coating(Material(600e9, 0.2), 12e-6))
    ind = Body(indenter, None, Rx, Ry)
    return ContactCase(coated, ind, 1.0) if swap else ContactCase(ind, coated, 1.0)


@pytest.mark.parametrize("kw", [{}, {"coated_rigid": True}, {"indenter": Material(300e9, 0.3)},
                                {"Rx": 30e-3, "Ry": 5e-3}])
def test_symmetry_under_swapping_bodies(kw):
    m = ClosedFormMethod("refit", warn=False)
    r1, r2 = m.solve(_pair(False, **kw)), m.solve(_pair(True, **kw))
    for f in ("delta", "a", "p0", "r_a", "r_b"):
        assert getattr(r1, f) == pytest.approx(getattr(r2, f), rel=1e-12), f


def test_two_different_coated_bodies_use_eq18():
    """Two different coated balls: eq (18) sums the two extended compliances (paper Section 6),
    with a warning and no validated bound (two identical ones go through their exact equivalent,
    tests/refit/test_printed_bounds.py)."""
    ball = Body(Material(200e9, 0.28), Coating(Material(406.25e9, 0.3), 12.336e-6), 10e-3, 10e-3)
    other = Body(Material(200e9, 0.28), Coating(Material(300e9, 0.3), 20e-6), 10e-3, 10e-3)
    case = ContactCase(ball, other, 1.0)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        res = ClosedFormMethod("refit").solve(case)
    assert any("rigid indenter on one coated body" in str(x.message) for x in w)
    assert res.meta["refit_bound"]["bound_percent"] is None
    e1 = res.meta["E_star"]
    assert all(np.isfinite(v) for v in e1.values())


def test_warns_outside_validated_range_and_reports_bound():
    inside = sweep.make_case(sweep.Point("elastic", 2.0, 0.5))
    outside = sweep.make_case(sweep.Point("elastic", 30.0, 0.5))
    with warnings.catch_warnings():
        warnings.simplefilter("error", FittedRangeWarning)
        res = ClosedFormMethod("refit").solve(inside)
    b = res.meta["refit_bound"]
    assert b["in_range"] and b["config"] == "elastic" and b["n_validation"] > 0
    with pytest.warns(FittedRangeWarning, match="outside the validated range"):
        res = ClosedFormMethod("refit").solve(outside)
    assert not res.meta["refit_bound"]["in_range"]


def test_ellipse_correction_vanishes_for_circles_and_at_E_1():
    surfs = RULE.ellipse_surfaces()
    for q in EL.QUANTITIES:
        assert np.all(EL.log_correction(surfs, q, np.array([0.3, 4.0]), 0.5, 1.0) == 0.0)
        assert np.all(EL.log_correction(surfs, q, 1.0, np.array([0.05, 2.0]), 8.0) == 0.0)


@pytest.mark.parametrize("q,k", [("a", -1 / 3), ("delta", -2 / 3), ("p", 2 / 3)])
def test_corrected_form_limits_and_continuity(q, k):
    """The corrected form keeps both Hertz limits (elastic substrate), coating Hertz (rigid
    substrate), and has no jumps along H, E, nu_c, nu_s (across the clamped box edges too)."""
    f = RULE.corrected_bar
    for nu_c, nu_s in ((0.0, 0.5), (0.3, 0.3), (0.5, 0.0)):
        np.testing.assert_allclose(f(q, E_GRID, 1e-9, nu_c, nu_s), 1.0, atol=1e-6)
        np.testing.assert_allclose(f(q, E_GRID, 1e9, nu_c, nu_s), E_GRID**k, rtol=1e-6)
    nu = np.array([0.0, 0.3, 0.5])
    np.testing.assert_allclose(f(q, None, 1e9, nu, config="rigid"), 1.0, rtol=1e-6)
    jumps = [_max_jump(lambda lh: np.log(f(q, 3.0, 10**lh, 0.2, 0.4)), -5, 3),
             _max_jump(lambda le: np.log(f(q, 10**le, 0.05, 0.45, 0.05)), -2, 2),
             _max_jump(lambda nu: np.log(f(q, 0.14, 0.12, nu, 0.045)), 0.0, 0.5),
             _max_jump(lambda nu: np.log(f(q, 0.14, 0.12, 0.485, nu)), 0.0, 0.5),
             _max_jump(lambda lh: np.log(f(q, None, 10**lh, 0.49, config="rigid")), -5, 3),
             _max_jump(lambda nu: np.log(f(q, None, 0.002, nu, config="rigid")), 0.0, 0.5)]
    assert max(jumps) < 1e-6, f"largest jump {max(jumps):.2e}"


def test_predictor_uses_the_best_form_and_says_so():
    """``predict`` applies the corrected form's factor for a rigid indenter on one coated body and
    names the form in the bound; with an elastic indenter it falls back to one alpha."""
    case = sweep.make_case(sweep.Point("elastic", 0.14, 0.12, 0.485, 0.045))
    res = ClosedFormMethod("refit", warn=False).solve(case)
    assert RULE.best_form("elastic") == "corrected"
    assert "second closed form" in res.meta["refit_bound"]["text"]
    want = {"a": RULE.bars("elastic", 0.14, 0.12, 0.485, 0.045)["a"][0] * case.normalisers.a0}
    assert res.a == pytest.approx(want["a"], rel=1e-10)


def test_p0_has_no_jump_across_the_ring_box_faces():
    """p0 of the corrected form is max(axis branch, ring branch) inside the ring box only: on the
    box faces the ring branch must lie below the axis branch, else p0 would jump there."""
    from coathertz.fitalpha.sweep import RING_BOX

    def f(E, H, nu_c, nu_s):
        return float(np.log(RULE.corrected_bar("p", E, H, nu_c, nu_s))[0])

    h0, h1 = (10.0**x for x in RING_BOX["log10_H"])
    e0 = 10.0 ** RING_BOX["log10_E"][0]
    nus = ((0.0, 0.5), (0.3, 0.3), (0.5, 0.0), (0.49, 0.01), (0.01, 0.49))
    jumps = [abs(f(E, H * (1 + 1e-12), nc, ns) - f(E, H * (1 - 1e-12), nc, ns))
             for E in (2.0, 3.0, 6.0, 10.0, 30.0) for H in (h0, h1) for nc, ns in nus]
    jumps += [abs(f(e0 * (1 + 1e-12), H, nc, ns) - f(e0 * (1 - 1e-12), H, nc, ns))
              for H in np.linspace(h0, h1, 15) for nc, ns in nus]
    assert max(jumps) < 1e-6, f"largest jump {max(jumps):.2e}"
