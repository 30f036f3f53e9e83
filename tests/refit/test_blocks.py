"""The refit rule's evaluation in one block per core equals the one-block evaluation (to the
round-off of the matrix products, whose summation order may depend on the block's size)."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.closedform.refit import ellipse as EL
from coathertz.closedform.refit import load
from coathertz.closedform.refit import rule as R


@pytest.fixture
def small_blocks(monkeypatch):
    monkeypatch.setattr(R, "PARALLEL_MIN", 1000)  # force threads on a few thousand points
    monkeypatch.setattr(R.os, "cpu_count", lambda: 3)  # three threads even on one core
    monkeypatch.setattr(R, "PIECE", 700)  # eight uneven pieces (each thread's buffers reused)


def _inputs(n=5003):
    rng = np.random.default_rng(3)
    return (10 ** rng.uniform(-1, 1, n), 10 ** rng.uniform(-3, 1, n), rng.uniform(0, 0.5, n),
            rng.uniform(0, 0.5, n), 10 ** rng.uniform(0, 1, n))


def test_blocks_equal_one_block(small_blocks, monkeypatch):
    rule = load()
    E, H, nu_c, nu_s, rho = _inputs()
    for config, args in (("elastic", (E, H, nu_c, nu_s)), ("rigid", (None, H, nu_c))):
        got = rule.bars(config, *args)
        want = rule._bars_function(config)(*args, *(() if config == "elastic" else (0.3,)))
        for q in want:
            np.testing.assert_allclose(got[q], want[q], rtol=1e-14, atol=0)
    got = rule.ellipse_bars(E, H, rho, nu_c, nu_s)
    gamma = np.linspace(0.01, 1.0, E.size)
    got_ind = rule.indenter_bars(E, H, gamma, nu_c, nu_s)
    monkeypatch.setattr(R, "PARALLEL_MIN", 10**9)  # the same call in one block
    monkeypatch.setattr(R, "PIECE", 10**9)  # ... and in one piece
    one = rule.ellipse_bars(E, H, rho, nu_c, nu_s)
    for q in EL.QUANTITIES:
        np.testing.assert_allclose(got[q], one[q], rtol=1e-14, atol=0)
    one = rule.indenter_bars(E, H, gamma, nu_c, nu_s)
    for q in one:
        np.testing.assert_allclose(got_ind[q], one[q], rtol=1e-14, atol=0)


def test_pieces_equal_one_piece(monkeypatch):
    """Each block evaluated in pieces (:data:`~coathertz.closedform.refit.rule.PIECE`) equals the
    one-piece evaluation; pieces of 1000 points cut the 5003 inputs unevenly."""
    rule = load()
    E, H, nu_c, nu_s, rho = _inputs()
    gamma = np.linspace(0.01, 1.0, E.size)
    calls = (lambda: rule.bars("elastic", E, H, nu_c, nu_s),
             lambda: rule.bars("rigid", None, H, nu_c),
             lambda: rule.ellipse_bars(E, H, rho, nu_c, nu_s),
             lambda: rule.indenter_bars(E, H, gamma, nu_c, nu_s))
    whole = [f() for f in calls]
    monkeypatch.setattr(R, "PIECE", 1000)
    for f, want in zip(calls, whole, strict=True):
        got = f()
        for q in want:
            assert got[q].shape == want[q].shape
            np.testing.assert_allclose(got[q], want[q], rtol=1e-14, atol=0, err_msg=q)


def test_ellipse_bars_are_the_circular_bars_times_the_correction():
    """The vectorised ellipse API against its definition (module docstring of refit.ellipse),
    evaluated term by term through the design matrix."""
    rule = load()
    E, H, nu_c, nu_s, rho = (x[:400] for x in _inputs())
    E = np.clip(E, 0.25, 4.0)  # the ellipse box
    base = rule.bars("elastic", E, H, nu_c, nu_s)
    surfs = rule.ellipse_surfaces()
    got = rule.ellipse_bars(E, H, rho, nu_c, nu_s)
    X = EL.variables(E, H, rho)
    for q in EL.QUANTITIES:
        s = surfs[q]
        want = base[EL.BASE[q]] * np.exp(EL.prefactor(E, H, rho) * (s.design(X) @ np.array(s.coef)))
        np.testing.assert_allclose(got[q], want, rtol=1e-12)


@pytest.mark.parametrize("E, H, rho, match", [
    (-1.0, 0.1, 2.0, "0 < E < inf"), (1.0, 0.0, 2.0, "H must be > 0"),
    (1.0, 0.1, 0.5, "finite and >= 1"), (2.0, 0.1, float("inf"), "finite and >= 1"),
])
def test_ellipse_bars_reject_bad_input(E, H, rho, match):
    from coathertz.errors import CoatHertzError

    with pytest.raises(CoatHertzError, match=match):
        load().ellipse_bars(E, H, rho)
