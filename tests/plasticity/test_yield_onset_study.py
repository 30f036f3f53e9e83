"""The yield_onset study at tiny resolution: protocol, homogeneous claims, figure."""

from __future__ import annotations

import pytest

from coathertz import verification as C
from coathertz.verification import get_study


def test_yield_onset_study_protocol():
    S = get_study("yield_onset")
    assert len(S.cases("tiny")) == 2 and len(S.cases("quick")) == 5 and len(S.cases("full")) == 91
    # the onset solves are the study's own; the registered methods cross-check the elastic contact:
    # all of them on the homogeneous case, the cheap ones on the grid
    tiers = {sc.id: sc.tier for sc in S.cases("quick")}
    assert tiers.pop("homogeneous") == "expensive" and set(tiers.values()) == {"cheap"}
    W_ys, a_ys = S.substrate_reference()
    assert 40 < W_ys < 50 and 100e-6 < a_ys < 130e-6  # p0 = 1.61 GPa on steel, R = 10 mm


@pytest.mark.slow
def test_yield_onset_study_tiny(tmp_path):
    """~8 s CPU (two onset searches at 12 elements across a)."""
    S = get_study("yield_onset")
    r = C.StudyResult(S.NAME, S.TITLE, S.CLAIM, "tiny")
    S.analyse(r)
    assert not r.failures
    claims = {c.id: c for c in r.claims}
    assert claims["yield-onset-homogeneous-p0"].holds and claims["yield-onset-homogeneous-z"].holds
    hom = next(x for x in r.extra["onset"] if x["case"] == "homogeneous")
    assert abs(hom["W_bar"] - 1.0) < 5e-3  # the FE onset of the substrate alone is W_ys (Hertz)
    coated = next(x for x in r.extra["onset"] if x["case"] != "homogeneous")
    assert coated["where"] in ("coating", "interface") and coated["W_bar"] < 0.2  # stiff coating, same Y
    assert all(p.exists() for p in S.plot(r, tmp_path))
