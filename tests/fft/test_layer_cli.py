"""``coathertz fft --layer-cells``: a coating thinner than a cell is resolved, or flagged."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main

#: E = 4 coating (800 GPa on 200 GPa, nu = 0.3), h = 0.33 um = H 0.01: 0.52 cells at N = 128
THIN = ["fft", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
        "--coating", "800 GPa,0.3,0.33 um"]


def test_thin_coating_is_refined_and_the_output_says_so(capsys):
    assert main(THIN) == 0
    out = capsys.readouterr()
    assert "grid refined from 128 to 250: the coating spanned 0.52 cells" in out.out, out.out
    assert "warning" not in out.err, out.err
    assert main([*THIN, "--json"]) == 0
    meta = json.loads(capsys.readouterr().out)["meta"]
    assert meta["layer_refinement"]["n"] == meta["grid"]["nx"] == 250
    assert meta["layer_cells"] >= 1.0 and "accuracy" not in meta


def test_layer_cells_off_keeps_the_grid_and_warns(capsys):
    assert main([*THIN, "--layer-cells", "off", "--json"]) == 0
    out = capsys.readouterr()
    meta = json.loads(out.out)["meta"]
    assert meta["grid"]["nx"] == 128 and "layer_refinement" not in meta
    assert "warning: the coating is 0.52 cells thick" in out.err, out.err
    assert "n >= 248 resolves it" in meta["accuracy"]


@pytest.mark.parametrize("bad, why", [("abc", "expected a number of cells or 'off'"),
                                      ("0", "layer_cells must be None or a number in [0.1, 8]")])
def test_bad_layer_cells_is_a_clear_error(capsys, bad, why):
    with pytest.raises(SystemExit) as exc:
        rc = main([*THIN, "--layer-cells", bad])
        raise SystemExit(rc)
    assert exc.value.code == 2
    assert why in capsys.readouterr().err
