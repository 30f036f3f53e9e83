"""a/R > 0.1 warns (ModelValidityWarning) and is recorded in meta, for every method (item 7)."""

from __future__ import annotations

import warnings

import pytest

from coathertz.casefile import load_example
from coathertz.cli import main
from coathertz.errors import ModelValidityWarning
from coathertz.methods import get_method, method_names
from coathertz.results import ContactResult
from coathertz.runner import Task, run_tasks
from coathertz.store import ResultStore
from coathertz.validity import A_OVER_R_MAX, check


def _result(a: float) -> ContactResult:
    return ContactResult("m", 1e-6, a, 1e9, 1.0)


def test_check_threshold():
    case = load_example("fig3_soft_coating")  # R = 10 mm
    inside = _result(A_OVER_R_MAX * case.R * 0.999)
    assert check(case, inside) is inside
    with pytest.warns(ModelValidityWarning, match=r"a/R = 0\.2 > 0\.1"):
        out = check(case, _result(0.2 * case.R))
    assert out.meta["validity"].startswith("a/R = 0.2 > 0.1")


def test_fft_cli_warns_on_stderr_and_in_json(capsys):
    assert main(["fft", "example:fig3_soft_coating", "--W", "1e12 N", "--grid", "32", "--json"]) == 0
    cap = capsys.readouterr()
    assert "coathertz fft: warning: fft: a/R = " in cap.err
    assert '"validity": "a/R = ' in cap.out


def test_predict_soft_coating_warns(capsys):
    assert main(["predict", "--W", "1 N", "--R", "10 mm", "--substrate", "200 GPa,0.3",
                 "--coating", "1e-3 Pa,0.3,40 um"]) == 0
    err = capsys.readouterr().err
    assert "a/R = " in err and "> 0.1" in err


@pytest.mark.parametrize("name", [m for m in method_names() if m in ("closed-form", "fft")])
def test_runner_records_validity_for_every_method(name):
    """Through the runner (what `verify` uses): meta['validity'] stored, one warning per run."""
    settings = {"n": 32} if name == "fft" else {}
    m = get_method(name, **settings)
    big = load_example("fig3_soft_coating").replace(W=1e12, label="huge")
    small = load_example("fig3_soft_coating")
    with ResultStore() as store, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = run_tasks([Task(big, m), Task(small, m)], store, workers=1, progress=False)
    assert "a/R" in out.get(big, m).result["meta"]["validity"]
    assert "validity" not in out.get(small, m).result["meta"]
    msgs = [str(w.message) for w in caught if w.category is ModelValidityWarning]
    assert len(msgs) == 1 and msgs[0].startswith("1 result(s)")


def test_the_a_over_R_rule_has_one_owner(monkeypatch):
    """Lowering ``coathertz.validity.A_OVER_R_MAX`` moves every method's flag (the exact method
    and the FE call the shared check; no method keeps its own copy of the rule), and a result
    checked by its method is warned about once."""
    import warnings

    import coathertz.validity as validity
    from coathertz.axisym import AxisymMethod
    from coathertz.casefile import load_case
    from coathertz.fem.method import FEMMethod

    case = load_case("example:b4c_on_steel")  # a/R = 0.0038
    monkeypatch.setattr(validity, "A_OVER_R_MAX", 1e-3)
    for method in (AxisymMethod(), FEMMethod(mesh="coarse")):
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            res = validity.check(case, method.solve(case))
        text = res.meta.get("validity", "")
        assert "a/R = 0.0038" in text and "> 0.001 " in text, text
        assert sum("a/R" in str(w.message) for w in rec) == 1, [str(w.message) for w in rec]
