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
    for q in ("delta-p0", "a"):  # fft (tiny grid) vs axisym, percent: the claim is computed; at
        # tiny the FFT's coarse grid need not meet the quick report's bounds
        agree = next(c for c in r.claims if c.id == f"multilayer-methods-agree-{q}")
        assert 0 < agree.value < 0.5 and agree.verdict in ("holds", "does not hold"), agree
    paths = mod.plot(r, tmp_path)
    assert {p.suffix for p in paths} == {".png"} and all(p.stat().st_size > 5000 for p in paths)
