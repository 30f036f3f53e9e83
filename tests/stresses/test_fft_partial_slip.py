"""Partial slip (Cattaneo--Mindlin) on the FFT grid against the closed form."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.errors import CoatHertzError
from coathertz.fft.partial_slip import solve_partial_slip

from .huber import hertz_on_grid

A, NU, MU, G = 1.0, 0.3, 0.3, 1.0
N = 64


@pytest.fixture(scope="module")
def hertz():
    g, X, _, R, p = hertz_on_grid(N, 3.0 * A, A)  # p0 = 1
    return g, X, R, p, float(p.sum()) * g.dx * g.dy


@pytest.mark.parametrize("ratio", [0.2, 0.5, 0.8])
def test_cattaneo_mindlin_stick_radius_and_traction(hertz, ratio):
    g, _, R, p, W = hertz
    r = solve_partial_slip(p, g, [(G, NU)], ratio * MU * W, MU)
    c = np.sqrt(r.stick.sum() * g.dx * g.dy / np.pi)  # radius of the stick area
    c_cm = A * (1 - ratio) ** (1 / 3)
    # Cattaneo-Mindlin traction: mu p0 (sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2))
    q_cm = MU * (p - (c_cm / A) * np.sqrt(np.clip(1 - (R / c_cm) ** 2, 0, None)))
    err_q = np.abs(r.q - q_cm).max() / MU
    # measured on 64^2 (dx = a/21): c/c_CM - 1 = 0.20 / 0.24 / 0.41 % at Q/mu W = 0.2 / 0.5 /
    # 0.8; max |q - q_CM| = 3.1 / 3.5 / 2.1 % of mu p0, in the cells at the stick edge where
    # q_CM has a square-root kink
    assert abs(c / c_cm - 1) < 0.01, f"c/a = {c:.4f}, Cattaneo-Mindlin {c_cm:.4f}"
    assert np.abs(r.q).max() <= MU * p.max() * (1 + 1e-12)
    assert abs(r.q.sum() * g.dx * g.dy / (ratio * MU * W) - 1) < 1e-9
    assert err_q < 0.06, f"max |q - q_CM| / (mu p0) = {err_q:.4f}"


def test_sliding_and_bad_input_are_one_line(hertz):
    g, _, _, p, W = hertz
    with pytest.raises(CoatHertzError, match="slides"):
        solve_partial_slip(p, g, [(G, NU)], MU * W, MU)
    with pytest.raises(CoatHertzError, match="Q must be >= 0"):
        solve_partial_slip(p, g, [(G, NU)], -1.0, MU)
    with pytest.raises(CoatHertzError, match="mu must be > 0"):
        solve_partial_slip(p, g, [(G, NU)], 0.1, -0.1)
