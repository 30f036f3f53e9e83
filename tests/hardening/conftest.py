"""Inputs for the hardening tests: bad case files written into a temporary folder."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

VERIF = Path(__file__).resolve().parents[1] / "verification"  # fake_method.py lives there
if str(VERIF) not in sys.path:
    sys.path.insert(0, str(VERIF))

CASE = """
W = "{W}"
[body1]
material = "rigid"
R = "{R}"
[body2]
material = {{ E = "200 GPa", nu = 0.3 }}
coating = {{ E = "{Ec}", nu = {nu_c}, h = "{h}" }}
"""


def write_case(folder: Path, name: str, **kw) -> Path:
    """A rigid sphere on a coated half-space, with any field replaced by ``kw``."""
    values = {"W": "1 N", "R": "10 mm", "Ec": "380 GPa", "nu_c": 0.17, "h": "40 um", **kw}
    path = folder / name
    path.write_text(CASE.format(**values))
    return path


@pytest.fixture
def bad_inputs(tmp_path, monkeypatch):
    """Work in ``tmp_path`` with the bad inputs of the table present."""
    monkeypatch.chdir(tmp_path)
    Path("binary.toml").write_bytes(bytes(range(256)) * 2)
    Path("dircase").mkdir()
    Path("afile").write_text("")
    Path("list.json").write_text("[1, 2, 3]")
    Path("garbage.sqlite").write_bytes(b"not a database " * 200)
    write_case(tmp_path, "nu_coat.toml", nu_c=0.6)
    write_case(tmp_path, "h_neg.toml", h="-40 um")
    write_case(tmp_path, "R_neg.toml", R="-10 mm")
    write_case(tmp_path, "big_load.toml", W="1e12 N")
    write_case(tmp_path, "W_neg.toml", W="-1 N")
    write_case(tmp_path, "Ec_neg.toml", Ec="-380 GPa")
    return tmp_path


def _check_one_clear_line(rc: int, err: str, argv: list[str], words: list[str]) -> None:
    """Exit status 2 and one line ``coathertz CMD: error: ...`` holding every one of ``words``."""
    assert rc == 2, f"exit status {rc}; stderr: {err}"
    assert "Traceback" not in err
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f"coathertz {argv[0]}: error: "), err
    for w in words:
        assert w in err, f"{w!r} not in {err!r}"


@pytest.fixture
def one_clear_line():
    """The check every bad-input table applies to a refused command (see
    :func:`_check_one_clear_line`)."""
    return _check_one_clear_line
