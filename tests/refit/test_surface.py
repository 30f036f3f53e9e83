"""The Chebyshev-product surface: fast evaluation equals the design matrix, clamping, round trip."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.closedform.refit.surface import Surface, chebyshev_table, term_set
from coathertz.errors import CoatHertzError


def _surface(seed=0):
    terms = term_set((5, 4, 2, 2), ((2, 2), (1, 1)))
    c = np.random.default_rng(seed).normal(size=len(terms))
    return Surface(("x", "y", "u", "v"), (-3, -1, 0, 0), (1, 1, 0.5, 0.5), terms, tuple(c))


def test_fast_evaluation_equals_design_matrix():
    s = _surface()
    X = np.random.default_rng(1).uniform([-4, -1.5, 0, 0], [2, 1.5, 0.5, 0.5], size=(70001, 4)).T
    np.testing.assert_allclose(s(X), s.design(X) @ np.array(s.coef), rtol=1e-12, atol=1e-12)


def test_chebyshev_table_matches_numpy():
    x = np.linspace(-1, 1, 11)
    T = chebyshev_table(x, 6)
    for k in range(7):
        np.testing.assert_allclose(T[k], np.polynomial.chebyshev.chebval(x, np.eye(7)[k]), atol=1e-14)


def test_clamped_outside_the_box():
    s = _surface()
    inside = np.array([[1.0], [0.3], [0.2], [0.1]])
    outside = inside.copy()
    outside[0] = 7.0  # far beyond hi = 1
    assert s(outside)[0] == s(inside)[0]


def test_round_trip_and_validation():
    s = _surface()
    assert Surface.from_dict(s.to_dict()) == s
    with pytest.raises(CoatHertzError, match="lo < hi"):
        Surface(("x",), (1.0,), (0.0,), ((0,),), (1.0,))
    with pytest.raises(CoatHertzError, match="shape"):
        s(np.zeros((3, 4)))


def test_shared_evaluation_equals_the_design_matrix():
    """Surfaces of different degrees and term sets in one shared evaluation (the matrix product
    over the union of the terms), across the table and product chunk boundaries."""
    from coathertz.closedform.refit.surface import evaluate_shared

    ss = [_surface(seed) for seed in range(3)]
    terms = term_set((3, 6, 1, 2), ((1, 3), (2, 0)))
    c = np.random.default_rng(9).normal(size=len(terms))
    ss.append(Surface(("x", "y", "u", "v"), (-3, -1, 0, 0), (1, 1, 0.5, 0.5), terms, tuple(c)))
    X = np.random.default_rng(2).uniform([-4, -1.5, 0, 0], [2, 1.5, 0.5, 0.5], size=(70001, 4)).T
    for got, s in zip(evaluate_shared(ss, X), ss, strict=True):
        np.testing.assert_allclose(got, s.design(X) @ np.array(s.coef), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("degrees", [(7,), (6, 3), (8, 4, 3)])
def test_full_tensor_surfaces_equal_the_design_matrix(degrees):
    """1, 2 and 3 variables with every term of the tensor (the corrected form's surfaces)."""
    import itertools

    d = len(degrees)
    terms = tuple(itertools.product(*(range(k + 1) for k in degrees)))
    c = np.random.default_rng(d).normal(size=len(terms))
    s = Surface(tuple("xyz"[:d]), (-1,) * d, (2,) * d, terms, tuple(c))
    X = np.random.default_rng(5).uniform(-1.5, 2.5, size=(d, 40000))
    np.testing.assert_allclose(s(X), s.design(X) @ c, rtol=1e-12, atol=1e-11)


def test_reused_buffers_across_calls_of_different_sizes():
    """The cached plan's work buffers (kept per thread) serve calls of any size in any order:
    a large call, a small one, then a large one again all equal the design matrix."""
    s = _surface(4)
    rng = np.random.default_rng(8)
    for n in (40000, 5, 1, 33333):
        X = rng.uniform([-4, -1.5, 0, 0], [2, 1.5, 0.5, 0.5], size=(n, 4)).T
        np.testing.assert_allclose(s(X), s.design(X) @ np.array(s.coef), rtol=1e-12, atol=1e-12,
                                   err_msg=f"n = {n}")
