"""Embedded result store: every finished (case, method) result, keyed so that runs resume.

A result is stored under the key ``(case_key, method, settings_key, code_version)``:

case_key
    SHA-256 of a canonical JSON form of the :class:`~coathertz.case.ContactCase` (materials,
    coatings, radii, load, angle; labels and names excluded), see :func:`case_key`.
method, settings_key
    The method's name and a hash of its ``settings()`` (the knobs that change its numbers).
code_version
    Package version plus a hash of the numerical source files (:func:`code_version`), so a
    change to any solver or to the case model invalidates earlier results, while a change to
    the report, the CLI or the studies does not.

Results are written (and committed) one by one as they arrive, so an interrupted run loses
nothing that finished; a rerun with the same key reuses them. SQLite from the standard
library, WAL journal, one writer (the process that runs the study). Failed cases are stored
too (``status = 'error'`` with the message) so that a rerun does not retry a case that cannot
converge, unless asked to (``retry_errors``).

Integrity and exclusivity (:func:`open_run_store`, used by ``coathertz verify``):

* a damaged file (truncated, overwritten) raises :class:`~coathertz.errors.StoreError` naming
  the file; with ``recover=True`` (``--recover-store``) the damaged file is moved aside to
  ``store.sqlite.damaged-<UTC timestamp>`` (kept, never deleted) and a new store is started;
* one run at a time per store: an exclusive lock (``store.sqlite.lock``, holding the pid) makes a
  second run on the same store stop with a clear message; a lock left by a dead process is
  taken over (the operating system releases ``flock`` locks when their holder dies).
"""

from __future__ import annotations

import contextlib
import csv
import datetime
import hashlib
import json
import math
import os
import sqlite3
import time
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from coathertz.case import ContactCase
from coathertz.errors import StoreError
from coathertz.jsonsafe import dumps as _json_dumps
from coathertz.jsonsafe import loads as _loads
from coathertz.materials import Body, Material

SCHEMA = """
CREATE TABLE IF NOT EXISTS results (
    case_key TEXT NOT NULL,
    method TEXT NOT NULL,
    settings_key TEXT NOT NULL,
    code_version TEXT NOT NULL,
    status TEXT NOT NULL,
    case_json TEXT NOT NULL,
    settings_json TEXT NOT NULL,
    result_json TEXT,
    error TEXT,
    created REAL NOT NULL,
    PRIMARY KEY (case_key, method, settings_key, code_version)
)
"""

def _num(x: float) -> Any:
    x = float(x)
    return x if math.isfinite(x) else str(x)  # as to_jsonable writes it


def _material_dict(m: Material) -> dict:
    d = {"E": _num(m.E), "nu": _num(m.nu)}
    if getattr(m, "plasticity", None) is not None:  # J2 yield data keys the case too
        d["plasticity"] = m.plasticity.key()
    return d


def _body_dict(b: Body) -> dict:
    d: dict[str, Any] = {"material": _material_dict(b.material), "Rx": _num(b.Rx), "Ry": _num(b.Ry)}
    if b.coating is not None:
        d["coating"] = {**_material_dict(b.coating.material), "h": _num(b.coating.h)}
        if b.coating.interface != "bonded":  # the default leaves the keys of bonded cases as they were
            d["coating"]["interface"] = b.coating.interface
    if b.layers:  # only then: the keys of other cases are unchanged
        d["layers"] = [{**_material_dict(L.material), "h": _num(L.h), "interface": L.interface}
                       for L in b.layers]
    return d


def case_dict(case: ContactCase) -> dict:
    """Canonical, JSON-ready description of a case (labels and names left out)."""
    return {"body1": _body_dict(case.body1), "body2": _body_dict(case.body2),
            "W": _num(case.W), "theta": _num(case.theta)}


def _hash(obj: Any) -> str:
    text = json.dumps(obj, sort_keys=True, separators=(",", ":"), default=str)  # keys: keep as is
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def case_key(case: ContactCase) -> str:
    """Hash of :func:`case_dict`: equal for cases that are physically the same.

    Kept on the case (a frozen dataclass; like its cached properties): a run asks for the key of
    each case a dozen times."""
    return _kept(case, "_store_case_key", lambda: _hash(case_dict(case)))


