"""``coathertz axisym``: output, JSON, fields file and clear errors."""

from __future__ import annotations

import json

import numpy as np

from coathertz.cli import main


def test_json_output(capsys):
    assert main(["axisym", "example:keer_case_b", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["normalisation"] == "s"
    assert d["meta"]["r_p0"] == 0.0 and d["meta"]["n_modes"] >= 16
    assert 0.7 < d["delta_bar"] < 0.9 and d["a"] == d["r_a"] == d["r_b"]


def test_table_output_and_fields(tmp_path, capsys):
    out = tmp_path / "f.npz"
    assert main(["axisym", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
                 "--coating", "2000 GPa,0.3,10 um", "--save-fields", str(out)]) == 0
    text = capsys.readouterr().out
    assert "p0 [MPa] (maximum)" in text and "maximum pressure at r =" in text  # off-axis ring
    f = np.load(out)
    assert set(f.files) == {"r", "pressure", "u_z"} and f["r"].shape == f["pressure"].shape


def test_frictionless_rigid_base(capsys):
    assert main(["axisym", "example:rigid_substrate", "--interface", "frictionless"]) == 0
    assert "frictionless interface" in capsys.readouterr().out


def test_elliptical_case_is_a_clear_error(capsys):
    assert main(["axisym", "example:elliptical_fig10"]) == 2
    err = capsys.readouterr().err
    assert "not axisymmetric" in err and "Rx = 17.4 mm" in err


def test_bad_input_errors(capsys):
    assert main(["axisym", "example:b4c_on_steel", "--modes", "1"]) == 2
    assert "--modes" in capsys.readouterr().err
    assert main(["axisym", "no_such_file.toml"]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert main(["axisym"]) == 2
    assert "--W" in capsys.readouterr().err
    assert main(["axisym", "--W", "-1 N", "--R", "10 mm", "--substrate", "rigid",
                 "--coating", "200 GPa,0.3,5 um"]) == 2
    assert "W" in capsys.readouterr().err


def test_list_examples(capsys):
    assert main(["axisym", "--list-examples"]) == 0
    assert "example:b4c_on_steel" in capsys.readouterr().out


def test_extreme_thin_coating_and_load_solve(capsys):
    """A 1e-15 m coating under 1e30 N (h/a ~ 1e-30) is solved with bounded memory (it used to end
    in 'out of memory'); the answer is the substrate's Hertz solution (ratios 1.0000000)."""
    assert main(["axisym", "example:b4c_on_steel", "--coating", "380 GPa,0.17,1e-15 m",
                 "--W", "1e30 N", "--modes", "32"]) == 0
    text = capsys.readouterr().out
    assert text.count("1.0000000") == 3, text


def test_out_of_memory_names_axisym_flag(monkeypatch, capsys):
    """Out of memory: one line naming axisym's own resolution flag (--modes), not --mesh/--grid."""
    from coathertz.axisym import AxisymMethod

    def boom(self, case):
        raise MemoryError

    monkeypatch.setattr(AxisymMethod, "solve", boom)
    assert main(["axisym", "example:b4c_on_steel"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "coathertz axisym: error: out of memory; use fewer Legendre modes (--modes)", err
