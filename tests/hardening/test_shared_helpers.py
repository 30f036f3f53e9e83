"""The shared helpers of one JSON sanitiser, one identical-pair equivalence,
the eq (13) constants in one place."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coathertz.casefile import load_example
from coathertz.closedform.extended import constants_from_ratio
from coathertz.jsonsafe import dumps, from_jsonable, loads, to_jsonable
from coathertz.materials import Material, coating_constants, lam_kappa


def test_jsonsafe_round_trip():
    obj = {"R": math.inf, "neg": -math.inf, "x": np.float64(2.5), "n": np.int64(3),
           "arr": np.array([1.0, np.inf]), "t": (1, 2), 3: None, "flag": True}
    text = dumps(obj, sort_keys=True)
    json.loads(text)  # strict JSON
    back = loads(text)
    assert back["R"] == math.inf and back["neg"] == -math.inf and back["x"] == 2.5 and back["n"] == 3
    assert back["arr"] == [1.0, math.inf] and back["t"] == [1, 2] and back["3"] is None
    assert back["flag"] is True
    assert math.isnan(from_jsonable(to_jsonable(math.nan)))
    assert dumps({"a": [math.nan, np.float32(np.inf)]}) == '{"a": ["nan", "inf"]}'  # no bare NaN


def test_jsonsafe_fast_paths_match_the_general_path():
    """Plain dicts, lists and numbers take a fast path (a run converts some 10^5 values); it
    gives what the general path gives, with numpy values, subclasses and specials nested in it,
    and ``loads`` skips the search for "inf"/"nan" strings only where the text has none."""
    from collections import OrderedDict

    from coathertz.jsonsafe import _to_jsonable

    obj = {"a": [1.0, math.inf, -math.inf, math.nan, 2, True, None, "s", np.float64(3.5),
                 np.float64(np.inf), (1, {2: 3.0}), {4, 5}], 7: {"x": np.arange(3), "y": [[math.nan]]},
           "od": OrderedDict(b=math.inf), "f": np.float32(0.5), "k": np.int64(2), "e": []}
    fast, slow = to_jsonable(obj), _to_jsonable(obj)
    assert json.dumps(fast, sort_keys=True) == json.dumps(slow, sort_keys=True)
    assert fast["a"][1:4] == ["inf", "-inf", "nan"] and fast["7"]["x"] == [0, 1, 2]
    for text in ['{"a": 1.5, "b": ["x", "nan "]}', '{"a": "inf", "b": ["-inf", "nan"]}', '"nan"',
                 '{"inf": 2}', '[1, {"c": "-inf"}]']:
        want = from_jsonable(json.loads(text))
        got = loads(text)
        assert json.dumps(to_jsonable(got)) == json.dumps(to_jsonable(want)), text
        assert type(got) is type(want)
    assert loads('{"a": "inf"}')["a"] == math.inf


@pytest.mark.parametrize("name", ["keer_case_a", "keer_case_b", "homogeneous_steel"])
def test_identical_pair_equivalent_is_exact_for_hertz(name):
    case = load_example(name)
    eq = case.identical_pair_equivalent()
    if not case.is_identical_pair:
        assert eq is None
        return
    assert eq.body1.is_rigid and eq.R == pytest.approx(2 * case.R, rel=1e-15)
    # eq (1): same a0 and p0, approach of the pair = 2 x approach of the equivalent
    for which in ("hertz_s", "hertz_c"):
        hp, he = getattr(case, which), getattr(eq, which)
        assert float(hp.a0) == pytest.approx(float(he.a0), rel=1e-13)
        assert float(hp.p0) == pytest.approx(float(he.p0), rel=1e-13)
        factor = case.IDENTICAL_PAIR_DELTA_FACTOR
        assert float(hp.delta0) == pytest.approx(factor * float(he.delta0), rel=1e-13)


def test_b4c_is_not_an_identical_pair():
    assert load_example("b4c_on_steel").identical_pair_equivalent() is None


def test_eq13_constants_agree_everywhere():
    c, s = Material(380e9, 0.17), Material(200e9, 0.3)
    k = coating_constants(c, s)
    assert (k.lam, k.kappa) == lam_kappa(k.mu, 0.17, 0.3)
    lam, kappa = constants_from_ratio(c.E_star / s.E_star, 0.17, 0.3)
    assert float(lam) == pytest.approx(k.lam, rel=1e-14) and float(kappa) == pytest.approx(k.kappa, rel=1e-14)
