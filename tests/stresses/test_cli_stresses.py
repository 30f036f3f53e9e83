"""``coathertz stresses``: JSON keys, numbers and one-line errors."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main

BASE = ["--substrate", "200 GPa,0.3", "--W", "100 N", "--R", "10 mm"]
KEYS = ("vm_max_coating", "vm_max_substrate", "vm_max", "tensile_max_surface", "tensile_max",
        "interface_shear_max", "interface_normal_max")


def test_json_homogeneous(capsys):
    assert main(["stresses", *BASE, "--grid", "64", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert all(k in d for k in KEYS)
    vm = d["vm_max"]
    # Hertz: 0.620 p0 at z = 0.48a on the axis (measured 0.620 p0 at 0.475a with n = 128)
    assert vm["over_p0"] == pytest.approx(0.620, abs=0.006)
    assert vm["at"][2] / d["a"] == pytest.approx(0.48, abs=0.03)
    assert d["vm_max_coating"] is None and d["interface_shear_max"] is None
    assert d["tensile_max_surface"]["over_p0"] == pytest.approx((1 - 0.6) / 3, abs=0.01)


def test_json_coated_sliding(capsys):
    args = ["stresses", *BASE, "--coating", "400 GPa,0.25,30 um", "--mu", "0.3", "--grid",
            "64", "--json"]
    assert main(args) == 0
    d = json.loads(capsys.readouterr().out)
    for k in KEYS:
        e = d[k]
        assert set(e) == {"value", "over_p0", "at"} and len(e["at"]) == 3
    assert d["interface_shear_max"]["at"][2] == pytest.approx(30e-6)
    assert d["vm_max_coating"]["at"][2] <= 30e-6 < d["vm_max_substrate"]["at"][2]
    # sliding tension at the trailing edge (x < 0), on the surface
    assert d["tensile_max_surface"]["at"][0] < 0


@pytest.mark.parametrize("extra, text", [
    (["--mu", "-0.1"], "--mu: friction coefficient must be in [0, 1]"),
    (["--depths", "-5"], "--depths: body2 depth -5 um outside the body"),
    (["--substrate", "rigid", "--coating", "400 GPa,0.25,30 um", "--depths", "40"],
     "--depths: body2 depth 40 um outside the body (valid: 0 to 30 um)"),
])
def test_bad_input_one_line(capsys, extra, text):
    assert main(["stresses", *BASE, *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert text in err and "\n" not in err and "Traceback" not in err
