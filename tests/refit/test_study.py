"""The ``refit`` study at the tiny resolution: runs against the exact method, claims, plots.

The refit error of one case is recomputed here from the rule and the exact method directly.
"""

from __future__ import annotations

import warnings

import pytest

from coathertz import verification as C
from coathertz.closedform.refit import predict
from coathertz.fitalpha.sweep import Point, make_case
from coathertz.methods import get_method
from coathertz.store import ResultStore
from coathertz.verification import get_study


@pytest.fixture(scope="module")
def tiny():
    mod = get_study("refit")
    methods, _ = C.build_methods("tiny")
    return C.run_study(mod, "tiny", methods, ResultStore(":memory:"), {"progress": False, "workers": 1})


def test_tiny_study_claims_and_independent_error(tiny, tmp_path):
    ids = {c.id for c in tiny.claims}
    for cfg in ("elastic", "rigid"):
        assert f"refit-{cfg}-paper-refit-axisym" in ids and f"refit-{cfg}-paper-paper-axisym" in ids
    assert "refit-ellipse-paper-refit-fft" in ids
    assert any(c.id == "refit-elastic-fft-vs-axisym" for c in tiny.claims)
    rec = next(r for r in tiny.extra["refit_errors"]
               if r["config"] == "elastic" and r["E"] == 4.0 and r["H"] == 1.0 and r["quantity"] == "p")
    case = make_case(Point("elastic", 4.0, 1.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exact = get_method("axisym").solve(case)
        pred, _ = predict(case, warn=False)
    assert rec["refit"] == pytest.approx(100 * (pred.p0 / exact.p0 - 1), abs=1e-6)
    paths = get_study("refit").plot(tiny, tmp_path)
    assert paths and all(p.stat().st_size > 1000 for p in paths)
