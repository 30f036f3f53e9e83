"""The README contract: every command it shows is run here or by .ci/run.

The ```bash blocks after the <!-- main-job --> and <!-- test-command --> markers are run by
.ci/run; every other ``coathertz ...`` line in a ```bash block, and every ```python block,
is run here.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from coathertz.cli import main

README = Path(__file__).resolve().parents[1] / "README.md"


def _blocks(lang: str) -> list[tuple[str, str]]:
    """(marker before the block or '', block text) for each ```lang block."""
    text = README.read_text()
    out = []
    for m in re.finditer(rf"(<!-- [\w-]+ -->\n)?```{lang}\n(.*?)```", text, re.S):
        out.append(((m.group(1) or "").strip(), m.group(2)))
    return out


def test_ci_blocks_present():
    markers = {mark: body for mark, body in _blocks("bash") if mark}
    assert "coathertz verify --quick --out reports/quick" in markers["<!-- main-job -->"]
    assert "pytest" in markers["<!-- test-command -->"]
    ci = (README.parent / ".ci" / "run").read_text()
    assert "<!-- main-job -->" in ci and "<!-- test-command -->" in ci


COMMANDS = [
    line.strip()
    for mark, body in _blocks("bash")
    if not mark
    for line in body.splitlines()
    if line.strip().startswith("coathertz ")
]


@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs(command, capsys):
    assert main(shlex.split(command)[1:]) == 0
    assert capsys.readouterr().out.strip()


def test_readme_numbers_are_what_predict_prints(capsys):
    main(["predict", "example:b4c_on_steel"])
    out = capsys.readouterr().out
    text = README.read_text()
    for number in ("0.15636", "37.989", "327.32"):
        assert number in out and number in text


@pytest.mark.parametrize("code", [b for _, b in _blocks("python")])
def test_readme_python_runs(code, capsys):
    exec(compile(code, "README", "exec"), {})
    assert capsys.readouterr().out.strip()