def _case_json(case: ContactCase) -> str:
    """The stored JSON text of :func:`case_dict` (kept on the case like its key)."""
    return _kept(case, "_store_case_json", lambda: _dumps(case_dict(case)))


def _kept(case: ContactCase, name: str, make) -> str:
    """``make()``, kept in the case's ``__dict__`` under ``name`` (where it has one)."""
    try:
        return case.__dict__[name]
    except (KeyError, AttributeError):
        pass
    value = make()
    with contextlib.suppress(AttributeError, TypeError):
        case.__dict__[name] = value
    return value


def settings_key(settings: Mapping[str, Any]) -> str:
    """Hash of a method's settings."""
    d = dict(settings)
    if not _ATOMS.issuperset(map(type, d.values())):
        return _hash(d)
    memo = (*d, *map(repr, d.values()))  # the exact text of each value: 1, 1.0, True, -0.0 apart
    key = _SETTINGS_KEYS.get(memo)
    if key is None:
        if len(_SETTINGS_KEYS) > 4096:
            _SETTINGS_KEYS.clear()
        key = _SETTINGS_KEYS[memo] = _hash(d)
    return key


_ATOMS = frozenset({str, int, float, bool, type(None)})
_SETTINGS_KEYS: dict[tuple[str, ...], str] = {}


def _source_files(module: str) -> list[tuple[str, Path]]:
    """(name, path) of the ``*.py`` files of a module or package (empty if it cannot be found)."""
    import importlib.util

    try:
        spec = importlib.util.find_spec(module)
    except (ImportError, ValueError):
        return []
    if spec is None:
        return []
    if spec.submodule_search_locations:
        out = []
        for loc in spec.submodule_search_locations:
            root = Path(loc)
            out += [(f"{module}/{p.relative_to(root).as_posix()}", p) for p in sorted(root.rglob("*.py"))
                    if "__pycache__" not in p.parts]
        return out
    return [(module, Path(spec.origin))] if spec.origin and spec.origin.endswith(".py") else []


@lru_cache(maxsize=64)
def code_version(method: str | None = None) -> str:
    """``<package version>+<hash of the numerical sources>``: the version key of stored numbers.

    With ``method`` (a registered name, or a study's variant such as ``fft-frictionless``), the
    hash covers the shared case model and validity rule (:data:`~coathertz.methods.SHARED_SOURCES`)
    and that method's own ``source_packages``: editing one method's source invalidates its
    stored results only, not the other methods'. Without, it covers every registered method
    (the provenance of a whole report). A change to the report, the CLI, the studies, this store
    or the runner changes neither. A method without ``source_packages`` is keyed by all sources.
    """
    import coathertz
    from coathertz.methods import SHARED_SOURCES, method_info, numerical_sources

    if method is None:
        modules, tag = numerical_sources(), ""
    else:
        try:
            pkgs = method_info(method).source_packages
        except Exception:  # a broken plug-in: keyed by everything
            pkgs = ()
        modules = [*SHARED_SOURCES, *pkgs] if pkgs else numerical_sources()
        tag = f"{method}-"
    h = hashlib.sha256()
    seen: set[Path] = set()
    for module in modules:
        for name, path in _source_files(module):
            if path in seen:
                continue
            seen.add(path)
            h.update(name.encode())
            h.update(path.read_bytes())
    return f"{coathertz.__version__}+{tag}{h.hexdigest()[:12]}"


@dataclass(frozen=True)
class StoredResult:
    """One row of the store."""

    case_key: str
    method: str
    settings_key: str
    code_version: str
    status: str  # "ok" or "error"
    case: dict
    settings: dict
    result: dict | None
    error: str | None
    created: float

    @property
    def ok(self) -> bool:
        return self.status == "ok"


def _dumps(obj: Any) -> str:
    return _json_dumps(obj, sort_keys=True)


def _prepare_folder(path: Path) -> None:
    """Refuse a folder given as the store file; create the store's parent folder."""
    if path.is_dir():
        raise StoreError(f"result store {path} is a directory, not a store file")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise StoreError(f"cannot create the folder of the result store {path}: "
                         f"{exc.strerror or exc}") from exc


