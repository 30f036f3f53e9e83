"""FFT stresses under full sliding (q = mu p along x) against Hamilton's (1983) closed form."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fft.frf import Layer
from coathertz.fft.grid import Grid
from coathertz.fft.stresses import (
    CoatedStressFRF,
    HomogeneousStressFRF,
    stresses_surface,
    von_mises,
)
from coathertz.materials import Material

NU = 0.3
N = 128


@pytest.fixture(scope="module")
def hertz():
    g = Grid(N, N, 4.0 / N, 4.0 / N)  # a = 1, domain 4a
    X, Y = np.meshgrid(g.x, g.y)
    p = np.sqrt(np.clip(1 - X**2 - Y**2, 0, None))  # p0 = 1
    return g, p


@pytest.mark.parametrize("mu", [0.1, 0.25, 0.5])
def test_sliding_surface_stresses_match_hamilton(hertz, mu):
    """On the x axis inside the contact (Hamilton 1983; Johnson 1985 sec. 7.2):
    ``sigma_x = sigma_r^Hertz - (4 + nu) pi mu x / (8a)``,
    ``sigma_y = sigma_theta^Hertz - 3 pi nu mu x / (8a)``,
    with the Hertz surface stresses of Johnson eq (3.43)."""
    g, p = hertz
    S = stresses_surface(g, [0.0], HomogeneousStressFRF(NU), p=p, qx=mu * p)[0]
    m = N // 2
    x = g.x
    sel = (np.abs(x) <= 0.9) & (x != 0)
    r = np.abs(x[sel])
    root = np.sqrt(1 - r * r)
    first = (1 - 2 * NU) / 3 / r**2 * (1 - root**3)
    sxx = first - root - (4 + NU) * np.pi * mu * x[sel] / 8
    syy = -first - 2 * NU * root - 3 * np.pi * NU * mu * x[sel] / 8
    ex = np.abs(S[0, m, sel] - sxx).max()
    ey = np.abs(S[1, m, sel] - syy).max()
    # measured at mu = 0.1, 0.25, 0.5: sigma_x 0.0016, 0.0028, 0.0054 p0, sigma_y 0.0014,
    # 0.0017, 0.0024 p0 (n = 128, |x| <= 0.9a; at |x| = a the
    # tangential part has a cusp the cells do not resolve: 9 % low there)
    assert ex < 0.01 and ey < 0.01, f"mu = {mu}: max error sigma_x {ex:.4f}, sigma_y {ey:.4f} p0"


def test_max_von_mises_moves_to_surface(hertz):
    """Hamilton (1983): yield (von Mises) starts at the surface once mu exceeds about 0.3."""
    g, p = hertz
    zs = np.r_[0.0, np.arange(0.02, 0.8, 0.02)]
    where = {}
    for mu in (0.25, 0.35):
        vm = von_mises(stresses_surface(g, zs, HomogeneousStressFRF(NU), p=p, qx=mu * p))
        where[mu] = (zs[np.unravel_index(vm.argmax(), vm.shape)[0]], vm[0].max(), vm[1:].max())
    # measured: mu = 0.25 max 0.647 p0 at z = 0.44a (surface 0.553); mu = 0.35 max 0.714 p0
    # on the surface (below: 0.674); the switch lies between mu = 0.30 and 0.35
    assert where[0.25][0] > 0.3 and where[0.35][0] == 0.0, (
        f"(z of max, surface max, subsurface max) per mu: {where}")


def test_same_material_coating_is_homogeneous_under_traction(hertz):
    """The layered transfer solutions (in-plane and antiplane) reduce to the closed form."""
    g, p = hertz
    mat = Material(E=200e9, nu=NU)
    zs = [0.1, 0.3, 0.6]
    kw = {"p": p, "qx": 0.3 * p, "qy": 0.2 * p}
    S1 = stresses_surface(g, zs, CoatedStressFRF(Layer(mat, mat, "bonded"), 0.3), **kw)
    S0 = stresses_surface(g, zs, HomogeneousStressFRF(NU), **kw)
    assert np.abs(S1 - S0).max() < 1e-6  # measured 8e-9 p0
