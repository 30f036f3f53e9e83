"""the README main job writes only ignored files; the published report is tracked."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PUBLISHED = ROOT / "reports" / "published" / "quick"


def _git(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=False)


needs_git = pytest.mark.skipif(shutil.which("git") is None or not (ROOT / ".git").exists(),
                               reason="not a git checkout")


@needs_git
@pytest.mark.parametrize("path", ["reports/quick/index.html", "reports/quick/figures/fig3.png",
                                  "reports/quick/baseline.json", "reports/quick/store.sqlite",
                                  "reports/quick/rows/fig3.csv", "reports/full/index.html",
                                  "reports/published/quick/store.sqlite"])
def test_main_job_output_is_ignored(path):
    assert _git("check-ignore", "-q", path).returncode == 0, f"{path} is not ignored: a run would dirty git"


@needs_git
def test_published_report_is_tracked_and_not_the_main_jobs_folder():
    tracked = _git("ls-files", "reports").stdout.split()
    assert "reports/published/quick/baseline.json" in tracked
    assert "reports/published/quick/index.html" in tracked
    assert not [p for p in tracked if p.startswith("reports/quick/")], "the main job's folder is tracked"
    assert _git("check-ignore", "-q", "reports/published/quick/index.html").returncode == 1


def test_published_baseline_loads():
    from coathertz.report.baseline import load_baseline

    data = load_baseline(PUBLISHED / "baseline.json")
    assert data["provenance"]["resolution"] == "quick"
    raw = json.loads((PUBLISHED / "baseline.json").read_text())
    assert data["claims"] and raw["format"] == data["format"]
