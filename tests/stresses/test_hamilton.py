"""Hamilton's (1983) closed form for the sliding sphere (``coathertz.hamilton``): against Huber's
field (normal part) and the FFT stresses under full sliding (q = mu p along x)."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fft.stresses import HomogeneousStressFRF, stresses_surface
from coathertz.hamilton import normal_part, sliding_stresses, von_mises_max_xz

from .huber import hertz_on_grid, huber

NU = 0.3
DEPTHS = (0.1, 0.2, 0.5, 1.0)


def test_normal_part_is_hubers_field():
    X, Y = np.meshgrid(np.linspace(-2, 2, 41), np.linspace(-2, 2, 41))
    R, th = np.hypot(X, Y), np.arctan2(Y, X)
    c, s = np.cos(th), np.sin(th)
    worst = 0.0
    for z in (0.01, 0.3, 1.0):
        sr, st, sz, trz = huber(R, z, 1.0, NU)
        ref = np.array([c * c * sr + s * s * st, s * s * sr + c * c * st, sz, s * trz, c * trz,
                        c * s * (sr - st)])
        worst = max(worst, float(np.abs(normal_part(X, Y, np.full_like(X, z), NU) - ref).max()))
    assert worst < 1e-10, f"Hamilton's normal part differs from Huber's field by {worst:.2e} p0"


@pytest.fixture(scope="module")
def fft_parts():
    g, X, Y, _, p = hertz_on_grid(128, 4.0)  # a = 1, p0 = 1, domain 4a, pad 4
    frf = HomogeneousStressFRF(NU)
    return X, Y, stresses_surface(g, DEPTHS, frf, p=p), stresses_surface(g, DEPTHS, frf, qx=p)


@pytest.mark.parametrize("mu", [0.1, 0.25, 0.5])
def test_fft_sliding_field_matches_hamilton(fft_parts, mu):
    """The whole 3-D field at z = 0.1a to a on the 128^2 grid, every component."""
    X, Y, Sp, Sq = fft_parts
    err = [float(np.abs(Sp[i] + mu * Sq[i] - sliding_stresses(X, Y, np.full_like(X, z), NU, mu)).max())
           for i, z in enumerate(DEPTHS)]
    # measured max |FFT - Hamilton| / p0 at z = 0.1, 0.2, 0.5, 1 a: mu = 0.1: 0.0076, 0.0026,
    # 0.0005, 0.0003; mu = 0.25: 0.0077, 0.0027, 0.0006, 0.0006; mu = 0.5: 0.0079, 0.0027, 0.0012,
    # 0.0011. The largest is next to the contact edge at z = 0.1a (3 cells): the pressure is
    # sampled at cell centres, not cell means (see coathertz.fft.stresses, "Accuracy near the
    # surface"); the tangential part alone is within 0.0023 mu p0 there.
    assert max(err) < 0.01, f"mu = {mu}: max |FFT - Hamilton| / p0 per depth {np.round(err, 4)}"


def test_hamilton_von_mises_maximum_moves_to_the_surface():
    """Hamilton (1983): the largest von Mises stress lies below the surface (0.620 p0 at
    z = 0.481a without friction) until mu reaches about 0.3, then on the surface at the
    trailing edge of the contact."""
    vm0, x0, z0, _ = von_mises_max_xz(NU, 0.0)
    assert abs(vm0 - 0.6200) < 2e-4 and abs(z0 - 0.4809) < 2e-3 and abs(x0) < 1e-9, (vm0, x0, z0)

    def below_minus_surface(mu):
        return _subsurface_max(mu) - von_mises_max_xz(NU, mu)[3]

    lo, hi = 0.25, 0.4
    assert below_minus_surface(lo) > 0 > below_minus_surface(hi)
    for _ in range(12):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if below_minus_surface(mid) > 0 else (lo, mid)
    # measured: the switch at mu = 0.3046 (nu = 0.3; subsurface peak taken over z >= 0.05a)
    assert 0.29 < lo < 0.33, f"maximum von Mises stress reaches the surface at mu = {lo:.4f}"


def _subsurface_max(mu: float) -> float:
    """Largest von Mises stress / p0 at z >= 0.05a in the plane y = 0 (the subsurface peak)."""
    xs, zs = np.linspace(-1.2, 1.2, 241), np.linspace(0.05, 0.8, 151)
    X, Z = np.meshgrid(xs, zs)
    s = sliding_stresses(X, 0 * X, Z, NU, mu)
    xx, yy, zz, yz, xz, xy = s
    vm = np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * (yz**2 + xz**2 + xy**2))
    return float(vm.max())
