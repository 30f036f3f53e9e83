"""The yield-onset claims carry a mesh uncertainty."""

from __future__ import annotations

import math

import pytest

from coathertz import verification as C
from coathertz.fem.plastic.onset import hertz_axis_onset
from coathertz.verification import get_study
from coathertz.verification.study import HOLDS


@pytest.fixture(scope="module")
def tiny():
    S = get_study("yield_onset")
    r = C.StudyResult(S.NAME, S.TITLE, S.CLAIM, "tiny")
    S.analyse(r)  # ~4 s: two onset searches at 12 and again at 24 elements across a
    return S, r


def test_refined_settings_double_the_mesh():
    S = get_study("yield_onset")
    for res in ("tiny", "quick", "full"):
        assert S.refined_fem_settings(res)["n_a"] == 2 * S.fem_settings(res)["n_a"]


def test_every_claim_has_a_finite_uncertainty(tiny):
    _, r = tiny
    assert not r.failures
    claims = {c.id: c for c in r.claims}
    assert set(claims) == {"yield-onset-homogeneous-p0", "yield-onset-homogeneous-z", "yield-onset-map"}
    for c in claims.values():
        assert math.isfinite(c.uncertainty) and c.uncertainty >= 0, c
        assert c.judged_against, c


def test_uncertainty_covers_the_error_against_the_hertz_axis_values(tiny):
    """The estimate 2|v_12 - v_24| bounds the true error of the coarse value. Measured at 12 / 24 /
    48 elements across a: z/a = 0.4905 / 0.4849 / 0.4799 against the Hertz axis value 0.4809 (the
    maximum is sampled at quadrature points, so z converges at first order and not monotonically:
    20 / 40 elements give 0.4906 / 0.4781), p0/Y = 1.61260 / 1.61291 / 1.61284 against 1.6128."""
    _, r = tiny
    claims = {c.id: c for c in r.claims}
    p0_cf, z_cf = hertz_axis_onset(0.3)
    hom = next(x for x in r.extra["onset"] if x["case"] == "homogeneous")
    for key, exact, cid in (("p0_over_Y", p0_cf, "yield-onset-homogeneous-p0"),
                            ("z_over_a", z_cf, "yield-onset-homogeneous-z")):
        err = 100 * abs(hom[key] / exact - 1)
        assert err == pytest.approx(claims[cid].value, rel=1e-12)
        assert err <= claims[cid].uncertainty, (key, err, claims[cid].uncertainty)
    # and it is an estimate, not a blanket: well below the claims' bounds (1 %, 3 %)
    assert claims["yield-onset-homogeneous-p0"].uncertainty < 0.2
    assert claims["yield-onset-homogeneous-z"].uncertainty < 3.0
    assert claims["yield-onset-homogeneous-p0"].verdict == HOLDS


def test_forked_searches_give_the_same_numbers(tiny):
    """With two workers the map, the homogeneous refined re-solve and (as soon as the map is
    known) the worst coated case's refined re-solve run in forked processes: every number is
    the one computed in this process."""
    import json

    from coathertz.jsonsafe import to_jsonable

    S, r1 = tiny
    r2 = C.StudyResult(S.NAME, S.TITLE, S.CLAIM, "tiny", workers=2)
    S.analyse(r2)
    assert not r2.failures, r2.failures

    def numbers(r):
        return json.dumps(to_jsonable([r.to_json()["claims"], r.extra]), sort_keys=True, default=repr)

    assert numbers(r2) == numbers(r1)
    assert "uncertainty" in r2.extra and len(r2.extra["uncertainty"]) == len(r1.extra["uncertainty"])
