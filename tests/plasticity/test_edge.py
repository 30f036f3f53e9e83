"""Contact edge estimator of the plastic path: bracket, radius from a fit of the pressure's own
decay ``c (1 - r^2/a^2)^n`` to the nodal contact forces (Hertzian n = 1/2 and plastic n ~ 0 edges
alike), uncertainty."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.plastic.edge import check_q2_layout, consistent_loads, edge_radius

R_NODES = np.linspace(0.0, 2.0e-3, 81)  # 40 Q2 edges, node spacing 25 um
S = R_NODES[1]


def _forces(a: float, n: float) -> np.ndarray:
    return 1e9 * consistent_loads(R_NODES, a, n, 0, 40)


def test_consistent_loads_integrate_the_pressure():
    """The loads sum to the pressure's resultant, 2 pi a^2 / (2 (n + 1)) (Johnson eq 4.9 family),
    to quadrature round-off; a uniform pressure over whole edges gives the Q2 weights' pattern."""
    for n in (0.0, 0.5, 1.0):
        a = R_NODES[30] + 0.37 * S
        total = consistent_loads(R_NODES, a, n, 0, 40).sum()
        exact = math.pi * a**2 / (n + 1.0)
        # the edge rule integrates s^(2n+1) * polynomial: the smooth (a + x)^n factor leaves ~1e-11 (measured)
        assert abs(total / exact - 1) < 1e-9, (n, total, exact)
    uniform = consistent_loads(R_NODES, 1.0, 0.0, 0, 40)  # a = 1 m beyond the nodes, n = 0: p = 1
    assert np.all(uniform[21:-2:2] > 1.8 * uniform[22:-1:2])  # off the axis: mid-side ~ 2x a vertex
    assert abs(uniform.sum() / (math.pi * R_NODES[-1] ** 2) - 1) < 1e-12


@pytest.mark.parametrize("n", [0.0, 0.1, 0.5, 1.0])
@pytest.mark.parametrize("frac", [0.1, 0.5, 0.9])
def test_power_law_pressure_edge_is_recovered(n, frac):
    """Forces of ``(1 - r^2/a^2)^n`` with the edge anywhere between two nodes: the exponent is found
    and ``a`` recovered to 1e-3 node spacings (the fit is exact in form; every node whose Q2 shape
    function reaches into the contact is loaded, the vertex after an edge in the first half of an
    element with a small negative force)."""
    a = R_NODES[40] + frac * S
    lam = _forces(a, n)
    active = np.abs(lam) > 0
    e = edge_radius(R_NODES, lam, active)
    last = int(np.nonzero(active)[0].max())
    assert (e["a_lo"], e["a_hi"]) == (R_NODES[last], R_NODES[last + 1])
    assert abs(e["a"] - a) < 1e-3 * S, (e["a"], a)
    assert e["n"] == pytest.approx(n, abs=1e-3)
    assert 0.05 * S * (1 - 1e-9) <= e["a_err"] <= 0.5 * S * (1 + 1e-9)
    assert e["residual"] < 1e-4
    assert not e["clipped"]


@pytest.mark.parametrize("n", [0.0, 0.5])
def test_force_free_first_node_costs_a_fraction_of_a_spacing(n):
    """In the FE the first node beyond the contact carries no force at all (not the small negative
    consistent load): with that node's force set to zero the radius moves by less than a fifth of
    a node spacing, at any edge position."""
    for frac in np.linspace(0.05, 0.95, 10):
        a = R_NODES[40] + frac * S
        lam = np.clip(_forces(a, n), 0.0, None)
        e = edge_radius(R_NODES, lam, lam > 0)
        assert abs(e["a"] - a) < 0.2 * S, (frac, (e["a"] - a) / S)


def test_oscillating_forces_average_out():
    """The vertex / mid-side oscillation of Q2 node-to-surface forces (+-5 %, as measured on the
    plastic path) moves the radius by far less than a node spacing."""
    a = R_NODES[40] + 0.4 * S
    lam = _forces(a, 0.05)
    lam[1::2] *= 1.05
    lam[2::2] *= 0.95
    e = edge_radius(R_NODES, lam, lam > 0)
    assert abs(e["a"] - a) < 0.25 * S, (e["a"] - a) / S
    assert e["a_err"] <= 0.5 * S


def test_edge_needs_free_nodes():
    with pytest.raises(ConvergenceError, match="candidate zone"):
        edge_radius(R_NODES, np.ones(81), R_NODES <= R_NODES[79])


def test_layout_is_checked():
    with pytest.raises(CoatHertzError, match="mid-side"):
        check_q2_layout(R_NODES**2)
