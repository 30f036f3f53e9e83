"""The result store: keys, round trip, errors, export."""

from __future__ import annotations

import csv
import json
import math

from fake_method import FakeMethod, cases

from coathertz.materials import Material
from coathertz.store import ResultStore, case_key, code_version, settings_key


def test_case_key_ignores_labels_and_separates_physics():
    c = cases(2)
    assert case_key(c[0]) == case_key(c[0].replace(label="other"))
    assert case_key(c[0]) != case_key(c[1])
    assert case_key(c[0]) != case_key(c[0].with_thickness(2e-6))


def test_settings_key_and_code_version():
    assert settings_key({"a": 1, "b": 2}) == settings_key({"b": 2, "a": 1})
    assert settings_key({"n": 64}) != settings_key({"n": 128})
    v = code_version()
    assert v.startswith("0.") or "+" in v


def test_memoised_keys_are_the_hashes_they_stand_for():
    """The case key is kept on the case and the settings key memoised by the exact text of each
    value: the same hashes as computed afresh, and 1, 1.0, True, -0.0, 0.0 stay apart."""
    import pickle

    from coathertz.store import _hash, case_dict

    c = cases(2)[1]
    first = case_key(c)
    assert case_key(c) == first == _hash(case_dict(c))
    assert case_key(pickle.loads(pickle.dumps(c))) == first  # a worker's copy: the same key
    assert case_key(c.replace(W=2 * c.W)) == _hash(case_dict(c.replace(W=2 * c.W))) != first
    values = [1, 1.0, True, -0.0, 0.0, None, "1", math.inf]
    keys = [settings_key({"x": v, "n": 64}) for v in values for _ in range(2)]
    assert keys == [_hash({"x": v, "n": 64}) for v in values for _ in range(2)]
    assert len(set(keys)) == len(values)
    assert settings_key({"x": [1, 2]}) == _hash({"x": [1, 2]})  # not memoised, the same hash


def test_round_trip_error_and_version(tmp_path):
    m = FakeMethod()
    c = cases(3)
    with ResultStore(tmp_path / "s.sqlite", version="v1") as st:
        r = m.solve(c[0]).scalars()
        st.put(c[0], m.name, m.settings(), r)
        st.put(c[1], m.name, m.settings(), None, "ConvergenceError: no")
        got = st.get(c[0], m.name, m.settings())
        assert got.ok and math.isclose(got.result["a"], r["a"]) and got.case["W"] == 1.0
        bad = st.get(c[1], m.name, m.settings())
        assert not bad.ok and "ConvergenceError" in bad.error
        assert st.get(c[2], m.name, m.settings()) is None
        assert st.get(c[0], m.name, {"other": 1}) is None
        assert set(st.get_many(c, m.name, m.settings())) == {case_key(c[0]), case_key(c[1])}
        st.export_csv(tmp_path / "s.csv")
        st.export_json(tmp_path / "s.json")
    with ResultStore(tmp_path / "s.sqlite", version="v2") as st:  # new code version: nothing reused
        assert st.get(c[0], m.name, m.settings()) is None
        assert st.count() == 2  # but the old rows are kept
    rows = list(csv.DictReader((tmp_path / "s.csv").open()))
    assert [r["status"] for r in rows] == ["ok", "error"]
    data = json.loads((tmp_path / "s.json").read_text())
    assert data[0]["result"]["p0"] > 0 and data[1]["result"] is None


def test_rigid_and_infinite_values_serialise(tmp_path):
    from coathertz.verification import rigid_substrate_case

    c = rigid_substrate_case(200e9, 0.5)
    with ResultStore(tmp_path / "s.sqlite", version="v") as st:
        st.put(c, "x", {}, {"a": 1.0, "r": math.inf})
        got = st.get(c, "x", {})
    assert got.case["body2"]["material"]["E"] == math.inf and got.result["r"] == math.inf
    assert Material(1e9, 0.3).E_star > 0


def test_editing_one_method_leaves_the_others_results_valid(tmp_path, monkeypatch):
    """Results are keyed by their own method's code version (its source packages plus the shared
    case model and validity rule): an edit to ``fem/`` invalidates the FE's stored results and
    keeps the FFT's and the exact method's; an edit to the shared case model invalidates all."""
    from pathlib import Path

    import coathertz.store as st

    path = tmp_path / "store.sqlite"
    c = cases(1)[0]
    with ResultStore(path) as s:
        for m in ("fft", "axisym", "fem"):
            s.put(c, m, {"n": 1}, {"delta": 1.0})
    before = {m: code_version(m) for m in ("fft", "axisym", "fem")}
    assert len(set(before.values())) == 3 and all(f"+{m}-" in v for m, v in before.items())

    def edited(part: str):
        real = Path.read_bytes

        def read_bytes(self):
            data = real(self)
            return data + b"\n# edited\n" if part in self.as_posix() else data

        return read_bytes

    for part, stale in (("/fem/", {"fem"}), ("/coathertz/case.py", {"fft", "axisym", "fem"})):
        monkeypatch.setattr(Path, "read_bytes", edited(part))
        st.code_version.cache_clear()
        after = {m: code_version(m) for m in before}
        assert {m for m in before if after[m] != before[m]} == stale, (part, before, after)
        with ResultStore(path) as s:
            found = {m for m in before if s.get(c, m, {"n": 1}) is not None}
        assert found == set(before) - stale, (part, found)
        monkeypatch.undo()
        st.code_version.cache_clear()
