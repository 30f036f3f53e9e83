"""Faults: workers die with their parent, a damaged store is reported and
recovered on request (never silently lost), and two runs never share one store."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from coathertz.cli import main
from coathertz.errors import StoreError
from coathertz.store import ResultStore, open_run_store

VERIF = str(Path(__file__).resolve().parents[1] / "verification")


def _alive(pid: int) -> bool:
    """Running (zombies, which hold nothing, count as dead)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().split(")")[-1].split()[0] != "Z"
    except FileNotFoundError:
        return False
    except OSError:  # pragma: no cover - no /proc: fall back to kill(0)
        try:
            os.kill(pid, 0)
            return True
        except ProcessLookupError:
            return False


def _wait_for(cond, timeout: float, step: float = 0.05) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if cond():
            return True
        time.sleep(step)
    return cond()


POOL = """
import sys
sys.path.insert(0, {verif!r})
import coathertz.runner as runner
if {no_prctl}:
    runner._set_parent_death_signal = lambda: False  # exercise the watchdog fallback
from fake_method import FakeMethod, cases
from coathertz.store import ResultStore
m = FakeMethod(delay=60.0, log={log!r})
runner.run_tasks([runner.Task(c, m) for c in cases(4)], ResultStore(":memory:"), workers=2,
                 progress=False)
"""


@pytest.mark.skipif(sys.platform != "linux", reason="uses /proc to watch the worker processes")
@pytest.mark.parametrize("no_prctl", [False, True], ids=["prctl", "watchdog"])
def test_workers_die_with_a_killed_parent(tmp_path, no_prctl):
    log = tmp_path / "log"
    script = POOL.format(verif=VERIF, log=str(log), no_prctl=no_prctl)
    parent = subprocess.Popen([sys.executable, "-c", textwrap.dedent(script)])
    try:
        assert _wait_for(lambda: log.exists() and len(log.read_text().split("\n")) > 2, 30), \
            "workers did not start"
        workers = {int(line.split()[1]) for line in log.read_text().splitlines()}
        assert len(workers) == 2 and parent.pid not in workers
        parent.send_signal(signal.SIGKILL)
        parent.wait(10)
        gone = _wait_for(lambda: not any(_alive(p) for p in workers), 5)
        assert gone, f"workers still alive 5 s after SIGKILL of their parent: {workers}"
    finally:
        parent.kill()
        for p in workers if "workers" in locals() else ():
            if _alive(p):
                os.kill(p, signal.SIGKILL)


def _filled_store(path: Path, n: int = 200) -> None:
    from fake_method import cases

    with ResultStore(path) as store:
        for c in cases(n):
            store.put(c, "fake", {"k": 1}, {"a": 1.0, "pad": "x" * 400})


def _truncate(path: Path) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _garbage(path: Path) -> None:
    path.write_bytes(b"\x00garbage" * 4000)


@pytest.mark.parametrize("damage", [_truncate, _garbage], ids=["truncated", "garbage"])
def test_damaged_store_error_and_recovery(tmp_path, damage):
    sys.path.insert(0, VERIF)
    path = tmp_path / "store.sqlite"
    _filled_store(path)
    damage(path)
    damaged = path.read_bytes()
    with pytest.raises(StoreError, match=r"store\.sqlite is damaged .*--recover-store") as info:
        open_run_store(path)
    assert str(path) in str(info.value)
    assert path.read_bytes() == damaged, "a failed open changed the damaged file"
    notes = []
    with open_run_store(path, recover=True, note=notes.append) as store:
        assert store.count() == 0
    kept = list(tmp_path.glob("store.sqlite.damaged-*"))
    assert [p.read_bytes() for p in kept if not p.name.endswith(("-wal", "-shm"))] == [damaged]
    assert "moved it aside" in notes[0] and kept[0].name in notes[0]
    with pytest.raises(sqlite3.DatabaseError):  # really damaged, not a false alarm
        db = sqlite3.connect(kept[0])
        db.execute("PRAGMA quick_check").fetchall()
        db.execute("SELECT * FROM results").fetchall()


def test_verify_recover_store_end_to_end(tmp_path, capsys):
    out = tmp_path / "v"
    out.mkdir()
    _garbage(out / "store.sqlite")
    argv = ["verify", "--tiny", "--study", "fig3", "--method", "closed-form", "--no-progress",
            "--out", str(out)]
    assert main(argv) == 2
    assert "--recover-store" in capsys.readouterr().err
    assert main([*argv, "--recover-store"]) == 0
    err = capsys.readouterr().err
    assert "moved it aside" in err
    assert len(list(out.glob("store.sqlite.damaged-*"))) == 1
    with ResultStore(out / "store.sqlite") as store:
        assert store.count() > 0


HOLDER = """
import sys, time
from coathertz.store import open_run_store
store = open_run_store({path!r})
print("locked", flush=True)
time.sleep(60)
"""


def test_second_run_on_one_store_is_refused_and_a_dead_holder_is_taken_over(tmp_path, capsys):
    path = tmp_path / "store.sqlite"
    holder = subprocess.Popen([sys.executable, "-c", HOLDER.format(path=str(path))],
                              stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        with pytest.raises(StoreError, match=rf"another coathertz run \(pid {holder.pid}, started"):
            open_run_store(path)
        rc = main(["verify", "--tiny", "--study", "fig3", "--method", "closed-form", "--no-progress",
                   "--out", str(tmp_path)])
        assert rc == 2
        assert f"pid {holder.pid}" in capsys.readouterr().err
        holder.send_signal(signal.SIGKILL)  # dies holding the lock: the lock file stays
        holder.wait(10)
        assert (tmp_path / "store.sqlite.lock").read_text().startswith(str(holder.pid))
        with open_run_store(path) as store:  # stale lock taken over
            assert store.count() == 0
            assert (tmp_path / "store.sqlite.lock").read_text().startswith(str(os.getpid()))
    finally:
        holder.kill()
