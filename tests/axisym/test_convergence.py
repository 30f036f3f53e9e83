"""Self-convergence of delta, a and p0 with the quadrature sizes: Legendre modes N (the Galerkin
basis) and Gauss nodes per panel of the xi integral; the observed rates are in the messages."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import coated

from coathertz.axisym import AxisymMethod
from coathertz.materials import RIGID

CASES = {
    "soft thin (E=1/4, H=0.01)": coated(0.25, 0.01),
    "stiff thin (E=4, H=0.01)": coated(4.0, 0.01),
    "rigid base, nu_c=0.5, H=0.05": coated(0.0, 0.05, nu_c=0.5, substrate=RIGID),
}
QS = ("delta", "a", "p0")


@pytest.fixture(scope="module")
def references():
    return {k: AxisymMethod(n_modes=160, order=20, decay=30.0).solve(c) for k, c in CASES.items()}


@pytest.mark.parametrize("name", list(CASES))
def test_modes_convergence(name, references):
    """Errors fall geometrically with N (spectral convergence of the Legendre basis): the fitted
    log10(error) per added mode is reported; the defaults are within 1e-8 of the reference."""
    case, ref = CASES[name], references[name]
    Ns = [8, 16, 24, 32]
    for q in QS:
        errs = np.array([abs(getattr(AxisymMethod(n_modes=n).solve(case), q) / getattr(ref, q) - 1)
                         for n in Ns])
        errs = np.maximum(errs, 1e-16)
        rate = np.polyfit(Ns, np.log10(errs), 1)[0]
        msg = f"{name}, {q}: errors {errs} at N = {Ns}; observed rate {rate:.3f} decades per mode"
        assert errs[-1] < 1e-5, msg
        if errs[0] > 1e-12:  # not yet at round-off at the coarsest N
            assert rate < -0.1, msg
    r = AxisymMethod().solve(case)
    for q in QS:
        assert abs(getattr(r, q) / getattr(ref, q) - 1) < 1e-8, (name, q, r.meta["n_modes"])


@pytest.mark.parametrize("name", list(CASES))
def test_xi_quadrature_convergence(name, references):
    """Gauss nodes per panel of the xi rule: spectral convergence, observed decades per node."""
    case, ref = CASES[name], references[name]
    orders = [4, 5, 6, 7]
    n = references[name].meta["n_modes"]
    for q in QS:
        errs = np.array([abs(getattr(AxisymMethod(n_modes=n, order=o).solve(case), q) / getattr(ref, q) - 1)
                         for o in orders])
        errs = np.maximum(errs, 1e-16)
        rate = np.polyfit(orders, np.log10(errs), 1)[0]
        msg = f"{name}, {q}: errors {errs} at order = {orders}; observed rate {rate:.2f} decades per node"
        assert errs[-1] < 1e-6 and rate < -0.5, msg
