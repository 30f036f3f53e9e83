"""The axisym method's protocol, metadata, errors, fields and a small FFT cross-check."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from conftest import R_SPHERE, STEEL, coated

from coathertz.axisym import AxisymMethod
from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import Body
from coathertz.methods import get_method, method_names


def test_registered_with_metadata():
    assert "axisym" in method_names()
    m = get_method("axisym")
    assert isinstance(m, AxisymMethod)
    assert (m.cost, m.marker, m.reference_rank) == ("cheap", "D", 30)
    assert m.source_packages == ("coathertz.axisym",)
    for res in ("tiny", "quick", "full"):
        assert isinstance(AxisymMethod.settings_for(res), dict)
        AxisymMethod(**AxisymMethod.settings_for(res))
    with pytest.raises(CoatHertzError, match="resolution"):
        AxisymMethod.settings_for("huge")
    json.dumps(dict(m.settings()))
    assert AxisymMethod(n_modes=32).settings() != m.settings()


def test_elliptical_case_is_rejected():
    case = ContactCase(Body(STEEL, None, 17.4e-3, 3e-3), Body.half_space(STEEL), 400.0)
    m = AxisymMethod()
    assert not m.supports(case)
    with pytest.raises(CoatHertzError, match="not axisymmetric"):
        m.solve(case)


@pytest.mark.parametrize("kw", [dict(interface="glued"), dict(n_modes=1), dict(order=2),
                                dict(rtol=0.5), dict(decay=1.0), dict(panel=0.0)])
def test_bad_settings(kw):
    with pytest.raises(CoatHertzError):
        AxisymMethod(**kw)


def test_solve_many_and_fields():
    cases = [coated(4.0, 0.3), coated(0.25, 0.3)]
    res = AxisymMethod().solve_many(cases)
    for c, r in zip(cases, res, strict=True):
        assert r.method == "axisym" and r.W == c.W and r.r_a == r.a == r.r_b
        f = r.fields
        rr, p, u = f["r"], f["pressure"], f["u_z"]
        assert np.all(p >= -1e-9 * r.p0) and np.isclose(np.max(p), r.p0, rtol=1e-6)
        inside = rr <= r.a
        assert np.allclose(u[inside], r.delta - rr[inside] ** 2 / (2 * c.R), rtol=0, atol=1e-12 * r.delta)
        # outside: separation (gap >= 0) and continuity at the edge
        gap = rr[~inside] ** 2 / (2 * c.R) - (r.delta - u[~inside])
        assert np.all(-u[~inside] + r.delta - rr[~inside] ** 2 / (2 * c.R) <= 1e-9 * r.delta)
        assert np.all(gap >= -1e-9 * r.delta)
        assert json.dumps(r.scalars())


def test_displacement_continuous_at_edge():
    """The outside formula (Sneddon + layer correction) meets the contact condition at r = a."""
    from coathertz.axisym.kernel import pair_compliance
    from coathertz.axisym.solver import XiRule, displacement, solve_load

    case = coated(4.0, 0.1)
    pc = pair_compliance(case)
    sol, _ = solve_load(pc, case.R, case.W, 48, XiRule())
    u = displacement(pc, sol, np.array([1.0, 1.0 + 1e-9]), case.R, XiRule())
    assert abs(u[1] - u[0]) < 1e-8 * sol.delta


def test_off_axis_pressure_peak_stiff_coating():
    """Stiff coating (E = 10) at H = 0.3: the pressure peaks on a ring (r ~ 0.70 a), 19.5 % above
    its value on the axis."""
    r = AxisymMethod().solve(coated(10.0, 0.3))
    rho = r.meta["r_p0"] / r.a
    p = r.fields["pressure"]
    assert 0.69 < rho < 0.71, rho
    assert 0.19 < r.p0 / p[0] - 1 < 0.2


def test_validity_warning():
    case = ContactCase.sphere_on_coated_half_space(R_SPHERE, 2e5, STEEL, 1e-4, STEEL)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        r = AxisymMethod().solve(case)
    assert any("a/R" in str(x.message) for x in w)
    assert "a/R" in r.meta["validity"]


def test_agrees_with_fft_small():
    """One coated case against the FFT at n = 128: delta and p0 within 3e-4 (FFT discretisation);
    the comparison over the paper's grids at n = 256 is in the slow test."""
    from coathertz.fft.method import FFTMethod

    case = coated(4.0, 0.3)
    a = AxisymMethod().solve(case)
    f = FFTMethod(n=128).solve(case)
    assert abs(f.delta / a.delta - 1) < 3e-4
    assert abs(f.p0 / a.p0 - 1) < 3e-4
    assert math.isfinite(a.meta["r_p0"])
