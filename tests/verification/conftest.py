"""Shared helpers for the verification tests: the fake method on sys.path, a tiny-run fixture."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))


def pytest_configure(config):
    config.addinivalue_line("markers", "browser: needs a headless Chromium (skipped, with the reason, "
                            "without one)")


@pytest.fixture(scope="session")
def tiny_methods():
    """Closed form and a coarse FFT (n = 32): what the tiny studies run in the tests."""
    from coathertz.verification import build_methods

    methods, notes = build_methods("tiny", ["closed-form", "fft"])
    assert not notes, notes
    return methods


@pytest.fixture(scope="session")
def tiny_results(tiny_methods, tmp_path_factory):
    """Every study run once at the tiny resolution (shared store), keyed by study name."""
    from coathertz.store import ResultStore
    from coathertz.verification import run_study, studies

    store = ResultStore(tmp_path_factory.mktemp("store") / "store.sqlite")
    out = {name: run_study(mod, "tiny", tiny_methods, store, {"workers": 1, "progress": False})
           for name, mod in studies().items()}
    store.close()
    return out
