"""The CG iteration allocates no array of grid size.

Each iteration reports ``tracemalloc``'s peak since the previous one, relative to the memory
held at its start: a temporary the size of the grid (even a boolean mask, ``n^2`` bytes) would
raise it by at least that much. The work buffers are allocated once, before the iteration.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from coathertz.fft.method import FFTMethod, case_coefficients, initial_gap
from coathertz.fft.solver import Convolver, get_backend, polonsky_keer

from .conftest import coated


@pytest.mark.parametrize(("batch", "precondition", "symmetric"),
                         [(1, False, False), (3, False, False), (1, True, False), (3, True, False),
                          (1, True, True), (3, True, True), (1, False, True)])
def test_cg_iteration_allocates_no_grid_array(batch, precondition, symmetric):
    n = 192 if symmetric else 96  # the quarter plane's boolean array (9216 bytes) above the ~2 kB of scalars
    case = coated(3.0, 0.3)
    grid = FFTMethod(n=n).grid_for(case)
    kern = np.stack([case_coefficients(case, grid)] * batch)
    conv = Convolver(kern, get_backend("numpy", 1))
    g0 = initial_gap(case, grid)
    excess: list[int] = []
    state = {}

    def cb(it):
        cur, peak = tracemalloc.get_traced_memory()
        if it > 1:
            excess.append(peak - state["start"])
        state["start"] = cur
        tracemalloc.reset_peak()

    tracemalloc.start()
    try:
        sol = polonsky_keer(conv, g0, [case.W] * batch, grid.cell_area, tol=1e-10, callback=cb,
                            precondition=precondition, symmetric=symmetric)
    finally:
        tracemalloc.stop()
    # a boolean grid array (float arrays are 8x larger); on the quarter plane a quarter of it
    grid_bytes = n * n // (4 if symmetric else 1)
    assert len(excess) >= (8 if precondition else 20), f"only {len(excess)} iterations observed"
    assert max(excess) < grid_bytes, (
        f"an iteration allocated {max(excess)} bytes beyond its start (grid array: "
        f">= {grid_bytes} bytes); per-iteration excess {excess}"
    )
    assert np.all(sol.iterations > (8 if precondition else 20)), sol.iterations
