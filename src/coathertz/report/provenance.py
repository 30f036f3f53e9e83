"""Provenance of a verification run: package version, git commit, date, machine."""

from __future__ import annotations

import datetime as _dt
import os
import platform
import subprocess
from pathlib import Path
from typing import Any


def _git(args: list[str], cwd: Path) -> str:
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10, check=True)
    except (OSError, subprocess.SubprocessError):
        return ""
    return out.stdout.strip()


def git_info(path: str | Path | None = None) -> dict[str, Any]:
    """Commit and dirty flag of the source tree (read-only git queries; empty if no git). Changes
    under ``reports/`` (generated output, e.g. a published report being regenerated) are not dirt."""
    import coathertz

    cwd = Path(path) if path else Path(coathertz.__file__).resolve().parent
    commit = _git(["rev-parse", "HEAD"], cwd)
    if not commit:
        return {"commit": "unknown", "dirty": None}
    # dirty = the source differs from the commit; generated reports (reports/) are output, not source
    status = _git(["status", "--porcelain", "--untracked-files=no", "--", ":(top)",
                   ":(top,exclude)reports"], cwd)
    return {"commit": commit, "short": commit[:10], "dirty": bool(status)}


def collect(resolution: str, extra: dict | None = None) -> dict[str, Any]:
    """Everything the report prints about how and where it was made."""
    import matplotlib
    import numpy
    import scipy

    import coathertz
    from coathertz.store import code_version

    info = {
        "package": "coathertz",
        "version": coathertz.__version__,
        "code_version": code_version(),
        **{f"git_{k}": v for k, v in git_info().items()},
        "date": _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M:%S UTC"),
        "resolution": resolution,
        "machine": f"{platform.node()} ({platform.machine()}, {os.cpu_count()} CPUs, {platform.system()} "
                   f"{platform.release()})",
        "processor": platform.processor() or platform.machine(),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "matplotlib": matplotlib.__version__,
    }
    info.update(extra or {})
    return info
