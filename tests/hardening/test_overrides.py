"""Case flags given with a case file replace its values, in every subcommand."""

from __future__ import annotations

import json

import pytest

from coathertz.casefile import load_example
from coathertz.cli import main
from coathertz.materials import Body, Coating, Material


def _json(capsys, argv):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_predict_applies_W(capsys):
    one = _json(capsys, ["predict", "example:b4c_on_steel"])
    five = _json(capsys, ["predict", "example:b4c_on_steel", "--W", "5 N"])
    assert "W=5 N" in five["case"]
    # Hertz with the coating removed scales as W^(1/3) (eq 1): an exact check that 5 N was used
    a1 = one["hertz_substrate"]["a"]
    assert five["hertz_substrate"]["a"] == pytest.approx(a1 * 5 ** (1 / 3), rel=1e-12)
    assert five["extended"]["a"] != pytest.approx(one["extended"]["a"], rel=1e-3)


def test_predict_applies_material_flags(capsys):
    out = _json(capsys, ["predict", "example:b4c_on_steel", "--coating", "100 GPa,0.3,10 um",
                         "--substrate", "300 GPa,0.25", "--R", "5 mm", "--indenter", "rigid"])
    case = load_example("b4c_on_steel")
    want = case.replace(body1=Body.rigid_sphere(5e-3),
                        body2=Body.half_space(Material(300e9, 0.25), Coating(Material(100e9, 0.3), 10e-6)))
    assert out["hertz_substrate"]["a"] == pytest.approx(want.a0s, rel=1e-12)
    assert out["hertz_coating"]["a"] == pytest.approx(want.a0c, rel=1e-12)


def test_fft_applies_W(capsys):
    a1 = _json(capsys, ["fft", "example:fig3_soft_coating", "--grid", "32"])
    a2 = _json(capsys, ["fft", "example:fig3_soft_coating", "--grid", "32", "--W", "800 N"])
    assert "W=800 N" in a2["case"]
    # the grid follows the Hertz estimate, so the normalised results are close, the radius is not
    assert a2["a"] / a1["a"] == pytest.approx(2.0, rel=0.1)  # a ~ W^(1/3) roughly: 8^(1/3) = 2


def test_fem_applies_W(capsys):
    out = _json(capsys, ["fem", "example:fig3_soft_coating", "--mesh", "coarse", "--W", "5 N"])
    assert "W=5 N" in out["case"]
    case = load_example("fig3_soft_coating").replace(W=5.0)
    assert out["a"] == pytest.approx(case.a0s, rel=0.5)
    assert out["a_bar"] == pytest.approx(out["a"] / case.a0s, rel=1e-12)


def test_flags_build_a_case_in_fft(capsys):
    out = _json(capsys, ["fft", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3", "--grid", "32"])
    assert out["a_bar"] == pytest.approx(1.0, abs=0.05)  # homogeneous: Hertz
