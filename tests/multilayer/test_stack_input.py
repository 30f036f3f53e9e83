"""Layer stacks from case files (``[[body2.layers]]``) and the CLI (``--coating`` repeated, top
first): same case both ways; bad input is one line naming the layer (exit 2 on the CLI)."""

from __future__ import annotations

import pytest

from coathertz.casefile import case_from_dict
from coathertz.cli import main
from coathertz.errors import CoatHertzError

BASE = {"W": "1 N", "body1": {"material": "rigid", "R": "10 mm"},
        "body2": {"material": {"E": "210 GPa", "nu": 0.3}}}
LAYERS = [{"E": "150 GPa", "nu": 0.22, "h": "2 um"},
          {"E": "300 GPa", "nu": 0.22, "h": "1.5 um", "interface": "frictionless"},
          {"E": "279 GPa", "nu": 0.21, "h": "0.3 um"}]
FLAGS = ["--W", "1 N", "--R", "10 mm", "--substrate", "210 GPa,0.3", "--coating", "150 GPa,0.22,2 um",
         "--coating", "300 GPa,0.22,1.5 um,frictionless", "--coating", "279 GPa,0.21,0.3 um"]


def doc(layers):
    return {**BASE, "body2": {**BASE["body2"], "layers": layers}}


def test_case_file_layers():
    c = case_from_dict(doc(LAYERS))
    L = c.body2.layers
    assert [x.h for x in L] == pytest.approx([2e-6, 1.5e-6, 0.3e-6], rel=1e-15)
    assert [x.interface for x in L] == ["bonded", "frictionless", "bonded"]
    assert L[0].material.E == 150e9 and c.is_stacked and not c.body2.is_coated


def test_cli_flags_equal_case_file(tmp_path, capsys):
    f = tmp_path / "s.toml"
    f.write_text('W = "1 N"\n[body1]\nmaterial = "rigid"\nR = "10 mm"\n[body2]\n'
                 'material = { E = "210 GPa", nu = 0.3 }\n'
                 + "".join(f'[[body2.layers]]\nE = "{x["E"]}"\nnu = {x["nu"]}\nh = "{x["h"]}"\n'
                           + (f'interface = "{x["interface"]}"\n' if "interface" in x else "")
                           for x in LAYERS))
    assert main(["axisym", str(f), "--json"]) == 0
    a = capsys.readouterr().out
    assert main(["axisym", *FLAGS, "--json"]) == 0
    b = capsys.readouterr().out
    import json

    da, db = json.loads(a), json.loads(b)
    for q in ("delta", "a", "p0"):
        assert da[q] == db[q], q


@pytest.mark.parametrize("layers,text", [
    ([], "[body2] layers: the stack is empty"),
    ([LAYERS[0], {**LAYERS[1], "h": "0 um"}], "[body2] layer 2 thickness h"),
    ([{**LAYERS[0], "nu": 0.6}], "[body2] layer 1: Poisson's ratio nu must satisfy"),
    ([{**LAYERS[0], "interface": "glued"}], "[body2] layer 1: interface must be one of"),
    ([{"E": "1 GPa", "nu": 0.3}], "[body2] layer 1: missing h"),
    ([LAYERS[0], LAYERS[1], {**LAYERS[2], "h": "-0.3 um"}], "[body2] layer 3 thickness h"),
    ([LAYERS[0], {**LAYERS[1], "interface": "sliding"}], "[body2] layer 2: interface must be one of"),
    ([{**LAYERS[0], "E": "0 GPa"}], "[body2] layer 1 E must satisfy 0 < E"),
    ([{**LAYERS[0], "E": "-150 GPa"}], "[body2] layer 1 E must satisfy 0 < E"),
])
def test_bad_case_file_layer_is_one_line(layers, text):
    with pytest.raises(CoatHertzError) as exc:
        case_from_dict(doc(layers))
    msg = str(exc.value)
    assert text in msg and "\n" not in msg, msg


def test_coating_and_layers_refused():
    d = doc(LAYERS)
    d["body2"]["coating"] = {"E": "380 GPa", "nu": 0.17, "h": "1 um"}
    with pytest.raises(CoatHertzError, match="either a coating or"):
        case_from_dict(d)


@pytest.mark.parametrize("bad,text", [
    ("300 GPa,0.22,-1.5 um", "--coating: layer 2 thickness h must satisfy 0 < h < inf"),
    ("300 GPa,0.22,0 um", "--coating: layer 2 thickness h must satisfy 0 < h < inf"),
    ("300 GPa,0.7,1.5 um", "--coating: layer 2 Poisson's ratio nu must satisfy"),
    ("300 GPa,0.22,1.5 um,glued", "--coating: layer 2: interface must be one of"),
])
def test_bad_cli_layer_exits_2(bad, text, capsys):
    argv = ["axisym", "--W", "1 N", "--R", "10 mm", "--substrate", "210 GPa,0.3",
            "--coating", "150 GPa,0.22,2 um", "--coating", bad]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert text in err and "\n" not in err and "Traceback" not in err, err


def test_bad_layer_on_body1_names_body1():
    d = doc(LAYERS)
    d["body1"] = {"material": {"E": "210 GPa", "nu": 0.3}, "R": "10 mm",
                  "layers": [{**LAYERS[0], "nu": 0.55}]}
    with pytest.raises(CoatHertzError) as exc:
        case_from_dict(d)
    msg = str(exc.value)
    assert "[body1] layer 1: Poisson's ratio nu must satisfy" in msg and "\n" not in msg, msg


@pytest.mark.parametrize("command", ["predict", "axisym", "fft", "fem"])
def test_interface_flag_on_a_stack_is_refused(command, capsys):
    """``--interface`` sets a single coating's interface; on a stack (interfaces per layer) it
    was silently ignored. Now one line naming the body and where a stack's interfaces go."""
    assert main([command, "example:tin_ti_on_steel", "--interface", "frictionless"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--interface: body2 has a layer stack" in err and "\n" not in err, err
