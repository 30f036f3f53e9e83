"""Bad inputs of one clear line on stderr, exit status 2, no traceback; silent
answers made explicit; output paths checked before anything is computed.

The CLI is called in-process through ``main(argv)`` except where the behaviour belongs to the
process (a closed pipe, SIGINT to the process group): those run the console script.
"""

from __future__ import annotations

import gzip
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from coathertz.casefile import load_case
from coathertz.cli import main
from coathertz.errors import CoatHertzError
from coathertz.methods import get_method
from coathertz.units import parse_quantity

VERIFY = ["verify", "--tiny", "--study", "fig3", "--method", "closed-form", "--no-progress"]
EXE = Path(sys.executable).with_name("coathertz")
CASE = Path(__file__).resolve().parents[2] / "src" / "coathertz" / "data" / "b4c_on_steel.toml"


@pytest.fixture
def inputs(tmp_path, monkeypatch):
    """Work in ``tmp_path`` with the bad files of the table present."""
    monkeypatch.chdir(tmp_path)
    Path("notgz.json.gz").write_text("hi")
    Path("cut.json.gz").write_bytes(gzip.compress(b'{"format": "x", "columns": {}}')[:20])
    shutil.copy(CASE, "case.toml")
    text = CASE.read_text()
    Path("theta.toml").write_text(text.replace('W = "1 N"', 'W = "1 N"\ntheta = 1e308'))
    Path("bom.toml").write_bytes(b"\xef\xbb\xbf" + CASE.read_bytes())
    Path("empty.sqlite").write_bytes(b"")
    return tmp_path


#: (id, argv, words the message must contain)
TABLE = [
    ("--scheduler 'not a url'", [*VERIFY, "--out", "v", "--scheduler", "not a url"],
     ["--scheduler 'not a url'", "not a scheduler address", "tcp://"]),
    ("--scheduler without a port", [*VERIFY, "--out", "v", "--scheduler", "tcp://somehost"],
     ["--scheduler", "missing port"]),
    ("fit-alpha --sweep not gzip", ["fit-alpha", "--sweep", "notgz.json.gz"],
     ["--sweep 'notgz.json.gz'", "not gzip-compressed JSON"]),
    ("fit-alpha --sweep truncated gzip", ["fit-alpha", "--sweep", "cut.json.gz"],
     ["--sweep 'cut.json.gz'", "not gzip-compressed JSON"]),
    ("fit-alpha --sweep a TOML file", ["fit-alpha", "--sweep", "case.toml"],
     ["--sweep 'case.toml'", "not JSON"]),
    ("fit-alpha --elastic-grid a,b", ["fit-alpha", "--elastic-grid", "a,b"],
     ["--elastic-grid", "3 comma-separated integers", "'a,b'"]),
    ("fit-alpha --rigid-grid 65", ["fit-alpha", "--rigid-grid", "65"], ["--rigid-grid", "'65'"]),
    ("theta = 1e308", ["predict", "theta.toml"], ["theta", "[-360 deg, 360 deg]", "1e+308"]),
    ("fem --vtu mesh.txt", ["fem", "case.toml", "--vtu", "mesh.txt"], ["--vtu 'mesh.txt'", "end in .vtu"]),
    ("--alpha a=1e300", ["predict", "case.toml", "--alpha", "a=1e300,p=1.6,delta=1.1"],
     ["--alpha", "alpha_a", "0 < alpha <= 1000", "1e+300"]),
    ("--W 1e400 N", ["predict", "case.toml", "--W", "1e400 N"], ["--W", "largest floating-point"]),
    ("--save-fields /proc", ["axisym", "case.toml", "--save-fields", "/proc/x.npz"],
     ["--save-fields '/proc/x.npz'", "cannot write"]),
    ("fem --plastic --out-json /proc", ["fem", "example:yielding_steel", "--plastic", "--out-json",
                                         "/proc/x.json"], ["--out-json '/proc/x.json'", "cannot write"]),
]


@pytest.mark.parametrize(("argv", "words"), [(a, w) for _, a, w in TABLE], ids=[t[0] for t in TABLE])
def test_bad_input_gives_one_clear_line(inputs, capsys, one_clear_line, argv, words):
    t0 = time.perf_counter()
    rc = main(argv)
    dt = time.perf_counter() - t0
    one_clear_line(rc, capsys.readouterr().err.strip(), argv, words)
    assert not (inputs / "v").exists(), "the --out folder was created before the input was checked"
    assert not (inputs / "mesh.txt").exists()
    assert dt < 5.0, f"{dt:.1f} s: the command computed before refusing its input"


