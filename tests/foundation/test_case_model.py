"""Case model: validation messages, derived quantities, units, TOML round trip."""

from __future__ import annotations

import math

import pytest

from coathertz import RIGID, Body, Coating, ContactCase, Material
from coathertz.casefile import case_from_dict, case_to_toml, examples, load_case, load_example
from coathertz.errors import CoatHertzError
from coathertz.materials import coating_constants
from coathertz.units import parse_quantity


@pytest.mark.parametrize(
    ("build", "match"),
    [
        (lambda: Material(-1e9, 0.3), "E must satisfy 0 < E"),
        (lambda: Material(1e9, 0.6), r"nu must satisfy -1 < nu <= 0.5"),
        (lambda: Material(1e9, -1.0), r"nu must satisfy -1 < nu <= 0.5"),
        (lambda: Coating(Material(1e9, 0.3), -1e-6), r"thickness h must satisfy 0 <= h"),
        (lambda: Coating(RIGID, 1e-6), "coating material must be elastic"),
        (lambda: Body(Material(1e9, 0.3), Rx=-1.0), "Rx must satisfy"),
        (lambda: Body.sphere(Material(1e9, 0.3), -1.0), r"radius R must satisfy 0 < R"),
        (lambda: ContactCase(Body.rigid_sphere(0.01), Body.half_space(RIGID), 1.0), "both are rigid"),
        (lambda: ContactCase(Body.rigid_sphere(0.01), Body.half_space(Material(1e9, 0.3)), 0.0),
         "W must satisfy"),
    ],
)
def test_bad_input_names_parameter_and_range(build, match):
    with pytest.raises(CoatHertzError, match=match):
        build()


def test_coating_constants_limits():
    c = Material(300e9, 0.25)
    k = coating_constants(c, RIGID)
    assert k.mu == 0 and k.lam == pytest.approx(4 * 0.25 - 3) and k.kappa == pytest.approx(1 / k.lam)
    same = coating_constants(c, c)
    assert same.mu == pytest.approx(1) and same.lam == pytest.approx(0, abs=1e-15)
    assert same.kappa == pytest.approx(0, abs=1e-15)
    # identity below eq (14): (1 - lam kappa)/(1 - (lam + kappa) + lam kappa) = Ec*/Es*
    s = Material(70e9, 0.35)
    k = coating_constants(c, s)
    lhs = (1 - k.lam * k.kappa) / (1 - (k.lam + k.kappa) + k.lam * k.kappa)
    assert lhs == pytest.approx(c.E_star / s.E_star, rel=1e-13)


def test_normalisers_and_H():
    steel = Material(200e9, 0.3)
    case = ContactCase.sphere_on_coated_half_space(0.01, 100.0, Material(400e9, 0.3), 10e-6, steel)
    assert case.normalisers.kind == "s"
    assert case.H == pytest.approx(10e-6 / case.a0s)
    assert case.modulus_ratio == pytest.approx(2.0)
    rig = ContactCase.sphere_on_coated_half_space(0.01, 100.0, steel, 10e-6, RIGID)
    assert rig.rigid_substrate and rig.normalisers.kind == "c"
    assert rig.H == pytest.approx(10e-6 / rig.a0c)
    assert rig.a0s == 0.0  # the substrate alone is rigid


@pytest.mark.parametrize(
    ("text", "dim", "value"),
    [("380 GPa", "pressure", 380e9), ("40 um", "length", 40e-6), ("10 mm", "length", 0.01),
     ("1 N", "force", 1.0), ("2.5e3 MPa", "pressure", 2.5e9), ("inf", "length", math.inf),
     ("90 deg", "angle", math.pi / 2)],
)
def test_units(text, dim, value):
    assert parse_quantity(text, dim) == pytest.approx(value)


@pytest.mark.parametrize("text", ["380", 380.0, "380 mm"])
def test_ambiguous_or_wrong_units_rejected(text):
    with pytest.raises(CoatHertzError, match="unit"):
        parse_quantity(text, "pressure", name="E")


def test_toml_roundtrip_all_examples():
    import tomllib

    assert {"b4c_on_steel", "keer_case_a", "keer_case_b"} <= set(examples())
    for name in examples():
        case = load_example(name)
        assert case_from_dict(tomllib.loads(case_to_toml(case))) == case


def test_toml_errors(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text(
        'W = "1 N"\n[body1]\nmaterial = "rigid"\nR = "10 mm"\n'
        '[body2]\nmaterial = { E = 200, nu = 0.3 }\n'
    )
    with pytest.raises(CoatHertzError, match=r"\[body2\] substrate material E = 200 has no unit"):
        load_case(p)
    p.write_text('W = "1 N"\nload = 3\n')
    with pytest.raises(CoatHertzError, match="unknown keys"):
        load_case(p)
    with pytest.raises(CoatHertzError, match="does not exist"):
        load_case(tmp_path / "missing.toml")
