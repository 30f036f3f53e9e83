"""The example scripts of ``docs/examples`` run, and print numbers that agree with independent
values: Hertz's eq (1) written out here, the thick-coating limit, a stack identity.

Every script in the folder needs a checker below (a new example without one fails)."""

from __future__ import annotations

import itertools
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
NUM = r"([-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?)"


def run(name: str) -> str:
    out = subprocess.run([sys.executable, "-W", "error::UserWarning", str(EXAMPLES / name)],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert not out.stderr.strip(), out.stderr  # an example runs inside every model's assumptions
    return out.stdout


def values(pattern: str, text: str) -> list[tuple[float, ...]]:
    return [tuple(float(g) for g in m.groups()) for m in re.finditer(pattern.replace("NUM", NUM), text)]


def check_hertz_every_method(out: str) -> None:
    # Hertz eq (1), rigid sphere on steel: E* = E / (1 - nu^2)
    E_star = 210e9 / (1 - 0.3**2)
    a0 = (3 * 100.0 * 10e-3 / (4 * E_star)) ** (1 / 3)
    (a, d, p), = values(r"a = NUM um, delta = NUM um, p0 = NUM MPa", out)
    assert a == pytest.approx(a0 * 1e6, rel=1e-6)
    assert d == pytest.approx(a0**2 / 10e-3 * 1e6, rel=1e-5)
    assert p == pytest.approx(3 * 100.0 / (2 * math.pi * a0**2) / 1e6, rel=1e-5)
    rows = dict(zip(["closed-form", "fft", "axisym"],
                    values(r"a/a0 - 1 = NUM\s+delta/delta0 - 1 = NUM\s+p0/p0H - 1 = NUM", out), strict=True))
    # closed form and the exact method: Hertz to round-off (1e-12: ~1e3 machine epsilons)
    for name in ("closed-form", "axisym"):
        assert max(map(abs, rows[name])) < 1e-12, (name, rows[name])
    # FFT on 128^2: a to its sub-cell bound (0.3 %), delta and p0 to 2e-4
    da, dd, dp = rows["fft"]
    assert abs(da) < 3e-3 and abs(dd) < 2e-4 and abs(dp) < 2e-4, rows["fft"]


def check_coating_limits(out: str) -> None:
    (ratio,), = values(r"a0c/a0s = NUM", out)
    assert ratio == pytest.approx(4 ** (-1 / 3), rel=1e-6)  # a0 ~ E*^(-1/3)
    rows = values(r"H = NUM: exact a/a0s = NUM, closed form a/a0s = NUM", out)
    assert [r[0] for r in rows] == [0.01, 0.1, 1.0, 3.0]
    exact = [r[1] for r in rows]
    assert all(x > y for x, y in itertools.pairwise(exact)), exact  # a stiffer body: smaller contact
    assert 4 ** (-1 / 3) < exact[-1] < exact[0] < 1.0
    for H, ex, cf in rows:  # the paper's fig 3 accuracy (quick report: max 0.97 % on a)
        assert abs(cf / ex - 1) < 0.015, (H, ex, cf)
    # thick limit: the substrate's effect decays like H^-3 (2e-3 at H = 3, so ~5e-8 at H = 100);
    # 1e-5 fails for any error in the limit itself
    (H, thick), = values(r"H = NUM: exact a/a0s = NUM\n", out + "\n")[-1:]
    assert H == 100 and abs(thick / 4 ** (-1 / 3) - 1) < 1e-5, thick


def check_layer_stack(out: str) -> None:
    rows = values(r"a = NUM um, delta = NUM nm, p0 = NUM GPa", out)
    assert len(rows) == 2 and 10 < rows[0][0] < 100  # a of tens of micrometres at 2 N
    (diff,), = values(r"largest relative difference: NUM", out)
    assert diff < 1e-9  # the exact method's identities hold to round-off


CHECKS = {f.__name__.removeprefix("check_") + ".py": f for f in
          (check_hertz_every_method, check_coating_limits, check_layer_stack)}


def test_every_example_has_a_check():
    assert sorted(p.name for p in EXAMPLES.glob("*.py")) == sorted(CHECKS)


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_example(name):
    CHECKS[name](run(name))