class ResultStore:
    """SQLite store of method results (see the module docstring).

    Parameters
    ----------
    path
        Database file (created with its parent folder); ``":memory:"`` for a throw-away store.
    version
        Code version used in the keys of every method (tests); default: each method's own
        :func:`code_version`, so that a change to one method's source leaves the others'
        results valid.
    """

    def __init__(self, path: str | Path = ":memory:", version: str | None = None) -> None:
        self.path = str(path)
        self._lock: _StoreLock | None = None
        if self.path != ":memory:":
            _prepare_folder(Path(self.path))
        self.version = version
        try:
            self._db = sqlite3.connect(self.path, timeout=30.0)
        except sqlite3.Error as exc:
            raise StoreError(f"cannot open the result store {self.path}: {exc}") from exc
        try:
            if self.path != ":memory:":
                _check_integrity(self._db, self.path)  # before anything writes to the file
                self._db.execute("PRAGMA journal_mode=WAL")
                # a commit reaches the file without waiting for the disk (no fsync per result):
                # a killed or interrupted run keeps every result it stored; only a power cut
                # could lose the last few, which a rerun computes again
                self._db.execute("PRAGMA synchronous=NORMAL")
            self._db.execute(SCHEMA)
            self._db.commit()
        except sqlite3.Error as exc:
            self._db.close()
            raise _store_error(self.path, exc) from exc

    # -- context manager ---------------------------------------------------------------
    def close(self) -> None:
        self._db.close()
        if self._lock is not None:
            self._lock.release()
            self._lock = None

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- access ------------------------------------------------------------------------
    def version_of(self, method: str) -> str:
        """The code version that keys ``method``'s results (see :func:`code_version`)."""
        return self.version or code_version(method)

    def key(self, case: ContactCase, method: str, settings: Mapping[str, Any]) -> tuple[str, str, str, str]:
        return case_key(case), method, settings_key(settings), self.version_of(method)

    def get(self, case: ContactCase, method: str, settings: Mapping[str, Any]) -> StoredResult | None:
        """The stored result of ``case`` by ``method`` with ``settings`` at this code version."""
        row = self._query(
            "SELECT * FROM results WHERE case_key=? AND method=? AND settings_key=? AND code_version=?",
            self.key(case, method, settings),
        )[:1]
        row = row[0] if row else None
        return None if row is None else self._row(row)

    def get_many(
        self, cases: Iterable[ContactCase], method: str, settings: Mapping[str, Any]
    ) -> dict[str, StoredResult]:
        """Stored results of several cases, keyed by case key (missing cases left out)."""
        skey = settings_key(settings)
        keys = list({case_key(c) for c in cases})
        out: dict[str, StoredResult] = {}
        for s in range(0, len(keys), 500):
            chunk = keys[s : s + 500]
            q = ",".join("?" * len(chunk))
            rows = self._query(
                f"SELECT * FROM results WHERE method=? AND settings_key=? AND code_version=? "
                f"AND case_key IN ({q})",
                (method, skey, self.version_of(method), *chunk),
            )
            for r in rows:
                sr = self._row(r)
                out[sr.case_key] = sr
        return out

    def put(
        self,
        case: ContactCase,
        method: str,
        settings: Mapping[str, Any],
        result: Mapping[str, Any] | None,
        error: str | None = None,
    ) -> None:
        """Store (and commit) one result, or the error of a failed case."""
        ck, m, sk, v = self.key(case, method, settings)
        try:
            self._db.execute(
                "INSERT OR REPLACE INTO results VALUES (?,?,?,?,?,?,?,?,?,?)",
                (ck, m, sk, v, "ok" if error is None else "error", _case_json(case),
                 _dumps(dict(settings)), None if result is None else _dumps(dict(result)), error,
                 time.time()),
            )
            self._db.commit()
        except sqlite3.Error as exc:
            raise _store_error(self.path, exc) from exc

    def count(self, method: str | None = None, status: str | None = None) -> int:
        q, args = "SELECT COUNT(*) FROM results WHERE 1=1", []
        if method is not None:
            q += " AND method=?"
            args.append(method)
        if status is not None:
            q += " AND status=?"
            args.append(status)
        return int(self._query(q, args)[0][0])

    def rows(self, method: str | None = None) -> Iterator[StoredResult]:
        q = "SELECT * FROM results" + (" WHERE method=?" if method else "") + " ORDER BY created"
        for r in self._query(q, (method,) if method else ()):
            yield self._row(r)

    def _query(self, sql: str, args: Iterable[Any] = ()) -> list[tuple]:
        """Rows of a read query; a damaged file raises :class:`~coathertz.errors.StoreError` naming it."""
        try:
            return self._db.execute(sql, tuple(args)).fetchall()
        except sqlite3.Error as exc:
            raise _store_error(self.path, exc) from exc

    @staticmethod
    def _row(r: tuple) -> StoredResult:
        return StoredResult(r[0], r[1], r[2], r[3], r[4], _loads(r[5]), _loads(r[6]), _loads(r[7]),
                            r[8], r[9])

    # -- export ------------------------------------------------------------------------
    def export_json(self, path: str | Path) -> Path:
        """All rows as a JSON list (inf/nan written as strings)."""
        path = Path(path)
        rows = [
            {"case_key": r.case_key, "method": r.method, "settings_key": r.settings_key,
             "code_version": r.code_version, "status": r.status, "case": r.case,
             "settings": r.settings, "result": r.result, "error": r.error, "created": r.created}
            for r in self.rows()
        ]
        path.write_text(_dumps(rows))
        return path

    def export_csv(self, path: str | Path) -> Path:
        """One line per row: keys, status and the scalar results (delta, a, p0, r_a, r_b, W)."""
        path = Path(path)
        cols = ["case_key", "method", "settings_key", "code_version", "status",
                "delta", "a", "p0", "r_a", "r_b", "W", "error", "case"]
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(cols)
            for r in self.rows():
                res = r.result or {}
                w.writerow([r.case_key, r.method, r.settings_key, r.code_version, r.status,
                            *(res.get(k, "") for k in ("delta", "a", "p0", "r_a", "r_b", "W")),
                            r.error or "", _dumps(r.case)])
        return path


