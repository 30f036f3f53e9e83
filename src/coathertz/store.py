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
"""

from __future__ import annotations

import csv
import hashlib
import json
import math
import sqlite3
import time
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from coathertz.case import ContactCase
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

#: Source files (relative to the package roots) that do NOT change any method's numbers.
_NOT_NUMERICAL = ("report", "cli", "store.py", "runner.py", "__pycache__")


def _num(x: float) -> Any:
    x = float(x)
    return x if math.isfinite(x) else str(x)


def _material_dict(m: Material) -> dict:
    d = {"E": _num(m.E), "nu": _num(m.nu)}
    if getattr(m, "plasticity", None) is not None:  # J2 yield data (issue 11) keys the case too
        d["plasticity"] = m.plasticity.key()
    return d


def _body_dict(b: Body) -> dict:
    d: dict[str, Any] = {"material": _material_dict(b.material), "Rx": _num(b.Rx), "Ry": _num(b.Ry)}
    if b.coating is not None:
        d["coating"] = {**_material_dict(b.coating.material), "h": _num(b.coating.h)}
    return d


def case_dict(case: ContactCase) -> dict:
    """Canonical, JSON-ready description of a case (labels and names left out)."""
    return {"body1": _body_dict(case.body1), "body2": _body_dict(case.body2),
            "W": _num(case.W), "theta": _num(case.theta)}


def _hash(obj: Any) -> str:
    text = json.dumps(obj, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def case_key(case: ContactCase) -> str:
    """Hash of :func:`case_dict`: equal for cases that are physically the same."""
    return _hash(case_dict(case))


def settings_key(settings: Mapping[str, Any]) -> str:
    """Hash of a method's settings."""
    return _hash(dict(settings))


@lru_cache(maxsize=1)
def code_version() -> str:
    """``<package version>+<hash of the numerical sources>``.

    The hash covers every ``*.py`` file of ``coathertz`` and ``coathertz.fem`` except the
    report, the CLI, this store and the runner (they do not change a method's numbers).
    """
    import coathertz

    roots = [Path(coathertz.__file__).parent]
    try:
        import coathertz.fem as fem

        roots.append(Path(fem.__file__).parent)
    except ImportError:  # pragma: no cover
        pass
    h = hashlib.sha256()
    for root in roots:
        for path in sorted(root.rglob("*.py")):
            rel = path.relative_to(root)
            if rel.parts[0] in _NOT_NUMERICAL:
                continue
            h.update(str(rel).encode())
            h.update(path.read_bytes())
    return f"{coathertz.__version__}+{h.hexdigest()[:12]}"


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


def _loads(text: str | None) -> Any:
    if text is None:
        return None

    def fix(v: Any) -> Any:
        if isinstance(v, str) and v in ("inf", "-inf", "nan"):
            return float(v)
        if isinstance(v, dict):
            return {k: fix(x) for k, x in v.items()}
        if isinstance(v, list):
            return [fix(x) for x in v]
        return v

    return fix(json.loads(text))


def _dumps(obj: Any) -> str:
    def fix(v: Any) -> Any:
        if isinstance(v, float) and not math.isfinite(v):
            return str(v)
        if isinstance(v, dict):
            return {str(k): fix(x) for k, x in v.items()}
        if isinstance(v, list | tuple):
            return [fix(x) for x in v]
        if hasattr(v, "item") and callable(v.item):  # numpy scalars
            return fix(v.item())
        return v

    return json.dumps(fix(obj), sort_keys=True, default=str)


class ResultStore:
    """SQLite store of method results (see the module docstring).

    Parameters
    ----------
    path
        Database file (created with its parent folder); ``":memory:"`` for a throw-away store.
    version
        Code version used in the keys; default :func:`code_version`.
    """

    def __init__(self, path: str | Path = ":memory:", version: str | None = None) -> None:
        self.path = str(path)
        if self.path != ":memory:":
            Path(self.path).parent.mkdir(parents=True, exist_ok=True)
        self.version = version or code_version()
        self._db = sqlite3.connect(self.path, timeout=30.0)
        if self.path != ":memory:":
            self._db.execute("PRAGMA journal_mode=WAL")
        self._db.execute(SCHEMA)
        self._db.commit()

    # -- context manager ---------------------------------------------------------------
    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- access ------------------------------------------------------------------------
    def key(self, case: ContactCase, method: str, settings: Mapping[str, Any]) -> tuple[str, str, str, str]:
        return case_key(case), method, settings_key(settings), self.version

    def get(self, case: ContactCase, method: str, settings: Mapping[str, Any]) -> StoredResult | None:
        """The stored result of ``case`` by ``method`` with ``settings`` at this code version."""
        row = self._db.execute(
            "SELECT * FROM results WHERE case_key=? AND method=? AND settings_key=? AND code_version=?",
            self.key(case, method, settings),
        ).fetchone()
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
            rows = self._db.execute(
                f"SELECT * FROM results WHERE method=? AND settings_key=? AND code_version=? "
                f"AND case_key IN ({q})",
                (method, skey, self.version, *chunk),
            ).fetchall()
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
        self._db.execute(
            "INSERT OR REPLACE INTO results VALUES (?,?,?,?,?,?,?,?,?,?)",
            (ck, m, sk, v, "ok" if error is None else "error", _dumps(case_dict(case)),
             _dumps(dict(settings)), None if result is None else _dumps(dict(result)), error, time.time()),
        )
        self._db.commit()

    def count(self, method: str | None = None, status: str | None = None) -> int:
        q, args = "SELECT COUNT(*) FROM results WHERE 1=1", []
        if method is not None:
            q += " AND method=?"
            args.append(method)
        if status is not None:
            q += " AND status=?"
            args.append(status)
        return int(self._db.execute(q, args).fetchone()[0])

    def rows(self, method: str | None = None) -> Iterator[StoredResult]:
        q = "SELECT * FROM results" + (" WHERE method=?" if method else "") + " ORDER BY created"
        for r in self._db.execute(q, (method,) if method else ()):
            yield self._row(r)

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
