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
    # interface stresses (exact method): the checks hold at round-off / the radial rule
    val = {c.id: c for c in r.claims}
    for cid, bound in (("multilayer-bonded-tractions-continuous", 1e-12),
                       ("multilayer-frictionless-shear-free", 1e-12),
                       ("multilayer-interface-equilibrium", 1e-4)):
        assert val[cid].verdict == "holds" and val[cid].value < bound, val[cid]
    rows = r.extra["interface_stresses"]
    assert len(rows) == 5  # TiN/steel, and two interfaces for each of the two interlayers
    # an interlayer of steel leaves the TiN/steel interface as it is (the kernel identity), and
    # a soft interlayer unloads the TiN's interface (measured 0.1884 -> 0.1381 p0)
    top = {(x["case"], x["interface"]): x for x in rows}
    alone, same, soft = top["coating-only", 1], top["Ei=1,hi=1um", 1], top["Ei=0.25,hi=1um", 1]
    assert abs(same["tau_max"] - alone["tau_max"]) < 1e-9 and abs(same["r_tau"] - alone["r_tau"]) < 1e-9
    assert 0.18 < alone["tau_max"] < 0.20 and 0.13 < soft["tau_max"] < 0.15, (alone, soft)
    assert val["multilayer-interface-stresses"].verdict == "observed"
    paths = mod.plot(r, tmp_path)
    assert [p.name for p in paths] == ["multilayer.png", "multilayer_interfaces.png"]
    assert all(p.stat().st_size > 5000 for p in paths)


def test_interface_stresses_forked_give_the_same_numbers():
    """With two workers each case's interface stresses (and the frictionless check) are computed
    in forked processes: every number is the one computed in this process."""
    import json

    from coathertz.jsonsafe import to_jsonable
    from coathertz.verification import StudyResult

    mod = get_study("multilayer")
    out = []
    for workers in (1, 2):
        r = StudyResult(mod.NAME, mod.TITLE, mod.CLAIM, "tiny", workers=workers)
        r.rows = [{"case": sc.id, "method": "axisym"} for sc in mod.cases("tiny")]
        mod.analyse_interfaces(r)
        assert not r.failures and r.extra["interface_stresses"], r.failures
        extra = {k: v for k, v in r.extra.items() if k != "interface_cpu_s"}
        out.append(json.dumps(to_jsonable([r.to_json()["claims"], extra]), sort_keys=True))
    assert out[0] == out[1]
    assert "multilayer-interface-equilibrium" in out[0]
