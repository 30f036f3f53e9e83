"""The shipped data file is reproducible from the shipped sweep (issue 10, "Must show").

* fast: the small fixture sweep (``tests/refit/data/small_sweep.json``, a subset of the shipped
  sweep) refits to exactly the fixture data file, through the ``fit-alpha`` command;
* fast: the shipped data file records the hash of the shipped sweep it was fitted from, and its
  validation errors are those of its surfaces on the sweep's validation rows;
* slow: a full refit of the shipped sweep reproduces the shipped coefficients.
"""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from coathertz.cli import main
from coathertz.cli.fit_alpha import compare, load_sweep
from coathertz.refit import load
from coathertz.refit.build import build
from coathertz.refit.sweep import select, table_hash

HERE = Path(__file__).parent / "data"
DATA = resources.files("coathertz") / "data"


def test_small_sweep_refits_to_fixture(tmp_path, capsys):
    out = tmp_path / "refit.json"
    rc = main(["fit-alpha", "--sweep", str(HERE / "small_sweep.json"), "--out", str(out),
               "--check", str(HERE / "small_refit.json")])
    text = capsys.readouterr().out
    assert rc == 0, text
    assert "matches" in text
    new, old = json.loads(out.read_text()), json.loads((HERE / "small_refit.json").read_text())
    for cfg in old["surfaces"]:
        for q, s in old["surfaces"][cfg].items():
            np.testing.assert_allclose(new["surfaces"][cfg][q]["coef"], s["coef"], rtol=1e-7, atol=1e-9)


def test_check_detects_a_different_file(tmp_path, capsys):
    """--check fails when the coefficients differ (the test above can fail)."""
    d = json.loads((HERE / "small_refit.json").read_text())
    d["surfaces"]["elastic"]["p"]["coef"][0] += 1e-3
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(d))
    assert main(["fit-alpha", "--sweep", str(HERE / "small_sweep.json"), "--check", str(bad)]) == 1
    assert "DIFFERS" in capsys.readouterr().out


def test_shipped_file_was_fitted_from_shipped_sweep():
    rule = load()
    cols, _ = load_sweep(Path(str(DATA / "alpha_refit_sweep.json")))
    assert rule.data["provenance"]["sweep_sha256"] == table_hash(cols)
    for key in ("code_version", "circular_method", "ellipse_method", "command"):
        assert key in rule.data["provenance"], key
    # the stored validation errors are those of the shipped surfaces on the validation rows
    for cfg in ("elastic", "rigid"):
        va = select(cols, config=cfg, set="valid")
        m = rule.model(cfg)
        for q in ("a", "delta", "p"):
            err = 100 * np.abs(m.bar(q, va["E"], va["H"], va["nu_c"], va["nu_s"]) / va[f"{q}_bar"] - 1)
            assert float(err.max()) == pytest.approx(rule.data["validation_error"][cfg][q]["max"], rel=1e-9)


@pytest.mark.slow
def test_full_refit_reproduces_shipped_file():
    cols, prov = load_sweep(Path(str(DATA / "alpha_refit_sweep.json")))
    new = build(cols, provenance=prov)
    assert compare(new, load().data) < 1e-6
