"""Stress fields from FFT contact solutions (homogeneous and coated bodies)."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.errors import CoatHertzError
from coathertz.fft.method import FFTMethod
from coathertz.fft.stresses import contact_stresses, default_depths
from coathertz.materials import RIGID, Body, Coating, Material

from .huber import huber

STEEL = Material(200e9, 0.3)
HARD = Material(400e9, 0.25)
SOLVER = FFTMethod(n=128)


def test_fft_solution_stresses_match_huber():
    case = ContactCase(Body.rigid_sphere(10e-3), Body.half_space(STEEL), 100.0)
    r = SOLVER.solve(case)
    h = hertz_circular(100.0, 10e-3, STEEL.E_star)
    a, p0 = h.a0, h.p0
    zs = np.linspace(0.2, 2.0, 10) * a
    F = contact_stresses(case, r, depths=zs)
    X, Y = np.meshgrid(F.x, F.y)
    R, th = np.hypot(X, Y), np.arctan2(Y, X)
    c, s = np.cos(th), np.sin(th)
    err = []
    for i, z in enumerate(zs):
        sr, st, sz, trz = huber(R, z, a, STEEL.nu)
        ref = np.array([c * c * sr + s * s * st, s * s * sr + c * c * st, sz,
                        s * trz, c * trz, c * s * (sr - st)]) * p0
        err.append(np.abs(F.sigma[i] - ref).max() / p0)
    # measured 0.0004 p0 at most (n = 128, domain 2.5a, pad 4, image trace removed)
    assert max(err) < 0.005, f"max |FFT - Huber| / p0 per depth: {np.round(err, 4)}"


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_coated_interface_tractions(interface):
    body = Body(STEEL, Coating(HARD, 30e-6))
    case = ContactCase(Body.rigid_sphere(10e-3), body, 100.0)
    r = FFTMethod(n=128, interface=interface).solve(case)
    h = 30e-6
    F = contact_stresses(case, r, depths=[h, h * (1 + 1e-9)], mu=0.3, interface=interface)
    p0 = r.p0
    up, down = F.sigma[0], F.sigma[1]
    # measured: jumps <= 4e-10 p0 (6 x 6 round-off), frictionless interface shear 2e-13 p0
    for j, name in ((2, "zz"), (3, "yz"), (4, "xz")):
        jump = np.abs(up[j] - down[j]).max() / p0
        assert jump < 1e-6, f"sigma_{name} jumps by {jump:.2e} p0 across the interface"
    if interface == "frictionless":
        shear = np.abs(up[3:5]).max() / p0
        assert shear < 1e-6, f"interface shear {shear:.2e} p0 on a frictionless interface"
    else:  # bonded: the interface carries shear (measured 0.31 p0 here, mu = 0.3)
        assert np.abs(up[4]).max() / p0 > 0.02
    # the lateral stress jumps (different moduli): the field is not trivially continuous
    assert np.abs(up[0] - down[0]).max() / p0 > 0.01


def test_default_depths_resolve_the_coating():
    body = Body(STEEL, Coating(HARD, 30e-6))
    z = default_depths(body, 100e-6)
    assert z[0] == 0 and np.sum(z <= 30e-6) == 17 and np.any((z > 30e-6) & (z < 30.1e-6))
    assert z[-1] == pytest.approx(300e-6) and np.all(np.diff(z) > 0)
    rigid = Body(RIGID, Coating(HARD, 30e-6))
    assert default_depths(rigid, 100e-6)[-1] == 30e-6


def test_bad_input_is_one_clear_line():
    case = ContactCase(Body.rigid_sphere(10e-3), Body(RIGID, Coating(HARD, 30e-6)), 10.0)
    r = SOLVER.solve(case)
    with pytest.raises(CoatHertzError, match="depths must be in"):
        contact_stresses(case, r, depths=[40e-6])
    with pytest.raises(CoatHertzError, match="mu must be in"):
        contact_stresses(case, r, mu=-0.1)
    with pytest.raises(CoatHertzError, match="rigid"):
        contact_stresses(case, r, body=1)


@pytest.mark.parametrize("H", [0.01, 0.1])
def test_coating_of_the_substrates_material_is_the_homogeneous_field(H):
    """A coating with the substrate's own elastic constants is no coating: its field equals the
    homogeneous one (same pressure, same grid). The image correction's slope T1 used to be a
    finite difference below the layered responses' floor w h = T_MIN, where they are frozen:
    at H = 0.01 it left a uniform -1.8e-3 p0 (z = 0.48a) and -3.7e-3 p0 (z = a) in sigma_xx,
    sigma_yy on every grid (32/64/128 alike). Measured after (n = 32..128): 1.2e-6 / 2.6e-6 p0
    at H = 0.01 and 1.2e-7 / 2.6e-7 p0 at H = 0.1, not grid-dependent (the O(T_MIN) limit of
    the responses); bound 2e-5 p0."""
    case0 = ContactCase(Body.rigid_sphere(10e-3), Body(STEEL), 100.0)
    r = FFTMethod(n=32, layer_cells=None).solve(case0)
    case1 = ContactCase(Body.rigid_sphere(10e-3), Body(STEEL, Coating(STEEL, H * r.a)), 100.0)
    z = r.a * np.array([0.48, 1.0])
    F0 = contact_stresses(case0, r, depths=z)
    F1 = contact_stresses(case1, r, depths=z)
    diff = np.abs(F1.sigma - F0.sigma).max() / r.p0
    assert diff < 2e-5, f"coating of the substrate's material: field differs by {diff:.2e} p0"
