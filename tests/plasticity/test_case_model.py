"""Yield data in the case model: TOML with units, round trip, result-store key."""

from __future__ import annotations

import tomllib

import pytest

from coathertz.casefile import case_from_dict, case_to_toml
from coathertz.errors import CoatHertzError
from coathertz.store import case_dict, case_key

DOC = """
W = "10 N"
[body1]
material = "rigid"
R = "10 mm"
[body2]
material = { E = "200 GPa", nu = 0.3, Y = "900 MPa", hardening = "linear", H = "5 GPa" }
coating = { E = "400 GPa", nu = 0.2, h = "20 um", Y = "4 GPa", hardening = "table", \
table = [[0, "4 GPa"], [0.01, "4.5 GPa"]] }
"""


def test_toml_reads_yield_data_with_units_and_round_trips():
    case = case_from_dict(tomllib.loads(DOC))
    sub = case.body2.material.plasticity
    coat = case.body2.coating.material.plasticity
    assert sub.Y == 900e6 and sub.hardening == "linear" and sub.H == 5e9
    assert coat.table == ((0.0, 4e9), (0.01, 4.5e9))
    again = case_from_dict(tomllib.loads(case_to_toml(case)))
    assert again == case and case_key(again) == case_key(case)


def test_store_key_includes_yield_data():
    case = case_from_dict(tomllib.loads(DOC))
    plain = DOC.replace(', Y = "900 MPa", hardening = "linear", H = "5 GPa"', "")
    elastic = case_from_dict(tomllib.loads(plain))
    other = case_from_dict(tomllib.loads(DOC.replace("900 MPa", "950 MPa")))
    assert case_dict(case)["body2"]["material"]["plasticity"] == {"Y": 900e6, "hardening": "linear", "H": 5e9}
    assert len({case_key(case), case_key(elastic), case_key(other)}) == 3
    assert "plasticity" not in case_dict(elastic)["body2"]["material"]


@pytest.mark.parametrize("bad, word", [
    ('Y = "900"', "has no unit"),
    ('H = "5 GPa"', "need the yield stress Y"),
    ('Y = "900 MPa", hardening = "power", n = 0.1', "eps0"),
])
def test_bad_yield_input_names_the_parameter(bad, word):
    doc = DOC.replace('Y = "900 MPa", hardening = "linear", H = "5 GPa"', bad)
    with pytest.raises(CoatHertzError, match=word):
        case_from_dict(tomllib.loads(doc))
