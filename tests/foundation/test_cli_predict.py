"""`coathertz predict` end to end (the CLI is called in-process through main(argv))."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main


def test_predict_json_b4c_with_figure_alphas(capsys):
    assert main(["predict", "example:b4c_on_steel", "--alpha", "a=3.35,p=1.619,delta=1.1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["extended"]["delta"] == pytest.approx(0.15500e-6, abs=5e-12)
    assert out["extended"]["a"] == pytest.approx(37.727e-6, abs=5e-10)
    assert out["extended"]["p0"] == pytest.approx(320.12e6, abs=5e3)
    assert out["hertz_substrate"]["a"] == pytest.approx(40.8665e-6, rel=1e-5)
    assert out["H"][0] == pytest.approx(0.9788, abs=1e-4)


def test_predict_table_from_flags(capsys):
    rc = main(["predict", "--W", "1 N", "--R", "10 mm", "--indenter", "200 GPa,0.3",
               "--substrate", "200 GPa,0.3", "--coating", "380 GPa,0.17,40 um"])
    assert rc == 0
    out = capsys.readouterr().out
    assert "extended Hertz" in out and "alpha_a = 2.413" in out and "40.867" in out


def test_predict_warns_outside_fitted_range(capsys):
    assert main(["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "100 GPa,0.3",
                 "--coating", "800 GPa,0.3,1 um"]) == 0
    cap = capsys.readouterr()
    assert "warning:" not in cap.out  # warnings go to stderr, the table to stdout
    assert "coathertz predict: warning:" in cap.err and "[1/4, 4]" in cap.err


def test_predict_bad_input_exit_2(capsys):
    assert main(["predict", "--W", "1", "--R", "10 mm", "--substrate", "200 GPa,0.3"]) == 2
    assert "has no unit" in capsys.readouterr().err
    assert main(["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.7"]) == 2
    assert "nu must satisfy" in capsys.readouterr().err


def test_list_examples(capsys):
    assert main(["predict", "--list-examples"]) == 0
    assert "example:keer_case_a" in capsys.readouterr().out
