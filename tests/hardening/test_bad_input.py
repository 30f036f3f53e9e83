"""Every bad input in the table below gives one clear line on stderr and exit status 2.

The table (input, message) is the one in the hardening report; the CLI is called in-process
through ``main(argv)``. Commands that would compute check their output paths first, so the
rows with a bad output path take no solver time.
"""

from __future__ import annotations

import os

import pytest

from coathertz.cli import main

VERIFY = ["verify", "--tiny", "--study", "fig3", "--method", "closed-form", "--no-progress"]

#: (id, argv, words the message must contain)
TABLE = [
    ("binary case file", ["predict", "binary.toml"], ["binary.toml", "not a text"]),
    ("fem --plastic --steps 0", ["fem", "example:yielding_steel", "--plastic", "--steps", "0"],
     ["--steps", "[1, 10000]", "got 0"]),
    ("--plastic without yield data", ["fem", "example:b4c_on_steel", "--plastic"],
     ["needs yield data", "Y ="]),
    ("axisym on an elliptical case", ["axisym", "example:elliptical_fig10"], ["not axisymmetric", "use fft"]),
    ("axisym --modes 1", ["axisym", "example:keer_case_a", "--modes", "1"], ["--modes", "[2, 400]", "got 1"]),
    ("directory as case file", ["predict", "dircase"], ["dircase", "is a directory"]),
    ("missing case file", ["predict", "nothere.toml"], ["does not exist", "example:b4c_on_steel"]),
    # refused before building: the mesh would not fit in memory, and a/R says why
    ("fem at W = 1e12 N", ["fem", "big_load.toml", "--mesh", "coarse"],
     ["max_memory_gb", "a/R ~ 32", "outside the half-space model"]),
    ("--save-fields into a missing folder",
     ["fft", "example:b4c_on_steel", "--save-fields", "nodir/x.npz"],
     ["--save-fields", "'nodir' does not exist"]),
    ("--vtu into a missing folder",
     ["fem", "example:fig3_soft_coating", "--vtu", "nodir/x.vtu"], ["--vtu", "'nodir' does not exist"]),
    ("--vtu is a folder", ["fem", "example:fig3_soft_coating", "--vtu", "dircase"], ["--vtu", "is a folder"]),
    ("--baseline is a JSON list", [*VERIFY, "--out", "v", "--baseline", "list.json"],
     ["--baseline", "list.json", "not a coathertz baseline"]),
    ("--out is a file", [*VERIFY, "--out", "afile"], ["--out 'afile' is a file"]),
    ("--out cannot be created", [*VERIFY, "--out", "/proc/coathertz-test"], ["--out", "cannot write"]),
    ("--store is a folder", [*VERIFY, "--out", "v", "--store", "dircase"], ["dircase", "is a directory"]),
    ("damaged store", [*VERIFY, "--out", "v", "--store", "garbage.sqlite"],
     ["garbage.sqlite", "damaged", "--recover-store"]),
    ("coating nu = 0.6", ["predict", "nu_coat.toml"], ["[body2] coating", "nu", "got 0.6"]),
    ("coating h = -40 um", ["predict", "h_neg.toml"], ["[body2] coating thickness h", "'-40 um'"]),
    ("load W = -1 N", ["predict", "W_neg.toml"], ["load W", "'-1 N'"]),
    ("coating E = -380 GPa", ["predict", "Ec_neg.toml"], ["[body2] coating E", "'-380 GPa'"]),
    ("sphere R = -10 mm", ["predict", "R_neg.toml"], ["[body1] sphere radius R", "'-10 mm'"]),
    ("--R -10 mm", ["predict", "--W", "1 N", "--R", "-10 mm", "--substrate", "200 GPa,0.3"],
     ["--R", "radius R", "'-10 mm'"]),
    ("--coating nu 0.6", ["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
                          "--coating", "380 GPa,0.6,40 um"], ["--coating", "coating", "got 0.6"]),
    ("--indenter nu 0.7", ["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
                           "--indenter", "200 GPa,0.7"], ["--indenter", "indenter", "got 0.7"]),
    ("--W -1 N on a case file", ["fft", "example:b4c_on_steel", "--W", "-1 N"], ["--W", "'-1 N'"]),
    ("fft without a case", ["fft"], ["give a case file"]),
]


@pytest.mark.parametrize(("argv", "words"), [(a, w) for _, a, w in TABLE], ids=[t[0] for t in TABLE])
def test_bad_input_gives_one_clear_line(bad_inputs, capsys, one_clear_line, argv, words):
    rc = main(argv)
    one_clear_line(rc, capsys.readouterr().err.strip(), argv, words)
    assert not (bad_inputs / "nodir").exists()


def test_damaged_store_is_left_untouched(bad_inputs, capsys):
    before = (bad_inputs / "garbage.sqlite").read_bytes()
    assert main([*VERIFY, "--out", "v", "--store", "garbage.sqlite"]) == 2
    assert (bad_inputs / "garbage.sqlite").read_bytes() == before


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0,
                    reason="root may write into read-only folders")
def test_read_only_out(bad_inputs, capsys):
    ro = bad_inputs / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        assert main([*VERIFY, "--out", str(ro)]) == 2
        err = capsys.readouterr().err
        assert "--out" in err and "cannot write there" in err and "Traceback" not in err
        assert main(["fft", "example:b4c_on_steel", "--save-fields", str(ro / "f.npz")]) == 2
        assert "not writable" in capsys.readouterr().err
    finally:
        ro.chmod(0o755)
