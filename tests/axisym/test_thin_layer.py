"""Thin layers in the exact method: the xi integral beyond ``X0`` in closed form (finite expansion
of ``j_{2m} j_{2n}``, integration by parts for the oscillating part), so that the quadrature's cost
and memory do not depend on ``h``; checked against the direct Gauss rule it replaces."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from coathertz.axisym import AxisymMethod
from coathertz.axisym import solver as S
from coathertz.axisym.kernel import pair_compliance
from coathertz.closedform.hertz import hertz_circular

from .conftest import coated

RULE = S.XiRule(order=8, panel=4.0)


@pytest.mark.parametrize("E_ratio,H", [(4.0, 1e-3), (0.25, 1e-3)])
@pytest.mark.parametrize("n_modes", [16, 32])
def test_tail_matrix_equals_direct_rule(E_ratio, H, n_modes):
    """The closed-form tail equals the direct rule over [X0, 14 a/h] to 1e-9 absolute (measured
    4e-11; the entries of A are up to ~5): the direct rule's own error at 8 nodes per panel of 4 and
    the 5-point stencil's, not round-off of the expansion."""
    case = coated(E_ratio, H)
    pc = pair_compliance(case)
    a = case.a0s
    X = 14.0 * a / pc.h_min
    X0 = S.direct_end(n_modes, RULE)
    assert X > 4.0 * X0
    xi, w, J = S.bessel_table(n_modes, X, RULE)
    Mv = pc.M(xi / a)
    n0 = int(np.searchsorted(xi, X0))
    ref = (J[:, n0:] * (w[n0:] * Mv[n0:])) @ J[:, n0:].T
    tail = S.tail_matrix(pc, a, n_modes, X0, X)
    err = np.abs(tail - ref).max()
    assert err < 1e-9, f"tail vs direct rule: max |diff| = {err:.2e} (|ref| max {np.abs(ref).max():.2e})"


def test_solution_with_tail_equals_direct(monkeypatch):
    """delta, a, p0 with the tail equal those of the direct rule over the whole range to 1e-9."""
    case = coated(4.0, 2e-3)
    m = AxisymMethod(n_modes=48, keep_fields=False)
    with_tail = m.solve(case)
    monkeypatch.setattr(S, "tail_start", lambda n_modes, panel: 1e9)
    direct = m.solve(case)
    assert with_tail.meta["n_xi"] < direct.meta["n_xi"] / 3
    for q in ("delta", "a", "p0"):
        d = abs(getattr(with_tail, q) / getattr(direct, q) - 1.0)
        assert d < 1e-9, f"{q}: tail vs direct rule differ by {d:.2e}"


def test_cost_independent_of_thickness():
    """From H = 1e-4 to 1e-12 the xi nodes are the same (the direct rule stops at X0) and a
    coating of 1e-12 a gives the substrate's Hertz solution to 1e-9."""
    n = set()
    for H in (1e-4, 1e-8, 1e-12):
        case = coated(4.0, H)
        r = AxisymMethod(n_modes=32, keep_fields=True).solve(case)
        n.add(r.meta["n_xi"])
        assert np.all(np.isfinite(r.fields["u_z"]))
    assert len(n) == 1, f"xi nodes vary with h: {sorted(n)}"
    h = hertz_circular(case.W, case.R, case.E_star_s)
    for q, ref in (("delta", h.delta0), ("a", h.a0), ("p0", h.p0)):
        d = abs(getattr(r, q) / ref - 1.0)
        assert d < 1e-9, f"H = 1e-12: {q} differs from the substrate's Hertz value by {d:.2e}"


def test_thin_layer_delta_self_convergence():
    """H = 1e-5: delta is converged to 1e-12 at 32 modes against 96 (measured ~1e-14); a and p0
    converge only like the edge boundary layer allows (relative error ~H, see the report)."""
    case = coated(4.0, 1e-5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        lo = AxisymMethod(n_modes=32, keep_fields=False).solve(case)
        hi = AxisymMethod(n_modes=96, keep_fields=False).solve(case)
    d = abs(lo.delta / hi.delta - 1.0)
    assert d < 1e-12, f"delta: N = 32 vs 96 differ by {d:.2e}"
    for q in ("a", "p0"):
        e = abs(getattr(lo, q) / getattr(hi, q) - 1.0)
        assert e < 1e-4, f"{q}: N = 32 vs 96 differ by {e:.2e} (edge boundary layer of width h)"
    assert math.isfinite(lo.p0)
