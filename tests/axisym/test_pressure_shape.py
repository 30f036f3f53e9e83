"""The pressure's Chebyshev coefficients as a cached linear map of the Legendre coefficients
(``solver._shape_matrix``) against the direct route (``chebinterpolate`` of the Abel integral)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.polynomial import chebyshev as npcheb

from coathertz.axisym import solver
from coathertz.axisym.solver import RadiusSolution


@pytest.mark.parametrize("n_modes", [2, 3, 8, 32, 64, 96, 160])
def test_shape_matrix_equals_interpolated_abel_integral(n_modes):
    """Random Legendre coefficients (decaying like a solution's): the matrix route equals
    ``chebinterpolate`` of ``_abel_integral`` to round-off, 1e-12 of the largest coefficient
    (measured <= 1.6e-13; both sum ~2N terms of size ~the largest)."""
    rng = np.random.default_rng(n_modes)
    c = rng.standard_normal(n_modes) * np.exp(-0.05 * np.arange(n_modes))
    sol = RadiusSolution(1.0, 0.0, 0.0, c, (c, c))

    def Q(v):
        return solver._abel_integral(c, np.sqrt(np.clip(0.5 * (v + 1.0), 0.0, 1.0)))

    ref = npcheb.chebinterpolate(Q, n_modes)
    got = solver.pressure_shape(sol)
    err = np.abs(got - ref).max() / np.abs(ref).max()
    assert err < 1e-12, f"N = {n_modes}: {err:.2e}"
    assert solver._shape_matrix(n_modes) is solver._shape_matrix(n_modes)  # cached


def test_hertz_shape():
    """g = 1 - x^2 (Hertz's shape, c = (2/3, -2/3)) has g'/x = -2, so Q = 2 and
    p = 2 E_ref sqrt(1 - rho^2) / (pi a): the matrix gives the constant 2 to round-off."""
    c = np.array([2.0 / 3.0, -2.0 / 3.0])
    sol = RadiusSolution(1.0, 0.0, 0.0, c, (c, c))
    q = solver.pressure_shape(sol)
    assert abs(q[0] - 2.0) < 1e-14 and np.abs(q[1:]).max() < 1e-14, q
