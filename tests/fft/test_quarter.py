"""The CG iteration on the quarter plane (``polonsky_keer(symmetric=True)``).

A point contact's problem is even in ``x`` and ``y`` about the centre cell; the quarter-plane
operator (:meth:`Convolver.quarter`, a DCT-I convolution) must be the whole grid's operator
restricted to even fields, to round-off, and the solve must give the whole grid's solution.
"""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.closedform.hertz import pressure_elliptical
from coathertz.fft.grid import Grid
from coathertz.fft.method import (
    FFTMethod,
    case_coefficients,
    case_quadrant,
    estimate_axes,
    initial_gap,
    prolong_pressure,
)
from coathertz.fft.solver import Convolver, _is_even, _unfold, get_backend, polonsky_keer

from .conftest import coated


def _even_field(rng, B: int, ny: int, nx: int) -> np.ndarray:
    My, Mx = ny - ny // 2, nx - nx // 2
    return _unfold(rng.random((B, My, Mx)), ny, nx)


@pytest.mark.parametrize(("ny", "nx"), [(32, 32), (33, 33), (32, 27), (48, 64)])
def test_quarter_operator_is_the_whole_grid_operator(ny, nx):
    """``K * p`` and the preconditioner on the quarter plane equal the whole grid's for even
    ``p`` (batch of 2 kernels), to round-off of the transforms (~1e-16 x log n, bound 1e-13)."""
    rng = np.random.default_rng(1)
    cases = [coated(3.0, 0.3), coated(0.25, 0.05)]
    g = Grid(nx, ny, 1e-6, 1.3e-6)
    conv = Convolver(np.stack([case_coefficients(c, g) for c in cases]), get_backend("numpy", 1))
    lazy = Convolver.from_quadrant(np.stack([case_quadrant(c, g) for c in cases]), get_backend("numpy", 1))
    p = _even_field(rng, 2, ny, nx)
    cy, cx = ny // 2, nx // 2
    q = np.ascontiguousarray(p[..., cy:, cx:])
    out = np.empty_like(q)
    for c in (conv, lazy):
        for whole, quarter in ((conv, c.quarter), (conv.precondition, c.precondition_quarter)):
            ref = whole(p)[..., cy:, cx:]
            quarter(q, out)
            err = float(np.max(np.abs(out - ref)) / np.max(np.abs(ref)))
            assert err < 1e-13, f"{quarter.__name__}: relative difference {err:.3g} (round-off 1e-13)"
    # the whole grid from the quarter plane, the cells without a mirror image included
    edge = np.empty((2, cy + 1, cx + 1))
    lazy.quarter(q, edge)
    whole = _unfold(edge, ny, nx)
    err = float(np.max(np.abs(whole - conv(p))) / np.max(np.abs(whole)))
    assert err < 1e-13, f"whole grid from the quarter plane: relative difference {err:.3g}"
    assert np.array_equal(lazy.khat, conv.khat) and np.array_equal(lazy.mhat, conv.mhat)


def test_quarter_add_cells_matches_the_operator():
    """The direct response of a few quarter-plane cells (their mirror images included) is the
    operator's, to round-off (centre, on-axis and off-axis cells)."""
    case = coated(3.0, 0.3)
    n = 32
    g = Grid(n, n, 1e-6, 1e-6)
    conv = Convolver(case_coefficients(case, g), get_backend("numpy", 1))
    My, Mx = conv.quadrant_shape
    q = np.zeros((1, My, Mx))
    cells = [(0, 0, 1.0), (0, 5, 2.0), (7, 0, -0.5), (9, 13, 3.0), (My - 1, Mx - 1, 1.5)]
    for i, j, c in cells:
        q[0, i, j] = c
    ref = np.empty_like(q)
    conv.quarter(q, ref)
    u = np.zeros_like(q)
    iy, ix, c = zip(*cells, strict=True)
    conv.add_cells_quarter(u, 0, np.array(iy), np.array(ix), np.array(c), np.empty((My, Mx)))
    err = float(np.max(np.abs(u - ref)) / np.max(np.abs(ref)))
    assert err < 1e-13, f"relative difference {err:.3g}"


@pytest.mark.parametrize("n", [64, 65])
def test_quarter_solve_matches_whole_grid(n):
    """From an even start, the quarter-plane CG gives the whole grid's solution: the iteration
    is the same to round-off, both stop at ``tol = 1e-10`` (P&K's measure), so p, u and delta
    agree far inside 1e-7 (measured ~1e-9 at n = 128), the iteration counts within one."""
    cases = [coated(3.0, 0.3), coated(0.25, 0.05)]
    grid = FFTMethod(n=n).grid_for(cases[0])
    kern = np.stack([case_coefficients(c, grid) for c in cases])
    g0 = np.stack([initial_gap(c, grid) for c in cases])
    X, Y = np.meshgrid(grid.x, grid.y)
    ra, rb = estimate_axes(cases[0])
    p0 = np.stack([pressure_elliptical(X, Y, 0.8 * ra, 0.8 * rb, 1.0)] * 2)
    assert _is_even(p0, n, n)
    W = [c.W for c in cases]
    sols = [polonsky_keer(Convolver(kern, get_backend("numpy", 1)), g0, W, grid.cell_area,
                          tol=1e-10, p_init=p0, precondition=True, symmetric=s) for s in (False, True)]
    whole, quarter = sols
    for name in ("p", "u"):
        a, b = getattr(whole, name), getattr(quarter, name)
        err = float(np.max(np.abs(a - b)) / np.max(np.abs(a)))
        assert err < 1e-7, f"{name}: relative difference {err:.3g}"
    assert np.allclose(quarter.delta, whole.delta, rtol=1e-9, atol=0)
    assert np.all(np.abs(quarter.iterations - whole.iterations) <= 1), (whole.iterations, quarter.iterations)
    assert quarter.convolutions <= whole.convolutions + 4


