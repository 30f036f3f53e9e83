"""Contact edge estimator of the plastic path: bracket, radius with the gap exponent chosen from
the data (Hertzian 3/2 and plastic ~ 1 edges alike), uncertainty."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.errors import ConvergenceError
from coathertz.fem.plastic.edge import edge_radius

R_NODES = np.linspace(0.0, 2.0e-3, 81)  # node spacing 25 um


@pytest.mark.parametrize("m", [1.0, 1.25, 1.5, 2.0])
@pytest.mark.parametrize("frac", [0.1, 0.5, 0.9])
def test_power_law_edge_is_recovered(m, frac):
    """Gap c (r - a)^m outside the edge, edge anywhere between two nodes: the exponent is found
    and a recovered to round-off (the fit is exact in form at the true m)."""
    s = R_NODES[1]
    a = R_NODES[40] + frac * s
    gap = np.where(R_NODES > a, 1e3 * np.clip(R_NODES - a, 0, None) ** m, 0.0)
    active = R_NODES <= a
    e = edge_radius(R_NODES, gap, active)
    assert (e["a_lo"], e["a_hi"]) == (R_NODES[40], R_NODES[41])
    assert e["m"] == pytest.approx(m)
    assert e["a"] == pytest.approx(a, rel=1e-9), (e["a"], a)
    assert 0.1 * s <= e["a_err"] <= 0.5 * s
    assert not e["clipped"]


def test_root_far_outside_the_bracket_is_clipped():
    """A gap that does not open like a power law (constant) has no root near the edge: the estimate
    stays within one node spacing of the bracket and says so."""
    gap = np.where(R_NODES > R_NODES[40], 1e-6, 0.0)
    gap[42:] += 1e-9 * np.arange(81 - 42)  # a nearly flat gap: root far inside the contact
    e = edge_radius(R_NODES, gap, R_NODES <= R_NODES[40])
    s = R_NODES[1]
    assert e["clipped"]
    assert R_NODES[40] - s - 1e-15 <= e["a"] <= R_NODES[41] + s + 1e-15


def test_edge_needs_free_nodes():
    with pytest.raises(ConvergenceError, match="candidate zone"):
        edge_radius(R_NODES, np.zeros(81), R_NODES <= R_NODES[77])
