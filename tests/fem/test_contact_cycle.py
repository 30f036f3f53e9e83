"""The active-set loop's cycle handling (fem/contact.py, ``_loop``).

A primal-dual active set can cycle between two sets when the edge node's multiplier and gap are
at round-off level (seen with the incompressible mixed system: 50 factorisations, then failure).
The loop accepts the best member of a cycle only if its violation is below CYCLE_TOL.
"""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.errors import ConvergenceError
from coathertz.fem.contact import CYCLE_TOL, ContactProblem, _loop


def _problem(n=4):
    z = np.zeros(n)
    cand = np.arange(n)
    return ContactProblem(None, z, np.array([], int), z[:0], cand, z, z + 1, np.zeros(n), 1.0, 1.0, 1.0)


def _alternating(edge_lam):
    """A fake step: the last node's multiplier is ``edge_lam`` when active; when it is inactive
    its gap is ``-edge_lam`` (penetration), so the exact PDAS update flips it back and forth."""

    def step(prob, solver, active):
        n = len(prob.cand)
        lam = np.where(active, 1.0, 0.0)
        lam[-1] = edge_lam if active[-1] else 0.0
        u = np.zeros(n)
        u[-1] = 0.0 if active[-1] else edge_lam  # gap = g0 - delta - u
        return u, u[prob.cand], 1.0, lam

    def update(active, lam, gap):
        # an exact update that misreads the edge node both ways (what round-off does)
        new = active.copy()
        new[-1] = not active[-1]
        return new

    return step, update


def test_round_off_cycle_is_accepted():
    prob = _problem()
    step, update = _alternating(-1e-12)
    sol = _loop(prob, None, step, update, np.array([True, True, True, False]), maxiter=50)
    assert sol.iterations == 2  # stopped at the first repeat, not after 50 factorisations


def test_genuine_cycle_raises():
    prob = _problem()
    step, update = _alternating(-10 * CYCLE_TOL)
    with pytest.raises(ConvergenceError, match="cycles"):
        _loop(prob, None, step, update, np.array([True, True, True, True]), maxiter=50)
