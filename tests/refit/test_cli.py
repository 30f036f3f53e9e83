"""``coathertz predict --alpha-rule refit`` end to end (in-process)."""

from __future__ import annotations

import json

from coathertz.cli import main


def test_predict_refit_prints_rule_and_bound(capsys):
    assert main(["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
                 "--coating", "380 GPa,0.17,40 um", "--alpha-rule", "refit"]) == 0
    out = capsys.readouterr().out
    assert "alpha (refit)" in out
    assert "refit rule (elastic, second closed form: eqs 17-18 x smooth correction factor): validated " \
           "error bound" in out and "inside the validated range" in out
    assert "warning:" not in out


def test_predict_refit_json_and_out_of_range_warning(capsys):
    assert main(["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "100 GPa,0.3",
                 "--coating", "3000 GPa,0.3,1 um", "--alpha-rule", "refit", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["alpha_source"] == "refit"
    assert out["refit_bound"]["in_range"] is False
    assert any("outside the validated range" in w for w in out["warnings"])


def test_predict_refit_ellipse_and_rigid(capsys):
    assert main(["predict", "example:elliptical_fig10", "--alpha-rule", "refit"]) == 0
    assert "refit rule (ellipse, " in capsys.readouterr().out
    assert main(["predict", "example:rigid_substrate", "--alpha-rule", "refit"]) == 0
    assert "refit rule (rigid, " in capsys.readouterr().out
