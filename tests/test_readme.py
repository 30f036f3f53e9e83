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


#: Numbers the README quotes from a command's output, by the command's first words.
QUOTED = {
    "coathertz fit-alpha": ["0.111", "0.045", "0.172", "0.004", "0.057", "0.047", "3.747", "5.101", "4.279",
                            "0.023", "1.544", "0.432", "7.34", "17.46", "22.81", "73.11", "95.24", "1430.15",
                            "165 of 11337", "3.73 %", "0.167", "0.343", "0.014", "0.380", "7.23", "20.75",
                            "13.03", "19.05", "(matches)"],
    "coathertz fem example:yielding_steel --plastic": ["28710", "20 increments", "1913", "29.12-178.9",
                                                       "0.00355", "0.24762"],
}


@pytest.mark.parametrize("command", COMMANDS)
def test_readme_command_runs(command, capsys):
    assert main(shlex.split(command)[1:]) == 0
    out = capsys.readouterr().out
    assert out.strip()
    text = README.read_text()
    for prefix, numbers in QUOTED.items():
        if command.startswith(prefix):
            for number in numbers:
                assert number in out, f"`{command}` does not print {number!r}"
                assert number.replace("-", "–") in text or number in text, number


def test_quoted_commands_are_in_the_readme():
    assert all(any(c.startswith(p) for c in COMMANDS) for p in QUOTED)


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


def _three_methods() -> list[list[str]]:
    """Rows (method, command, delta, a, p0) of the table after <!-- three-methods -->."""
    text = README.read_text().split("<!-- three-methods -->", 1)[1]
    rows = []
    for line in text.strip().splitlines():
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[1].startswith("`coathertz "):
            rows.append([cells[0], cells[1].strip("`"), *cells[2:5]])
    return rows


def _printed(out: str) -> tuple[str, str, str]:
    """(delta, a, p0) as printed: the extended-Hertz row of predict, the first value column of
    the delta / a / p0 rows of fft and fem."""
    lines = out.splitlines()
    ext = [ln for ln in lines if ln.startswith("extended Hertz")]
    if ext:
        return tuple(ext[0].split()[2:5])
    def value(prefix: str) -> str:  # "a [um] (edge-fit)   37.005  0.90170" -> "37.005"
        row = next(ln for ln in lines if ln.startswith(prefix))
        return re.match(r"[^\]]*\]\s*(?:\([^)]*\)\s*)?(\S+)", row).group(1)
    return value("delta [um]"), value("a [um]"), value("p0 [MPa]")


def test_readme_three_methods_table_is_what_the_commands_print(capsys):
    """the quoted numbers are exactly what the shown commands print."""
    rows = _three_methods()
    assert [r[1].split()[1] for r in rows] == ["predict", "fft", "fem", "axisym"]
    for method, command, *quoted in rows:
        assert main(shlex.split(command)[1:]) == 0
        printed = _printed(capsys.readouterr().out)
        assert list(printed) == quoted, f"{method}: README quotes {quoted}, `{command}` prints {printed}"


def test_readme_says_how_to_reach_the_command():
    """the install puts coathertz in .venv/bin; the README says so."""
    block = dict(_blocks("bash"))["<!-- activate -->"]
    assert "source .venv/bin/activate" in block
    assert ".venv/bin/coathertz" in README.read_text()


def test_readme_needs_nothing_outside_the_repository():
    """the notes users need are in the repository."""
    text = README.read_text()
    assert "../shared" not in text
    for link in re.findall(r"\]\(([^)#]+)", text):
        if not link.startswith("http"):
            assert (README.parent / link).exists(), link