# -- integrity, recovery and the one-run-at-a-time lock --------------------------------------
RECOVER_HINT = "--recover-store"


def _check_integrity(db: sqlite3.Connection, path: str) -> None:
    """Raise ``sqlite3.DatabaseError`` if SQLite finds the file damaged (``quick_check``)."""
    rows = db.execute("PRAGMA quick_check").fetchall()
    if rows != [("ok",)]:
        raise sqlite3.DatabaseError("; ".join(str(r[0]) for r in rows[:3]))


def _store_error(path: str, exc: sqlite3.Error) -> StoreError:
    text = str(exc)
    if isinstance(exc, sqlite3.OperationalError) and "full" in text:  # SQLITE_FULL
        return StoreError(f"cannot write the result store {path}: the disk is full ({text}); the "
                          "results stored so far are kept; free some space or give another --store")
    if isinstance(exc, sqlite3.OperationalError) and ("readonly" in text or "unable to open" in text
                                                       or "disk I/O" in text):
        return StoreError(f"cannot write the result store {path} ({text}); choose a writable "
                          "folder with --out or --store")
    return StoreError(
        f"the result store {path} is damaged ({text}); nothing was changed. Run the same command "
        f"with {RECOVER_HINT} to move it aside to {path}.damaged-<timestamp> (kept) and recompute, "
        "or give another --store"
    )


def move_aside(path: str | Path) -> Path:
    """Rename a damaged store (and its ``-wal``/``-shm`` files) to ``PATH.damaged-<UTC time>``."""
    path = Path(path)
    stamp = datetime.datetime.now(datetime.UTC).strftime("%Y%m%dT%H%M%SZ")
    target = path.with_name(f"{path.name}.damaged-{stamp}")
    n = 1
    while target.exists():
        target = path.with_name(f"{path.name}.damaged-{stamp}-{n}")
        n += 1
    path.rename(target)
    for suffix in ("-wal", "-shm"):
        side = path.with_name(path.name + suffix)
        if side.exists():
            side.rename(target.with_name(target.name + suffix))
    return target