def test_save_fields_writes_exactly_the_name_given(inputs, capsys):
    for name in ("fields", "prof.dat"):
        assert main(["axisym", "case.toml", "--save-fields", name]) == 0
        assert f"fields written to {name} (NumPy .npz archive)" in capsys.readouterr().out
        assert Path(name).is_file() and not Path(f"{name}.npz").exists()
        with np.load(name) as z:
            assert {"r", "p"} <= set(z.files) or len(z.files) >= 2, z.files


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full on this system")
def test_disk_full_names_the_file(inputs, capsys):
    assert main(["axisym", "case.toml", "--save-fields", "/dev/full"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("coathertz axisym: error: --save-fields '/dev/full': writing failed"), err
    assert "No space left" in err and len(err.splitlines()) == 1
    assert not Path("/dev/full.npz").exists()


def test_empty_store_says_its_results_are_gone(inputs, capsys):
    assert main([*VERIFY, "--out", "v", "--store", "empty.sqlite"]) == 0
    err = capsys.readouterr().err
    assert "empty.sqlite is empty (0 bytes): any results it held are gone" in err, err


def test_locked_store_does_not_create_the_out_folder(inputs, capsys):
    from coathertz.store import open_run_store

    held = open_run_store(inputs / "held.sqlite")
    try:
        assert main([*VERIFY, "--out", "new_out", "--store", "held.sqlite"]) == 2
    finally:
        held.close()
    err = capsys.readouterr().err
    assert "held.sqlite" in err and "Traceback" not in err
    assert not (inputs / "new_out").exists()


def test_bom_case_file_is_read(inputs):
    assert load_case("bom.toml") == load_case("case.toml")


def test_km_is_a_length():
    assert parse_quantity("1 km", "length") == 1e3
    with pytest.raises(CoatHertzError, match="overflows in SI units"):
        parse_quantity("1e306 km", "length", name="R")


@pytest.mark.parametrize(("name", "settings", "words"), [
    ("fft", {"grid": 0}, ["get_method('fft')", "unknown setting grid", "takes n,"]),
    ("axisym", {"bogus": 1}, ["get_method('axisym')", "unknown setting bogus", "n_modes"]),
    ("fft", {"n": 0}, ["get_method('fft')", "grid n", "got 0"]),
])
def test_get_method_names_the_bad_setting(name, settings, words):
    with pytest.raises(CoatHertzError) as info:
        get_method(name, **settings)
    for w in words:
        assert w in str(info.value), str(info.value)


@pytest.mark.parametrize("name", ["fft", "axisym", "closed-form"])
def test_solve_names_a_case_that_is_not_one(name):
    with pytest.raises(CoatHertzError, match=rf"{name}.solve\(case\): case must be a coathertz "
                                             r"ContactCase.*got str 'case'"):
        get_method(name).solve("case")


@pytest.mark.skipif(not EXE.exists(), reason="console script not installed next to the interpreter")
def test_closed_pipe_exits_quietly(tmp_path):
    r = subprocess.run(f"'{EXE}' verify --list | head -1", shell=True, capture_output=True, text=True,
                       cwd=tmp_path, timeout=120)
    assert r.stdout.startswith("study"), r.stdout
    assert r.stderr == "", r.stderr


def _default_sigint() -> None:
    """In the child: Ctrl-C's default action, whatever the launcher left. A suite started in the
    background by a non-interactive shell (``bash .ci/run &``) ignores SIGINT, and a Python
    started so keeps ignoring it: the run then went on past the test's timeout."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.skipif(not EXE.exists() or os.name != "posix", reason="needs the console script and POSIX")
def test_sigint_to_the_process_group_prints_no_worker_traceback(tmp_path):
    """Ctrl-C in a terminal signals the whole process group, workers included."""
    p = subprocess.Popen([str(EXE), "verify", "--full", "--study", "fig3", "--method", "fft",  # minutes
                          "--no-progress", "--workers", "2", "--out", str(tmp_path / "o")],
                         stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
                         start_new_session=True,
                         preexec_fn=_default_sigint, env={**os.environ, "OMP_NUM_THREADS": "1"})
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (tmp_path / "o" / "store.sqlite").exists():
        time.sleep(0.1)
    time.sleep(2.0)  # workers forked and solving
    assert p.poll() is None, "the run ended before it could be interrupted"
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, err)
    assert "Process ForkProcess" not in err and "Traceback" not in err, err
    assert "interrupted" in err, err


def test_disk_full_while_writing_the_report_names_the_file(inputs, capsys, monkeypatch):
    import errno

    import coathertz.report

    def full(results, out, *args, **kw):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(out / "fig3_errors.png"))

    monkeypatch.setattr(coathertz.report, "write_report", full)
    assert main([*VERIFY, "--out", "rep"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("coathertz verify: error: --out 'rep': writing 'rep/fig3_errors.png' failed "
                          "(No space left on device)"), err
