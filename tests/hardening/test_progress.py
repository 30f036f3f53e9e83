"""Progress of a run on stderr: a line every few seconds when stderr is not a
terminal, and an ETA weighted by each method's measured cost per case."""

from __future__ import annotations

import io

import pytest

from coathertz.runner import COST_PRIOR, PROGRESS_INTERVAL, Progress


class Clock:
    def __init__(self) -> None:
        self.t = 0.0

    def __call__(self) -> float:
        return self.t


def test_eta_is_weighted_by_the_measured_cost_of_each_method():
    """100 closed-form cases at 10 ms and 1 of 2 FE cases at 10 s are done after 11 s: one FE
    case (10 s) is left. A count-based ETA would say 11 s * 1/101 = 0.11 s."""
    clock, out = Clock(), io.StringIO()
    p = Progress({"closed-form": 100, "fem": 2}, "fig3", stream=out, tty=False, clock=clock)
    assert p.eta() is None
    for _ in range(100):
        clock.t += 0.01
        p.update("closed-form", 1, 0.01)
    clock.t += 10.0
    p.update("fem", 1, 10.0)
    assert p.eta() == pytest.approx(10.0, rel=1e-9)


def test_eta_before_a_method_has_finished_uses_its_cost_class():
    clock = Clock()
    p = Progress({"closed-form": 10, "fem": 1}, "x", stream=io.StringIO(), tty=False, clock=clock)
    clock.t = 0.1
    p.update("closed-form", 10, 0.1)
    # the FE case is priced at its class prior, measured against the closed form's 10 ms
    assert p.eta() == pytest.approx(0.1 * COST_PRIOR["expensive"] / 0.1, rel=1e-9)


def test_a_line_every_interval_when_stderr_is_not_a_terminal():
    clock, out = Clock(), io.StringIO()
    p = Progress({"fft": 640}, "fig3", stream=out, tty=False, clock=clock)
    for _ in range(640):
        clock.t += 1 / 32  # exact in binary; 20 s in all: a line at 5, 10, 15 and 20 s
        p.update("fft", 1, 1 / 32)
    p.close()
    lines = out.getvalue().splitlines()
    assert len(lines) == round(20.0 / PROGRESS_INTERVAL), lines
    assert lines[0] == "fig3: 160/640 cases done, 32 cases/s, elapsed 5 s, about 15 s left", lines[0]
    assert lines[-1] == "fig3: 640/640 cases done, 32 cases/s, elapsed 20 s", lines[-1]


def test_on_a_terminal_the_line_is_redrawn_and_erased():
    clock, out = Clock(), io.StringIO()
    p = Progress({"fft": 10}, "fig3", stream=out, tty=True, clock=clock)
    for _ in range(10):
        clock.t += 1.0
        p.update("fft", 1, 1.0)
    p.close()
    text = out.getvalue()
    assert "\n" not in text and text.count("\r") >= 10
    assert text.endswith("\r") and text.rsplit("\r", 2)[-2].strip() == ""


def test_disabled_progress_writes_nothing():
    clock, out = Clock(), io.StringIO()
    p = Progress({"fft": 10}, "fig3", enabled=False, stream=out, tty=False, clock=clock)
    for _ in range(10):
        clock.t += 10.0
        p.update("fft", 1, 10.0)
    p.close()
    assert out.getvalue() == ""


def test_the_readme_example_has_the_format_printed():
    import re
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    example = re.search(r"e\.g\. `(fig3: [^`]*)`", readme).group(1)
    clock, out = Clock(), io.StringIO()
    p = Progress({"fft": 220}, "fig3", stream=out, tty=False, clock=clock)
    clock.t = 7.0
    p.update("fft", 193, 7.0)
    pattern = re.sub(r"\d+(\.\d+)?", r"\\d+(\\.\\d+)?", re.escape(p.line()))
    assert re.fullmatch(pattern, example), (example, p.line())