def test_quarter_solve_falls_back_where_the_contact_reaches_the_edge():
    """A grid too small for the contact (half-width 0.8 of the Hertz radius): the cells without
    a mirror image (row and column 0) penetrate on the quarter plane, so the solve goes on on the
    whole grid; the result is the whole grid's solution (to 1e-7 at tol 1e-10)."""
    case = coated(3.0, 0.3)
    ra, rb = estimate_axes(case)
    grid = Grid(32, 32, 0.8 * ra / 15.5, 0.8 * rb / 15.5)
    kern = case_coefficients(case, grid)
    g0 = initial_gap(case, grid)
    X, Y = np.meshgrid(grid.x, grid.y)
    p0 = pressure_elliptical(X, Y, 0.5 * ra, 0.5 * rb, 1.0)
    sols = [polonsky_keer(Convolver(kern, get_backend("numpy", 1)), g0, case.W, grid.cell_area,
                          tol=1e-10, p_init=p0, precondition=True, symmetric=s) for s in (False, True)]
    whole, quarter = sols
    assert whole.p[0, 0, :].max() > 0 and whole.p[0, :, 0].max() > 0  # the edge is in contact
    err = float(np.max(np.abs(quarter.p - whole.p)) / np.max(whole.p))
    assert err < 1e-7, f"relative difference {err:.3g}"
    assert quarter.p[0, 0, :].max() > 0


def test_uneven_start_takes_the_whole_grid():
    """A start that is not even (or has pressure on a cell without mirror image) is solved on the
    whole grid: the same result as ``symmetric=False``, bit for bit."""
    case = coated(0.25, 0.05)
    grid = FFTMethod(n=32).grid_for(case)
    kern = case_coefficients(case, grid)
    g0 = initial_gap(case, grid)
    X, Y = np.meshgrid(grid.x, grid.y)
    ra, rb = estimate_axes(case)
    p0 = pressure_elliptical(X - grid.dx, Y, 0.8 * ra, 0.8 * rb, 1.0)
    assert not _is_even(p0, 32, 32)
    a, b = (polonsky_keer(Convolver(kern, get_backend("numpy", 1)), g0, case.W, grid.cell_area,
                          tol=1e-8, p_init=p0, precondition=True, symmetric=s) for s in (False, True))
    assert np.array_equal(a.p, b.p) and a.convolutions == b.convolutions


@pytest.mark.parametrize(("nc", "nf", "ratio"),
                         [(32, 64, 2.0), (64, 128, 2.0), (128, 128, 1.37), (64, 150, 2.3)])
def test_prolonged_start_is_even(nc, nf, ratio):
    """An even coarse pressure prolonged (and cut to the contact) is even to round-off: the cut
    at the indicator's midline no longer depends on the weights' round-off (it made starts
    uneven by up to a fifth of their peak, and the whole grid had to take them)."""
    coarse = Grid(nc, nc, 1.0, 1.0)
    half = (nf / 2 - 0.5) * ratio / (nc / 2 - 0.5)
    fine = Grid(nf, nf, half, half)
    X, Y = np.meshgrid(coarse.x, coarse.y)
    for r in (7.0, 10.0, 12.5, 0.4 * nc):
        pc = pressure_elliptical(X, Y, r, 0.8 * r, 1.0)
        assert _is_even(pc, nc, nc)
        pf = prolong_pressure(pc, coarse, fine)
        assert _is_even(pf, nf, nf), f"r = {r}: the prolonged start is not even"


@pytest.mark.parametrize("n", [64, 65])
def test_method_results_match_the_whole_grid(n, monkeypatch):
    """``FFTMethod`` (nested start, re-gridding, thin-coating refinement) gives the same delta, a
    and p0 on the quarter plane as on the whole grid: the iterations are the same to round-off,
    so the results agree far inside the CG tolerance 1e-6 (measured <= 3e-14; bound 1e-10)."""
    import coathertz.fft.method as fm

    cases = [coated(3.0, 0.3), coated(0.25, 0.02)]
    quarter = [FFTMethod(n=n).solve(c) for c in cases]
    solve = fm.polonsky_keer

    def whole_grid(*args, **kw):
        return solve(*args, **{**kw, "symmetric": False})

    monkeypatch.setattr(fm, "polonsky_keer", whole_grid)
    whole = [FFTMethod(n=n).solve(c) for c in cases]
    for q, w in zip(quarter, whole, strict=True):
        assert q.meta["grid"] == w.meta["grid"]
        for name in ("delta", "a", "p0"):
            rel = abs(getattr(q, name) / getattr(w, name) - 1)
            assert rel < 1e-10, f"{name}: relative difference {rel:.3g}"
