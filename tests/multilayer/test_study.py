"""The ``multilayer`` study at the tiny resolution (closed form and a coarse FFT, as the study
tests run): the identity claim holds, the figure is written."""

from __future__ import annotations

from coathertz.store import ResultStore
from coathertz.verification import build_methods, get_study, run_study


def test_tiny_multilayer_study(tmp_path):
    mod = get_study("multilayer")
    methods, notes = build_methods("tiny", ["closed-form", "fft", "axisym"])
    assert not notes, notes
    store = ResultStore(tmp_path / "s.sqlite")
    r = run_study(mod, "tiny", methods, store, {"workers": 1, "progress": False})
    store.close()
    assert not r.failures, r.failures
    assert {row["method"] for row in r.rows if row["case"] != "coating-only"} == {"fft", "axisym"}
    claim = next(c for c in r.claims if c.id == "multilayer-substrate-interlayer-adds-nothing")
    assert claim.verdict == "holds" and claim.value < 1e-6, claim
    agree = next(c for c in r.claims if c.id == "multilayer-methods-agree")
    assert agree.value < 0.5, agree  # fft (tiny grid) vs axisym, percent
    paths = mod.plot(r, tmp_path)
    assert {p.suffix for p in paths} == {".png"} and all(p.stat().st_size > 5000 for p in paths)