#: Lock file descriptors held by this process; worker processes close their inherited copies
#: (``coathertz.runner``), so that only the run itself holds the lock.
HELD_LOCK_FDS: set[int] = set()


class _StoreLock:
    """Exclusive, pid-stamped lock file ``<store>.lock`` (see :func:`open_run_store`)."""

    def __init__(self, store_path: str | Path) -> None:
        self.path = Path(f"{store_path}.lock")
        self.fd: int | None = None

    def acquire(self) -> None:
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise StoreError(f"cannot create the lock file {self.path}: {exc.strerror or exc}") from exc
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not Linux/macOS: pid check only
            fcntl = None
        if fcntl is not None:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                holder = self._holder(fd)
                os.close(fd)
                raise StoreError(self._busy(holder)) from None
        else:  # pragma: no cover
            holder = self._holder(fd)
            if holder and holder[0] != os.getpid() and _pid_alive(holder[0]):
                os.close(fd)
                raise StoreError(self._busy(holder))
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()} {time.time():.0f}\n".encode())
        self.fd = fd
        HELD_LOCK_FDS.add(fd)

    def _busy(self, holder: tuple[int, float] | None) -> str:
        who = "another coathertz run"
        if holder:
            started = datetime.datetime.fromtimestamp(holder[1], datetime.UTC).strftime("%H:%M:%S UTC")
            who += f" (pid {holder[0]}, started {started})"
        store = str(self.path)[: -len(".lock")]
        return (f"{who} is using the result store {store}; wait for it to finish, or give this run "
                "another --out (or --store). Two runs on one store would solve the same cases twice")

    @staticmethod
    def _holder(fd: int) -> tuple[int, float] | None:
        try:
            os.lseek(fd, 0, os.SEEK_SET)
            pid, started = os.read(fd, 100).decode().split()[:2]
            return int(pid), float(started)
        except (OSError, ValueError):
            return None

    def release(self) -> None:
        if self.fd is None:
            return
        HELD_LOCK_FDS.discard(self.fd)
        try:
            os.ftruncate(self.fd, 0)
        finally:
            os.close(self.fd)  # releases the flock
            self.fd = None


def _pid_alive(pid: int) -> bool:  # pragma: no cover - fallback without fcntl
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _empty_store(path: Path, note) -> None:
    """A store file of 0 bytes (truncated, or a run killed as it created the file): SQLite would
    take it silently for a new store. Say so: whatever it held is gone."""
    msg = (f"the result store {path} is empty (0 bytes): any results it held are gone (truncated "
           "file?); starting a new store there")
    if note is not None:
        note(msg)
    else:
        import warnings

        warnings.warn(msg, stacklevel=3)


def open_run_store(path: str | Path, *, recover: bool = False, version: str | None = None,
                   note=None) -> ResultStore:
    """Open the store of a run: exclusive (one run per store), integrity-checked.

    Parameters
    ----------
    path
        Store file.
    recover
        If the file is damaged, move it aside (:func:`move_aside`, the file is kept) and start a
        new store; otherwise a damaged file raises :class:`~coathertz.errors.StoreError`.
    note
        Callable receiving a one-line message when a damaged store was moved aside.
    """
    if str(path) == ":memory:":
        return ResultStore(path, version)
    path = Path(path)
    _prepare_folder(path)
    lock = _StoreLock(path)
    lock.acquire()
    try:
        if path.is_file() and path.stat().st_size == 0:
            _empty_store(path, note)
        try:
            store = ResultStore(path, version)
        except StoreError as exc:
            if not recover or not path.exists() or "damaged" not in str(exc):
                raise
            moved = move_aside(path)
            if note is not None:
                note(f"the result store {path} was damaged ({exc.__cause__}); moved it aside to "
                     f"{moved} (kept) and started a new store")
            store = ResultStore(path, version)
    except BaseException:
        lock.release()
        raise
    store._lock = lock
    return store
