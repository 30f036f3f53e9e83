"""Coated half-space limits and the two-identical-bodies construction."""

from __future__ import annotations

import pytest

from coathertz.case import ContactCase
from coathertz.materials import Body, Coating, Material


@pytest.mark.parametrize("H", [0.05, 1.0])
def test_equal_moduli_reproduce_hertz_at_any_H(fx, H):
    case = fx.coated_case(200e9, H)
    r = fx.solve(case, mesh="coarse")
    assert r.delta == pytest.approx(case.delta0s, rel=1e-3)
    assert r.a == pytest.approx(case.a0s, rel=2e-3)  # coarse-mesh edge fit: measured <= 1e-3
    assert r.p0 == pytest.approx(case.p0s, rel=2e-3)


def test_thin_coating_tends_to_substrate_hertz(fx):
    """E = Ec*/Es* = 4. Measured max deviation from substrate Hertz over (delta, a, p0):
    7.3 % at H = 0.1 and 1.26 % at H = 0.01 (a/a0s = 0.9874; n_a = 40, 80, 120 agree to
    5e-5, the stiff film's edge boundary layer of width ~h keeps a below a0s)."""
    devs = []
    for H in (0.1, 0.01):
        case = fx.coated_case(800e9, H)
        r = fx.solve(case, mesh="coarse")
        devs.append(max(abs(r.delta / case.delta0s - 1), abs(r.a / case.a0s - 1), abs(r.p0 / case.p0s - 1)))
    assert devs[1] < 0.3 * devs[0], devs
    assert devs[1] < 0.015, devs


def test_thick_coating_tends_to_coating_hertz(fx):
    """E = 1/4 (soft coating). a and p0 approach coating Hertz quickly; delta, an integral of
    the deformation over depth, only like O(a/h): measured delta/delta0c - 1 = -3.3 % at
    H = 20 (h/a ~ 13) and about four times that at H = 5."""
    devs = []
    for H in (5.0, 20.0):
        case = fx.coated_case(50e9, H)
        r = fx.solve(case, mesh="coarse")
        devs.append(abs(r.delta / case.delta0c - 1))
    assert devs[1] < 0.5 * devs[0] and devs[1] < 0.05, devs
    assert r.a == pytest.approx(case.a0c, rel=0.01)
    assert r.p0 == pytest.approx(case.p0c, rel=0.01)


def test_two_identical_bodies_equal_one_body_under_sphere_of_twice_radius(fx):
    mat, coat = Material(200e9, 0.28), Coating(Material(406.25e9, 0.3), 12.336e-6)
    pair = ContactCase(Body.sphere(mat, 0.02, coat), Body.sphere(mat, 0.02, coat), 1.0)
    single = ContactCase(Body.rigid_sphere(0.02), Body.half_space(mat, coat), 1.0)
    rp = fx.solve(pair, mesh="coarse")
    rs = fx.solve(single, mesh="coarse")
    assert rp.delta == pytest.approx(2 * rs.delta, rel=1e-12)
    assert rp.a == pytest.approx(rs.a, rel=1e-12) and rp.p0 == pytest.approx(rs.p0, rel=1e-12)
    assert rp.meta["R_model"] == pytest.approx(0.02)


def test_uncoated_identical_pair_is_hertz(fx):
    pair = ContactCase(Body.sphere(fx.STEEL, 0.02), Body.sphere(fx.STEEL, 0.02), 50.0)
    r = fx.solve(pair, mesh="coarse")
    assert r.delta == pytest.approx(pair.delta0s, rel=1e-3)
    assert r.a == pytest.approx(pair.a0s, rel=2e-3)
    assert r.p0 == pytest.approx(pair.p0s, rel=2e-3)


@pytest.mark.parametrize(
    ("name", "delta", "a", "p0"),
    [("keer_case_a", 0.158182e-6, 36.998e-6, 314.916e6), ("keer_case_b", 0.130838e-6, 32.781e-6, 442.583e6)],
)
def test_section6_cases_at_coarse_mesh_match_converged_values(name, delta, a, p0):
    """Converged values (n_a = 160, 233k dofs); the coarse mesh (n_a = 20) is within 0.1 %
    (measured 1e-3 on a of case A, <= 5e-5 otherwise). The independent DC-FFT solver (128^2)
    gives 0.15817 um, 37.005 um, 314.92 MPa (A) and 0.13083 um, 32.785 um, 442.58 MPa (B)."""
    from importlib.resources import files

    from coathertz.casefile import load_case
    from coathertz.fem.method import FEMMethod

    case = load_case(files("coathertz") / "data" / f"{name}.toml")
    r = FEMMethod(mesh="coarse").solve(case)
    assert r.delta == pytest.approx(delta, rel=2e-4)
    assert r.a == pytest.approx(a, rel=1.5e-3)
    assert r.p0 == pytest.approx(p0, rel=3e-4)


def test_interface_tractions_continuous_and_sigma_rr_jumps(fx):
    """Bonded interface: sigma_zz and sigma_rz continuous (measured jump of the per-region
    projections 0.25 % / 0.4 % of p0 at E = 4, H = 0.3, coarse mesh), sigma_rr jumps (50 % of p0)."""
    import numpy as np

    case = fx.coated_case(800e9, 0.3)
    r = fx.solve(case, mesh="coarse", stresses=True)
    f = r.fields

    def jump(name):
        return np.max(np.abs(f[f"interface_coating_{name}"] - f[f"interface_substrate_{name}"])) / r.p0

    assert jump("sigma_zz") < 0.02
    assert jump("sigma_rz") < 0.02
    assert jump("sigma_rr") > 0.2
    same = fx.coated_case(200e9, 0.3)
    rs = fx.solve(same, mesh="coarse", stresses=True)
    js = np.max(np.abs(rs.fields["interface_coating_sigma_rr"] - rs.fields["interface_substrate_sigma_rr"]))
    assert js / rs.p0 < 0.02
