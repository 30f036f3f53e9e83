"""``coathertz fem CASE --plastic --unload --steps N``: table, JSON curves, VTU files, bad input."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main
from coathertz.errors import CoatHertzError


def test_cli_plastic_unload(tmp_path, capsys):
    out = tmp_path / "curves.json"
    rc = main(["fem", "example:yielding_steel", "--plastic", "--unload", "--steps", "1", "--mesh", "coarse",
               "--out-json", str(out), "--vtu-dir", str(tmp_path / "vtu"),
               "--out-csv", str(tmp_path / "c.csv"), "--plot-dir", str(tmp_path / "fig")])
    assert rc == 0
    text = capsys.readouterr()
    assert "residual depth" in text.out and "Newton" in text.out and "loading" in text.err
    data = json.loads(out.read_text())
    # one step: the loading's first increment ends at the elastic onset (homogeneous body)
    assert data["curves"]["phase"] == ["loading", "loading", "unloading"] and data["curves"]["W"][-1] == 0.0
    # (the coarse mesh yields 0.66 % below Hertz's onset load: a trace of plastic strain there)
    assert data["curves"]["ep_max"][0] < 0.01 * data["curves"]["ep_max"][1], data["curves"]["ep_max"]
    assert data["final"]["residual_depth"] > 0
    # the W = 0 row has no nan: no contact (a = p_mean = 0), the approach at which the sphere just
    # touches the crater's bottom is the residual depth
    c = data["curves"]
    assert c["a"][-1] == 0.0 and c["p_mean"][-1] == 0.0
    assert c["delta"][-1] == pytest.approx(data["final"]["residual_depth"], rel=1e-12)
    assert all(v is not None for k in ("W", "delta", "a", "p_max", "p_mean") for v in c[k])
    import csv

    rows = list(csv.reader((tmp_path / "c.csv").open()))
    assert rows[0][:3] == ["W [N]", "delta [m]", "a [m]"] and len(rows) == 4
    assert float(rows[1][0]) == pytest.approx(c["W"][0], rel=1e-15) and float(rows[3][0]) == 0.0
    assert "nan" not in (tmp_path / "c.csv").read_text()
    import matplotlib.image as mpimg

    for name in ("load_approach.png", "plastic_zone.png"):
        img = mpimg.imread(tmp_path / "fig" / name)
        assert img.shape[0] > 300 and img[..., :3].std() > 0.05, name  # not blank
    assert len(list((tmp_path / "vtu").glob("*.vtu"))) == 3  # one per increment: onset, full load, unloaded


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


def _one_line_error(argv, capsys) -> str:
    rc = main(argv)
    err = capsys.readouterr().err.strip()
    assert rc == 2, f"exit status {rc}; stderr: {err}"
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    return err


def test_cli_plastic_reload_needs_unload(capsys):
    err = _one_line_error(["fem", "example:yielding_steel", "--plastic", "--reload"], capsys)
    assert "--reload" in err and "--unload" in err


@pytest.mark.parametrize("flag", ["--unload", "--follow-contact", "--approach=2um"])
def test_cli_plastic_options_need_plastic(flag, capsys):
    """A path option without ``--plastic`` is one clear line, not silently ignored."""
    err = _one_line_error(["fem", "example:yielding_steel", flag], capsys)
    assert flag.split("=")[0] in err and "--plastic" in err


def test_cli_plastic_follow_contact(capsys):
    """``--follow-contact``: the table's elements across a stay near the mesh's own at the first
    increment (16.4 on the coarse mesh) instead of falling to 1-3 early on a mesh sized for the
    deepest approach; one line reports the remeshes and the largest load change of a rebalance."""
    rc = main(["fem", "example:yielding_steel", "--plastic", "--steps", "3", "--mesh", "coarse",
               "--approach", "6 um", "--follow-contact", "--json"])
    assert rc == 0
    data = json.loads(capsys.readouterr().out)
    assert data["meta"]["follow_contact"] and len(data["meta"]["remeshes"]) >= 1
    assert min(data["elements_across_a"]) > 12 / 1.25, data["elements_across_a"]
    rc = main(["fem", "example:yielding_steel", "--plastic", "--steps", "3", "--mesh", "coarse",
               "--approach", "6 um", "--follow-contact"])
    out = capsys.readouterr().out
    assert rc == 0 and "contact-following meshes:" in out and "remeshes" in out


def test_cli_plastic_elastic_path_says_no_plastic_zone(capsys):
    """Below first yield (54 N) there is no plastic zone: one line says so (no 'depth nan-0 um')."""
    rc = main(["fem", "example:yielding_steel", "--W", "20 N", "--plastic", "--steps", "1", "--mesh",
               "coarse"])
    out = capsys.readouterr().out
    assert rc == 0
    assert "plastic zone: none" in out and "nan" not in out


def test_cli_plastic_mesh_help_names_the_plastic_levels(capsys):
    with pytest.raises(SystemExit):
        main(["fem", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "with --plastic 12 / 20 / 32" in out


def test_linear_hardening_needs_H():
    from coathertz.casefile import case_from_dict

    data = {"W": "10 N", "body1": {"material": "rigid", "R": "10 mm"},
            "body2": {"material": {"E": "200 GPa", "nu": 0.3, "Y": "1 GPa", "hardening": "linear"}}}
    with pytest.raises(CoatHertzError, match=r'hardening = "linear" needs the hardening modulus H'):
        case_from_dict(data)
    data["body2"]["material"]["H"] = "10 GPa"
    assert case_from_dict(data).body2.material.plasticity.H == 10e9


def test_cli_plastic_says_when_the_mesh_grew(monkeypatch, capsys):
    """A mesh sized for a third of the contact: the run grows it and says so on one line."""
    import coathertz.fem.plastic.method as pm

    sized = pm.reference_radius
    monkeypatch.setattr(pm, "reference_radius", lambda *a, **k: sized(*a, **k) / 3.0)
    rc = main(["fem", "example:yielding_steel", "--plastic", "--steps", "1", "--mesh", "coarse",
               "--approach", "1.5 um"])
    cap = capsys.readouterr()
    assert rc == 0
    lines = [ln for ln in cap.err.splitlines() if "grown mesh" in ln]
    assert len(lines) == 1 and "candidate zone's edge" in lines[0], cap.err
