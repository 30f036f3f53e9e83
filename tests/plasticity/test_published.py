"""Published elastic-plastic sphere fits (Kogut & Etsion 2002, Jackson & Green 2005) as coded."""

from __future__ import annotations

import math

import pytest

from coathertz.errors import CoatHertzError
from coathertz.fem.plastic.published import jackson_green, kogut_etsion, kogut_etsion_critical
from coathertz.materials import Material

E_STAR, Y, NU, R = Material(200e9, 0.3).E_star, 1e9, 0.3, 0.01


def test_kogut_etsion_mean_pressure_closed_form():
    """p_mean = P / A = (2/3) K H (1.40 / 0.94) x^(1.263 - 1.146) for 6 <= x <= 110 (P_c / A_c =
    (2/3) K H), and the README's 20 um example: 1.40 x^1.263 P_c = 1931 N."""
    dc, _ = kogut_etsion_critical(E_STAR, Y, NU, R)
    K = 0.454 + 0.41 * NU
    for x in (7.0, 50.0, 109.0):
        f = kogut_etsion(x * dc, E_STAR, Y, NU, R)
        exact = 2.0 / 3.0 * K * 2.8 * Y * 1.40 / 0.94 * x ** (1.263 - 1.146)
        assert f.p_mean == pytest.approx(exact, rel=1e-12)
        assert f.P == pytest.approx(math.pi * f.a**2 * f.p_mean, rel=1e-12)
    assert kogut_etsion(20e-6, E_STAR, Y, NU, R).P == pytest.approx(1931.37, abs=0.01)


def test_jackson_green_values():
    """README example (20 um, 1993 N as in test_contact_zone) and the area law A = pi R delta (x/1.9)^B."""
    f = jackson_green(20e-6, E_STAR, Y, NU, R)
    assert f.P == pytest.approx(1993.28, abs=0.01)
    x = 20e-6 / f.delta_c
    B = 0.14 * math.exp(23 * Y / E_STAR)
    assert math.pi * f.a**2 == pytest.approx(math.pi * R * 20e-6 * (x / 1.9) ** B, rel=1e-12)


@pytest.mark.parametrize("fit, x", [(kogut_etsion, 0.5), (kogut_etsion, 200.0), (jackson_green, 1.0)])
def test_out_of_range_is_refused(fit, x):
    dc = kogut_etsion_critical(E_STAR, Y, NU, R)[0]
    with pytest.raises(CoatHertzError, match="delta/delta_c"):
        fit(x * dc, E_STAR, Y, NU, R)


def test_bad_input_one_line():
    with pytest.raises(CoatHertzError, match="nu must be in"):
        kogut_etsion(1e-6, E_STAR, Y, 0.5, R)
    with pytest.raises(CoatHertzError, match="Y must be > 0"):
        jackson_green(1e-6, E_STAR, -1.0, NU, R)
