"""The method registry drives the studies: one contract test over every registered
method, and a fifth method registered from the tests alone (no study, store or report edited)."""

from __future__ import annotations

import json
from importlib.metadata import EntryPoint

import pytest

from coathertz import methods as registry
from coathertz.methods import COSTS, RESOLUTIONS, method_info, method_names, settings_for
from coathertz.runner import Task
from coathertz.store import ResultStore, code_version, settings_key
from coathertz.verification import build_methods, get_study, plan, run_study, studies, variants_of
from coathertz.verification.study import NO_METHOD


@pytest.mark.parametrize("name", method_names())
def test_method_metadata(name):
    info = method_info(name)
    assert info.cost in COSTS and info.marker and info.label
    assert isinstance(info.reference_rank, int)
    assert info.source_packages, f"{name} declares no source packages: the store could not invalidate it"
    for res in RESOLUTIONS:
        m = registry.get_method(name, **settings_for(name, res))
        json.dumps(dict(m.settings()))  # JSON-ready: it is hashed into the store key
    assert set(info.source_packages) <= set(registry.numerical_sources())


@pytest.mark.parametrize("name", method_names())
def test_settings_that_differ_make_different_store_keys(name):
    """A method's settings are in the store key: two resolutions with different constructor
    settings never share stored results."""
    keys = {res: settings_key(registry.get_method(name, **settings_for(name, res)).settings())
            for res in RESOLUTIONS}
    for r1 in RESOLUTIONS:
        for r2 in RESOLUTIONS:
            if settings_for(name, r1) != settings_for(name, r2):
                assert keys[r1] != keys[r2], (name, r1, r2)
    m = registry.get_method(name, **settings_for(name, "quick"))
    from fake_method import cases

    assert Task(cases(1)[0], m).key[2] == settings_key(m.settings())


@pytest.mark.parametrize("resolution", ["quick", "full"])
def test_every_method_runs_a_case_of_every_study_it_supports(resolution):
    """Contract: for every registered method and every study, if the method supports any of the
    study's cases, the study gives it at least one (no method silently runs on zero cases).
    Cases of tier ``NO_METHOD`` are the study's own (solved in its ``analyse``) and excluded."""
    methods, notes = build_methods(resolution)
    assert not notes, notes
    for sname, mod in studies().items():
        cases = [sc for sc in mod.cases(resolution) if sc.tier != NO_METHOD]
        todo, absent = plan(cases, methods, variants_of(mod, methods, resolution)[0])
        ran = {n for _, n, _ in todo}
        for name, m in methods.items():
            if any(m.supports(sc.case) for sc in cases):
                assert name in ran, f"{name} supports {sname} cases but runs none: {absent}"


@pytest.fixture
def fifth(monkeypatch):
    """Register FifthMethod as the entry point ``fifth`` (what a plug-in's pyproject would do)."""
    real = registry._entry_points
    ep = EntryPoint("fifth", "fake_method:FifthMethod", registry.GROUP)
    monkeypatch.setattr(registry, "_entry_points", lambda: {**real(), "fifth": ep})
    registry.method_info.cache_clear()
    code_version.cache_clear()
    yield
    registry.method_info.cache_clear()
    code_version.cache_clear()


