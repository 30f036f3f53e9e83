"""The ``stresses`` study at tiny resolution (grids 24^2 / 32^2): its claims and numbers."""

from __future__ import annotations

import pytest

from coathertz.verification import StudyResult, get_study


@pytest.fixture(scope="module")
def tiny():
    S = get_study("stresses")
    r = StudyResult(S.NAME, S.TITLE, S.CLAIM, "tiny")
    S.analyse(r)
    return S, r


def _claim(r, cid):
    return next(c for c in r.claims if c.id == cid)


def test_protocol():
    S = get_study("stresses")
    for res in ("tiny", "quick", "full"):
        cs = S.cases(res)
        assert cs and len({c.id for c in cs}) == len(cs) and all(c.tier == "none" for c in cs)
    assert len(S.cases("tiny")) <= len(S.cases("quick")) <= len(S.cases("full"))
    assert len(S.cases("full")) == 1 + 5 * 6 + 2 + 8


def test_homogeneous_onset(tiny):
    _, r = tiny
    assert not r.failures, r.failures
    p0 = _claim(r, "stresses-homogeneous-p0")
    z = _claim(r, "stresses-homogeneous-z")
    # measured (24^2 / 32^2): p0/Y 1.6149 / 1.6140 against 1.6129 (0.13 %, uncertainty 0.05 %);
    # z/a 0.4839 / 0.4833 against 0.4809 (0.62 %, uncertainty 0.13 %)
    assert p0.verdict == "holds" and p0.value < 0.3 and p0.uncertainty < 0.2, p0
    assert z.verdict == "holds" and z.value < 1.5 and z.uncertainty < 0.5, z
    hom = [row for row in r.extra["onset"] if row["case"] == "homogeneous"]
    assert hom[0]["mu"] == 0 and hom[0]["W_bar"] == 1.0 and hom[0]["where"] == "substrate"


def test_onset_against_hamilton(tiny):
    _, r = tiny
    ham = r.extra["hamilton"]
    # Hamilton (closed form): 0.6200 / 0.6476 / 0.9650 p0 at mu = 0 / 0.25 / 0.5
    assert ham[0.0]["vm_over_p0"] == pytest.approx(0.6200, abs=2e-4)
    assert ham[0.25]["vm_over_p0"] == pytest.approx(0.6476, abs=2e-4)
    assert ham[0.5]["vm_over_p0"] == pytest.approx(0.9650, abs=5e-4) and ham[0.5]["z_over_a"] == 0.0
    below = _claim(r, "stresses-hamilton-vm")
    # measured below the surface (mu = 0, 0.25): 0.13 % worst (24^2), uncertainty 0.05 %
    assert below.verdict == "holds" and below.value < 0.5, below
    # on the surface (mu = 0.5, trailing edge): FFT 0.9497 (24^2), 0.9281 (32^2) against 0.9650:
    # the edge converges at order 1/2, the uncertainty (x 7.5) covers the bound: inconclusive
    surf = _claim(r, "stresses-hamilton-vm-surface")
    assert surf.value < 6.0 and surf.uncertainty > surf.value, surf
    sw = r.extra["surface_switch"]
    assert sw["hamilton"] == pytest.approx(0.305, abs=0.003) and sw["fft"] == 0.5
    assert _claim(r, "stresses-surface-switch").verdict == "holds"


def test_coated_map_numbers(tiny):
    _, r = tiny
    rows = {row["mu"]: row for row in r.extra["onset"] if row["case"] == "E=4,H=0.3"}
    # a coating four times stiffer, H = 0.3: first yield at the interface at 6.6 % of the uncoated
    # load without friction (refined grid 6.8 %); on the surface at mu = 0.5 (3.2 %, refined 3.05 %)
    assert rows[0.0]["where"] == "interface" and 0.055 < rows[0.0]["W_bar"] < 0.08, rows[0.0]
    assert rows[0.5]["where"] == "surface" and 0.025 < rows[0.5]["W_bar"] < 0.04, rows[0.5]
    wmin = _claim(r, "stresses-map-wy-min")
    # its uncertainty: |0.0316 - 0.0304| x 7.5 (surface peak at the trailing edge, order 1/2 on
    # 24^2 / 32^2) + the interpolation in W (10 %): 0.012
    assert wmin.verdict == "observed" and 0.01 < wmin.uncertainty < 0.1, wmin
    shear = _claim(r, "stresses-map-iface-shear")
    # measured 0.099 p0 at mu = 0.25 (refined 0.0995)
    assert 0.08 < shear.value < 0.12 and shear.uncertainty < 0.01, shear


def test_figures(tiny, tmp_path):
    S, r = tiny
    paths = S.plot(r, tmp_path)
    assert {p.name for p in paths} == {"stresses_onset_vs_mu.png", "stresses_maps.png", "stresses_slice.png"}
    for p in paths:
        assert p.stat().st_size > 5000, p


def test_forked_searches_give_the_same_numbers(tiny):
    """With the run's two workers the onset searches and refined re-solves run in forked
    processes: every number is the one computed in this process."""
    import json

    from coathertz.jsonsafe import to_jsonable

    S, r1 = tiny
    r2 = StudyResult(S.NAME, S.TITLE, S.CLAIM, "tiny", workers=2)
    S.analyse(r2)
    assert not r2.failures, r2.failures

    def numbers(r):
        extra = {k: v for k, v in r.extra.items() if k != "cpu_s"}
        return json.dumps(to_jsonable([r.to_json()["claims"], extra]), sort_keys=True, default=repr)

    assert numbers(r2) == numbers(r1)
