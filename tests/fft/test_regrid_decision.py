"""The re-gridding decision of the FFT method is not flipped by round-off.

The decision is discrete (the contact's extent in cells): a cell whose pressure is at
round-off level, at the edge of the contact, used to move it by one cell. Such cells do not
count now (``DECISION_FLOOR`` of the peak; 100 times the pressure changes of a 1e-16 change of
the kernel, which are about the solver tolerance 1e-6 of the peak).
"""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fft import estimators
from coathertz.fft.grid import grid_for_axes
from coathertz.fft.method import DECISION_FLOOR, FFTMethod, settled_contact

A = 1e-4  # contact radius [m]


def _hertz(grid, a):
    X, Y = np.meshgrid(grid.x, grid.y)
    return np.sqrt(np.clip(1.0 - (X**2 + Y**2) / a**2, 0.0, None))


def _decision(method, p, grid):
    q = settled_contact(p)
    return method._refit(estimators.contact_extent(q, grid), estimators.moment_axes(q, grid), grid)


def test_settled_contact_drops_only_cells_below_the_floor():
    grid = grid_for_axes(A, A, 64)
    p = _hertz(grid, A)
    p[0, 0] = 0.5 * DECISION_FLOOR
    q = settled_contact(p)
    assert q[0, 0] == 0.0
    m = p >= DECISION_FLOOR
    np.testing.assert_array_equal(q[m], p[m])
    assert np.count_nonzero(q) == np.count_nonzero(p) - 1
    assert np.array_equal(settled_contact(np.zeros((4, 4))), np.zeros((4, 4)))


@pytest.mark.parametrize("noise", [1e-16, 1e-12, 1e-6])
def test_a_round_off_cell_does_not_flip_the_regrid_decision(noise):
    """A Hertzian contact that suits its grid, plus one cell of pressure ``noise`` (relative to
    the peak) near the grid's boundary: the raw extent would call the contact touching and
    re-grid; the decision with the settled contact is the one without the cell (no re-grid)."""
    method = FFTMethod(n=64)
    grid = grid_for_axes(A, A, 64)
    p = _hertz(grid, A)
    assert _decision(method, p, grid) is None  # the contact suits the grid
    noisy = p.copy()
    noisy[grid.ny // 2, 1] = noise * p.max()  # one cell from the boundary
    raw = method._refit(estimators.contact_extent(noisy, grid), estimators.moment_axes(noisy, grid), grid)
    assert raw is not None, "the raw extent should see the stray cell (the test's premise)"
    assert _decision(method, noisy, grid) is None, f"a cell at {noise:g} of the peak flipped the decision"


def test_the_floor_keeps_a_resolved_edge_cell():
    """The outermost cells of a resolved Hertzian contact lie far above the floor (asserted: 100
    times it), so the settled extent is the contact's own."""
    grid = grid_for_axes(A, A, 64)
    p = _hertz(grid, A)
    edge = p[p > 0].min()
    assert edge > 100 * DECISION_FLOOR, f"smallest contact cell {edge:.2e} of the peak"
    assert estimators.contact_extent(settled_contact(p), grid) == estimators.contact_extent(p, grid)