def test_a_fifth_method_runs_and_arbitrates(fifth, tmp_path):
    """A registered method appears everywhere without touching the studies: it runs the fig-3 cases,
    becomes their reference (rank 25 > FFT's 20), the FFT is its cross-check, its settings are in
    the store key and its sources in the code version."""
    assert "fifth" in method_names()
    assert "fake_method" in registry.numerical_sources()
    methods, notes = build_methods("tiny", ["closed-form", "fft", "fifth"])
    assert not notes and methods["fifth"].bias == 1.001  # settings_for(tiny)
    with ResultStore(tmp_path / "s.sqlite") as st:
        r = run_study(get_study("fig3"), "tiny", methods, st, {"workers": 1, "progress": False})
        case = get_study("fig3").cases("tiny")[0].case
        stored = st.get(case, "fifth", methods["fifth"].settings())
    assert stored is not None and stored.ok and stored.settings == {"bias": 1.001}
    assert set(r.reference.values()) == {"fifth"}
    assert {d["pair"] for d in r.crosscheck} == {"fft vs fifth"}
    claim = next(c for c in r.claims if c.id == "fig3-max-err")
    assert claim.judged_against.startswith("FIFTH")
    assert claim.uncertainty > 0  # the spread to the FFT
    # fig 10 (ellipses): the fifth method does not support them, the FFT stays the reference
    with ResultStore(tmp_path / "s.sqlite") as st:
        r10 = run_study(get_study("fig10"), "tiny", methods, st, {"workers": 1, "progress": False})
    assert set(r10.reference.values()) == {"fft"}
    assert "does not support" in r10.skipped["fifth"]


def test_inconclusive_verdict():
    """A miss smaller than the uncertainty is inconclusive; a larger one does not hold."""
    from coathertz.verification import INCONCLUSIVE, Claim, judge

    assert judge("within", 0.07, (-2.5, 0.0), 0.11, (-2.48, 0.07)) == (False, True)
    assert judge("within", 0.07, (-2.5, 0.0), 0.05, (-2.48, 0.07)) == (False, False)
    assert judge("<", 1.49, 1.5, 0.05) == (True, True)
    assert judge("<", 1.2, 1.5, 0.05) == (True, False)
    assert judge(">", 2.5, 2.0, 0.1) == (True, False)
    holds, inc = judge("within", 0.07, (-2.5, 0.0), 0.11, (-2.48, 0.07))
    assert Claim("x", "t", 0.07, "within [-2.5, 0] %", holds, inconclusive=inc).verdict == INCONCLUSIVE
    assert Claim("x", "t", 0.07, "within [-2.5, 0] %", False).verdict == "does not hold"


def test_old_protocol_method_sets_still_work():
    """A study written against the old protocol (a set of method names) keeps working."""
    from coathertz.verification import StudyCase, elastic_case

    case = elastic_case(3.0, 0.5)
    assert StudyCase("a", case, {}, frozenset({"closed-form", "fft"})).tier == "moderate"
    assert StudyCase("b", case, {}, frozenset({"closed-form", "fft", "fem"})).tier == "expensive"
    none = StudyCase("c", case, {}, frozenset())
    assert none.tier == "none"
    methods, _ = build_methods("tiny", ["closed-form", "fft"])
    todo, absent = plan([none], methods, {})
    assert todo == [] and set(absent["c"]) == {"closed-form", "fft"}


def test_a_method_missing_a_required_member_is_refused_by_name(monkeypatch):
    """The registry checks each class against the contract when it loads it and names what is
    missing or malformed (here ``solve``, and a malformed optional hook)."""
    import pytest

    from coathertz import methods
    from coathertz.errors import CoatHertzError
    from coathertz.fft.method import FFTMethod

    class NoSolve:
        name, cost, marker, label, reference_rank, source_packages = "bad", "pricey", "x", "bad", 1, ()

        @classmethod
        def settings_for(cls, resolution):
            return {}

        def settings(self):
            return {}

        def supports(self, case):
            return True

    class BadHook(FFTMethod):
        inline = "yes"

    class EP:
        def __init__(self, cls):
            self.cls = cls

        def load(self):
            return self.cls

    monkeypatch.setattr(methods, "_entry_points", lambda: {"bad": EP(NoSolve), "hook": EP(BadHook),
                                                           "fft": EP(FFTMethod)})
    with pytest.raises(CoatHertzError, match=r"method 'bad' .*missing solve \(method\)"):
        methods.method_class("bad")
    with pytest.raises(CoatHertzError, match=r"method 'hook' .*inline must be a bool, got 'yes'"):
        methods.method_class("hook")
    assert methods.method_class("fft") is FFTMethod
    for name in ("closed-form", "fft", "fem", "axisym"):  # the registered ones meet it
        monkeypatch.undo()
        methods.method_class(name)
