"""A fast, controllable stand-in for a numerical method (runner and store tests).

Imported by module name (``conftest.py`` puts this folder on ``sys.path``) so that worker
processes and subprocesses can unpickle it.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

from coathertz.case import ContactCase
from coathertz.errors import ConvergenceError
from coathertz.results import ContactResult


@dataclass(frozen=True)
class FakeMethod:
    """Hertz with the coatings removed; optionally slow, logging, or failing on one label."""

    name: str = "fake"
    delay: float = 0.0
    log: str | None = None
    fail_label: str | None = None

    def settings(self) -> dict:
        return {"kind": "hertz-s", "fail": self.fail_label}

    def supports(self, case: ContactCase) -> bool:
        return True

    def solve(self, case: ContactCase) -> ContactResult:
        if self.log:
            with open(self.log, "a") as fh:
                fh.write(f"{case.label} {os.getpid()}\n")
        if self.delay:
            time.sleep(self.delay)
        if case.label == self.fail_label:
            raise ConvergenceError(f"fake failure on {case.label}")
        h = case.hertz_s
        return ContactResult(self.name, float(h.delta0), float(h.a0), float(h.p0), case.W,
                             meta={"pid": os.getpid()})


def cases(n: int) -> list[ContactCase]:
    from coathertz.materials import Material

    sub, coat = Material(200e9, 0.3), Material(400e9, 0.3)
    return [ContactCase.sphere_on_coated_half_space(10e-3, 1.0 + i, coat, 1e-6, sub, label=f"c{i}")
            for i in range(n)]


@dataclass(frozen=True)
class FifthMethod:
    """A registered-looking method with the full metadata of :mod:`coathertz.methods`: Hertz of the
    substrate scaled by ``bias`` (so its results are recognisable), ranked above the FFT."""

    bias: float = 1.0
    name: str = "fifth"

    cost = "cheap"
    marker = "P"
    label = "fifth method (test)"
    reference_rank = 25
    source_packages = ("fake_method",)

    @classmethod
    def settings_for(cls, resolution: str) -> dict:
        return {"bias": {"tiny": 1.001, "quick": 1.0, "full": 1.0}[resolution]}

    def settings(self) -> dict:
        return {"bias": self.bias}

    def supports(self, case: ContactCase) -> bool:
        return case.is_circular

    def solve(self, case: ContactCase) -> ContactResult:
        h = case.hertz_s
        return ContactResult(self.name, float(h.delta0) * self.bias, float(h.a0) * self.bias,
                             float(h.p0) * self.bias, case.W)
