"""Homogeneous bodies against Hertz: accuracy at the default grid and observed orders.

Measured (rigid 10 mm sphere on steel, 1 N, default tol; relative errors):

====  =========  ==========  =========  ========
n     delta      a edge-fit  a_num      p0
====  =========  ==========  =========  ========
32    -3.7e-4    -3.2e-3     +6.1e-3    +1.9e-4
64    -6.8e-5    -5.7e-5     +7.5e-3    +6.6e-5
128   -1.2e-5    -8.4e-5     +3.5e-4    +2.0e-5
256   -3.4e-6    +6.5e-5     +1.5e-3    +4.7e-6
====  =========  ==========  =========  ========

delta and p0 converge at order ~2; the radius estimators do not converge smoothly (a cell is
in or out of the contact): a_num scatters within 1e-2, the edge fit within 3e-4 for n >= 64.
The 0.3 % tolerance of the issue is met at the default n = 128 with a margin of >= 8x.
"""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.fft.method import FFTMethod
from coathertz.materials import Body, Material

from .conftest import STEEL


def _errors(case, n, ref, **kw):
    r = FFTMethod(n=n, **kw).solve(case)
    return {
        "delta": r.delta / float(ref.delta0) - 1,
        "a": r.a / float(ref.a0) - 1,
        "a_num": r.meta["a_num"] / float(ref.a0) - 1,
        "p0": r.p0 / float(ref.p0) - 1,
    }, r


def test_default_resolution_within_0p3_percent(homogeneous):
    err, r = _errors(homogeneous, FFTMethod().n, homogeneous.hertz_s)
    for k, v in err.items():
        assert abs(v) < 3e-3, f"{k}: relative error {v:.2e} at n = {FFTMethod().n}"
    assert r.meta["residual"] < 1e-6 and r.meta["penetration"] < 1e-6


def _orders(case, ns, keys):
    ref = case.hertz_s
    errs = {k: [] for k in keys}
    for n in ns:
        e, _ = _errors(case, n, ref)
        for k in keys:
            errs[k].append(abs(e[k]))
    hs = 1.0 / np.asarray(ns, dtype=float)
    return {k: np.polyfit(np.log(hs), np.log(v), 1)[0] for k, v in errs.items()}, errs


def test_observed_orders_three_grids(homogeneous):
    ns = (32, 64, 128)
    orders, errs = _orders(homogeneous, ns, ("delta", "p0"))
    msg = f"observed orders {orders} on n = {ns}; errors {errs}"
    assert orders["delta"] > 1.8, msg
    assert orders["p0"] > 1.4, msg


@pytest.mark.slow
def test_observed_orders_four_grids_slow(homogeneous):
    ns = (32, 64, 128, 256)
    orders, errs = _orders(homogeneous, ns, ("delta", "p0", "a", "a_num"))
    msg = f"observed orders {orders} on n = {ns}; errors {errs}"
    assert orders["delta"] > 1.8 and orders["p0"] > 1.5, msg
    assert max(errs["a"][1:]) < 5e-4 and max(errs["a_num"]) < 1e-2, msg


def test_elastic_indenter_adds_compliance():
    ball = Material(110e9, 0.34)
    case = ContactCase(Body.sphere(ball, 6e-3), Body.half_space(STEEL), 5.0)
    err, _ = _errors(case, 128, case.hertz_s)
    for k, v in err.items():
        assert abs(v) < 3e-3, f"{k}: {v:.2e}"


@pytest.mark.parametrize("spacing_ratio", [None, 1 / 3])
def test_elliptical_paper_geometry(spacing_ratio):
    """Section 5 geometry: Rx = 17.4 mm, Ry = 3 mm, W = 400 N (1/zeta ~ 3.18), steel."""
    case = ContactCase(Body(Material.rigid(), None, 17.4e-3, 3e-3), Body.half_space(STEEL), 400.0)
    ref = case.hertz_s
    r = FFTMethod(n=128, spacing_ratio=spacing_ratio).solve(case)
    if spacing_ratio is not None:
        g = r.meta["grid"]
        assert g["dy"] == pytest.approx(g["dx"] / 3)
    errs = {
        "delta": r.delta / float(ref.delta0) - 1,
        "p0": r.p0 / float(ref.p0) - 1,
        "r_a": r.r_a / float(ref.r_a0) - 1,
        "r_b": r.r_b / float(ref.r_b0) - 1,
    }
    for k, v in errs.items():
        assert abs(v) < 3e-3, f"{k}: {v:.2e} ({errs})"
    # semi-axes from the sector fits of the gap; measured with
    # dy = dx/3: r_a +2.2e-4, r_b +5.5e-4; square cells: +8.6e-5, +9.6e-4
    assert max(abs(errs["r_a"]), abs(errs["r_b"])) < 2e-3, errs
    assert r.meta["radius_estimator"] == "gap-fit"


def test_coated_self_convergence_orders():
    """E = 3, H = 0.3 on n = 32, 64, 128 against n = 256: delta and p0 converge at ~2."""
    from .conftest import coated

    case = coated(3.0, 0.3)
    ref = FFTMethod(n=256).solve(case)
    ns = (32, 64, 128)
    rs = [FFTMethod(n=n).solve(case) for n in ns]
    hs = np.log(1.0 / np.asarray(ns, dtype=float))
    ed = [abs(r.delta / ref.delta - 1) for r in rs]
    ep = [abs(r.p0 / ref.p0 - 1) for r in rs]
    od, op = np.polyfit(hs, np.log(ed), 1)[0], np.polyfit(hs, np.log(ep), 1)[0]
    msg = f"observed orders delta {od:.2f}, p0 {op:.2f}; errors {ed}, {ep}"
    assert od > 1.5 and op > 1.5, msg
    assert ed[-1] < 1e-4 and ep[-1] < 1e-4, msg
    assert abs(rs[-1].a / ref.a - 1) < 1e-3 and abs(rs[-1].meta["a_num"] / ref.a - 1) < 5e-3
