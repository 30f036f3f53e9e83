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


def test_readme_three_method_numbers(capsys):
    """The numbers quoted for case A: closed form exactly as printed by predict; FFT (128^2) and
    FE (default mesh) to the quoted digits (their convergence studies put both within 2e-4)."""
    from coathertz.casefile import load_example
    from coathertz.extended import predict
    from coathertz.fem.method import FEMMethod
    from coathertz.fft.method import FFTMethod

    text = README.read_text()
    case = load_example("keer_case_a")
    r = predict(case)
    assert f"δ = {r.delta * 1e6:.5f} µm, a = {r.a * 1e6:.3f} µm, p0 = {r.p0 / 1e6:.2f} MPa" in text
    for res in (FFTMethod(n=128, keep_fields=False).solve(case), FEMMethod().solve(case)):
        assert abs(res.delta * 1e6 - 0.15817) < 2e-5
        assert abs(res.a * 1e6 - 37.005) < 0.01
        assert abs(res.p0 / 1e6 - 314.92) < 0.02
