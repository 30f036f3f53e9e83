"""Appendix A curves and the E-mappings of eqs (19) and (21)."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.closedform.alpha import (
    CURVES,
    EQ21_RULE,
    PAPER_RULE,
    AlphaRule,
    Alphas,
    alpha_a_3,
    alpha_p_3,
    breakpoint_jumps,
    eq19_p,
    eq21,
)
from coathertz.errors import CoatHertzError


def test_pieces_are_closed_on_the_right():
    """Appendix A: first interval [0.01, b1], the others (b_k, b_k+1]."""
    assert alpha_a_3(0.05) == 5.51
    assert alpha_a_3(0.0500001) == pytest.approx(-34.22 * 0.05**3 + 43.67 * 0.05**2 - 20.316 * 0.05 + 6.331,
                                                 abs=1e-4)
    assert alpha_p_3(1.2) == pytest.approx(-0.648 * 1.44 + 0.882 * 1.2 + 2.073)
    assert alpha_p_3(3.0) == pytest.approx(0.0854 * 9 - 0.779 * 3 + 3.02)


def test_breakpoint_jumps_reported():
    """The pieces do not join continuously (NOTES.md): the largest jumps are those of
    alpha_a(3) at H = 0.05 (-0.090) and alpha_a(1/3) at H = 0.1 (-0.072)."""
    jumps = {(r["quantity"], r["curve"], r["H"]): r["jump"] for r in breakpoint_jumps()}
    assert jumps[("a", "3", 0.05)] == pytest.approx(-0.0899, abs=1e-3)
    assert jumps[("a", "1/3", 0.1)] == pytest.approx(-0.0716, abs=1e-3)
    assert jumps[("p", "1/3", 0.2)] == pytest.approx(0.0, abs=1e-12)
    assert max(abs(j) for j in jumps.values()) == pytest.approx(0.0899, abs=1e-3)


@pytest.mark.parametrize("q", ["a", "delta", "p"])
def test_rule_reproduces_representative_curves(q):
    H = np.linspace(0.01, 3, 301)
    np.testing.assert_allclose(PAPER_RULE.alpha(q, 1 / 3, H), CURVES[(q, "1/3")](H), rtol=1e-14)
    np.testing.assert_allclose(PAPER_RULE.alpha(q, 3.0, H), CURVES[(q, "3")](H), rtol=1e-14)


def test_eq19_joins_at_one_third_and_three():
    H = np.linspace(0.01, 3, 50)
    a13, a3 = CURVES[("p", "1/3")](H), CURVES[("p", "3")](H)
    for E in (1 / 3, 3.0):
        lo, hi = eq19_p(E * (1 - 1e-12), a13, a3), eq19_p(E * (1 + 1e-12), a13, a3)
        np.testing.assert_allclose(lo, hi, atol=1e-9)


def test_eq21_delta_row_four_is_the_separate_line():
    assert eq21("delta", 3.5, 0.0, 1.2) == pytest.approx(0.225 + 3.5 * (1.2 - 0.225) / 3)
    assert eq21("p", 3.5, 0.0, 1.2) == pytest.approx(1.2 + 0.5 / 0.926)


def test_eq21_fill_rule_differs_from_representative_rule():
    """The two fills of the gaps of eq (19) are different assumptions: show they differ."""
    H = 0.5
    assert PAPER_RULE.alpha("a", 2.0, H) == pytest.approx(alpha_a_3(H))
    assert EQ21_RULE.alpha("a", 2.0, H) != pytest.approx(alpha_a_3(H), rel=1e-3)


def test_bad_inputs():
    with pytest.raises(CoatHertzError, match="missing must be"):
        AlphaRule(missing="guess")
    with pytest.raises(CoatHertzError, match="quantity"):
        PAPER_RULE.alpha("q", 1.0, 1.0)
    with pytest.raises(CoatHertzError, match="H must be > 0"):
        alpha_a_3(0.0)
    with pytest.raises(CoatHertzError, match="alpha_a must satisfy"):
        Alphas(a=-1, delta=1, p=1)
    assert Alphas.parse("a=3.35,p=1.619,delta=1.1") == Alphas(3.35, 1.1, 1.619)
    with pytest.raises(CoatHertzError, match="missing"):
        Alphas.parse("a=1")


def test_alpha_positive_and_held_outside_fitted_range():
    H = np.geomspace(1e-4, 1e3, 400)
    for rule in (PAPER_RULE, EQ21_RULE):
        for q in ("a", "delta", "p"):
            for E in np.geomspace(0.05, 20, 30):
                assert np.all(rule.alpha(q, E, H) > 0), (rule.name, q, E)
    assert alpha_a_3(10.0) == alpha_a_3(3.0)
    assert PAPER_RULE.alpha("p", 10.0, 1.0) == PAPER_RULE.alpha("p", 4.0, 1.0)


def test_one_H_gives_the_numbers_of_the_vectorised_curves():
    """A single H takes a short path (studies ask for one case at a time); every curve and rule
    gives exactly the vectorised values, at and next to the breakpoints and outside the range."""
    from coathertz.closedform import alpha as A

    rng = np.random.default_rng(1)
    bps = sorted({b for v in A.BREAKPOINTS.values() for b in v})
    Hs = np.concatenate([10 ** rng.uniform(-3, 1, 300), bps, [b * (1 + 1e-12) for b in bps],
                         [1e-5, 0.01, 3.0, 10.0]])
    for f in A.CURVES.values():
        assert [f(float(h)).item() for h in Hs] == f(Hs).tolist()
    for rule in (A.PAPER_RULE, A.EQ21_RULE, A.ELLIPTICAL_RULE):
        for q in ("a", "b", "delta", "p"):
            for E in (0.1, 1 / 3, 0.5, 1.0, 2.0, 4.0, 5.0):
                assert [float(rule.alpha(q, E, float(h))) for h in Hs] == rule.alpha(q, E, Hs).tolist()
