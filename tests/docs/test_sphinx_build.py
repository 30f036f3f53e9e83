"""The documentation builds with warnings as errors and every cross-reference resolved (the
README's docs command); every module of the package is on a page."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def readme_docs_command() -> list[str]:
    """The arguments of the README's docs build command (the block after ``<!-- docs-build -->``)."""
    m = re.search(r"<!-- docs-build -->\n```bash\n(.*?)\n```", (ROOT / "README.md").read_text(), re.S)
    assert m, "README: the docs build command (<!-- docs-build -->) is missing"
    words = shlex.split(m.group(1))
    assert words[0] == ".venv/bin/sphinx-build", words
    return words[1:]


def test_docs_build_without_warnings():
    pytest.importorskip("sphinx", reason="the docs extra is not installed (pip install -e '.[docs]')")
    pytest.importorskip("myst_parser", reason="the docs extra is not installed (pip install -e '.[docs]')")
    args = readme_docs_command()
    assert {"-E", "-W", "-n"} <= set(args), ("warnings must be errors and references checked, on every "
                                            "page (-E: no page kept from an earlier build hides one)")
    out = subprocess.run([sys.executable, "-m", "sphinx", *args], cwd=ROOT, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-5000:]
    html = ROOT / args[-1]
    api = (html / "api.html").read_text()
    internals = (html / "internals.html").read_text()
    for name in ("coathertz.case.ContactCase", "coathertz.methods.Method", "coathertz.fft.method.FFTMethod",
                 "coathertz.axisym.method.AxisymMethod", "coathertz.fem.method.FEMMethod"):
        assert f'id="{name}"' in api + (html / "contract.html").read_text(), name
    assert 'id="module-coathertz.fft.solver"' in internals
