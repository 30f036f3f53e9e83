"""``coathertz fem CASE --plastic --unload --steps N``: table, JSON curves, VTU files, bad input."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main
from coathertz.errors import CoatHertzError


def test_cli_plastic_unload(tmp_path, capsys):
    out = tmp_path / "curves.json"
    rc = main(["fem", "example:yielding_steel", "--plastic", "--unload", "--steps", "1", "--mesh", "coarse",
               "--out-json", str(out), "--vtu-dir", str(tmp_path / "vtu")])
    assert rc == 0
    text = capsys.readouterr()
    assert "residual depth" in text.out and "Newton" in text.out and "loading" in text.err
    data = json.loads(out.read_text())
    assert data["curves"]["phase"] == ["loading", "unloading"] and data["curves"]["W"][-1] == 0.0
    assert data["final"]["residual_depth"] > 0
    assert len(list((tmp_path / "vtu").glob("*.vtu"))) == 2


def test_cli_plastic_approach_control(capsys):
    rc = main(["fem", "example:yielding_steel", "--plastic", "--steps", "1", "--mesh", "coarse",
               "--approach", "1.5 um", "--json"])
    assert rc == 0
    data = json.loads(capsys.readouterr().out)
    assert data["meta"]["control"] == "approach" and abs(data["delta"][-1] - 1.5e-6) < 1e-15
    assert 50.0 < data["W"][-1] < 56.0  # Hertz at 1.5 um: 53.8 N (first yield 1.50 um at 54 N)


def test_cli_plastic_needs_yield_data():
    with pytest.raises(CoatHertzError, match="needs yield data"):
        from argparse import Namespace

        from coathertz.casefile import load_case
        from coathertz.cli._plastic import run_plastic

        run_plastic(load_case("example:homogeneous_steel"), Namespace())
