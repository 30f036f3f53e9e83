"""The FE stresses at given points (coathertz.fem.stress_points) against the exact axisymmetric
field (coathertz.axisym.stresses): mesh convergence away from the contact edge."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from coathertz.axisym.method import AxisymMethod
from coathertz.axisym.stresses import AxisymStresses
from coathertz.case import ContactCase
from coathertz.casefile import load_example
from coathertz.errors import CoatHertzError
from coathertz.fem.method import FEMMethod
from coathertz.fem.stress_points import sample

#: Points inside the FE's fine zone (r <= 1.5a, z <= 0.5a) and away from the contact edge
#: (|r - a| >= 0.3a): the graded mesh beyond that zone does not refine with n_a.
RHO = np.array([0.0, 0.25, 0.5, 0.7, 1.3])


def _errors(case, depths_of, n_as):
    res = AxisymMethod().solve(case)
    a, p0, h = res.a, res.p0, case.body2.coating.h
    S = AxisymStresses(case, res)
    r, z = RHO * a, depths_of(a, h)
    exact = S.field(r, z).sigma
    errs, models = [], []
    for n_a in n_as:
        _, model, path = FEMMethod(n_a=n_a).solve_full(case)
        fe = sample(model, path.x, r, z)
        errs.append(np.abs(fe - exact).max() / p0)
        models.append((model, path, fe))
    return np.array(errs), models, (a, p0, h, S)


def test_fem_converges_to_exact_coated():
    """Fig. 3 configuration (rigid sphere, soft bonded coating E = 1/3, h = 0.12a): max |FE -
    exact| / p0 over r = 0..0.7a and 1.3a, z = h/2, h (coating side), 2h, 0.3a, 0.45a. Measured
    at n_a = 10, 20, 40, 80 elements across a: 1.3e-3, 8.9e-4, 3.1e-4, 8.2e-5 (observed order
    0.5, 1.5, 1.9: second order once the coating is resolved)."""
    case = load_example("fig3_soft_coating")
    errs, _, _ = _errors(case, lambda a, h: np.array([0.5 * h, h, 2 * h, 0.3 * a, 0.45 * a]),
                         (20, 40, 80))
    order = math.log2(errs[1] / errs[2])
    assert errs[1] < 0.005 and errs[2] < 0.002, f"max |FE - exact| / p0 at n_a = 20, 40, 80: {errs}"
    assert order > 1.5, f"errors {errs} at n_a = 20, 40, 80: observed order {order:.2f}"


def test_fem_converges_to_exact_rigid_base_frictionless():
    """A steel coating on a rigid base, frictionless interface (h = 0.41a): measured 1.3e-3,
    3.5e-4, 8.6e-5, 2.2e-5 p0 at n_a = 10, 20, 40, 80 (order 1.9, 2.0, 2.0); the FE's shear on
    the base tends to 0 (2.6e-5, 3.9e-6 p0 at n_a = 20, 40: the projection's error)."""
    case = load_example("rigid_substrate")
    coat = dataclasses.replace(case.body2.coating, interface="frictionless")
    case = case.replace(body2=dataclasses.replace(case.body2, coating=coat))
    errs, models, (_, p0, _, _) = _errors(
        case, lambda a, h: np.array([0.25 * h, 0.5 * h, 0.75 * h, h]), (20, 40))
    order = math.log2(errs[0] / errs[1])
    assert errs[1] < 0.005 and order > 1.5, f"errors {errs} at n_a = 20, 40: order {order:.2f}"
    base_shear = [np.abs(fe[-1, 3]).max() / p0 for _, _, fe in models]
    assert base_shear[1] < base_shear[0] < 1e-3, f"FE shear on the frictionless base {base_shear}"


def test_interface_sides_and_bad_points():
    """Both faces of a bonded interface: sigma_rr jumps (the regions' own projections), and the
    tractions agree with the exact ones on either face; points outside the body are refused."""
    case = load_example("fig3_soft_coating")
    res = AxisymMethod().solve(case)
    a, p0, h = res.a, res.p0, case.body2.coating.h
    S = AxisymStresses(case, res)
    _, model, path = FEMMethod(n_a=40).solve_full(case)
    r = RHO * a
    for side in ("above", "below"):
        fe = sample(model, path.x, r, [h], side=side)[0]
        ex = S.field(r, [h], side=side).sigma[0]
        err = np.abs(fe - ex).max() / p0
        assert err < 2e-3, f"{side}: max |FE - exact| / p0 = {err:.2e} (measured 3e-4)"
    up = sample(model, path.x, r, [h], side="above")[0]
    dn = sample(model, path.x, r, [h], side="below")[0]
    assert np.abs(up[0] - dn[0]).max() / p0 > 0.1  # the soft coating's lateral stress jumps
    with pytest.raises(CoatHertzError, match="the meshed body"):
        sample(model, path.x, r, [-1e-6])
    with pytest.raises(CoatHertzError, match="side must be one of"):
        sample(model, path.x, r, [h], side="middle")


@pytest.mark.parametrize(("E", "H"), [(0.25, 0.01), (0.25, 3.0), (4.0, 0.01), (4.0, 3.0)])
def test_fem_fig3_corners(E, H):
    """Default mesh against the exact field on the corners of fig. 3 (rigid sphere 10 mm, 100 N,
    steel substrate, coating E = Ec/Es, h = H a0), at r = 0..0.7a, 1.3a and z = 0.1a, 0.3a,
    0.45a (and h if shallower): measured 2e-4, 3.6e-4, 2.3e-4, 1.8e-4 p0."""
    from coathertz.closedform.hertz import hertz_circular
    from coathertz.materials import Body, Coating, Material

    steel = Material(200e9, 0.3)
    a0 = hertz_circular(100.0, 10e-3, steel.E_star).a0
    case = ContactCase(Body.rigid_sphere(10e-3), Body(steel, Coating(Material(E * 200e9, 0.3), H * a0)),
                       100.0)
    res = AxisymMethod().solve(case)
    a, p0, h = res.a, res.p0, H * a0
    z = np.array([0.1, 0.3, 0.45]) * a
    if h < 0.45 * a:
        z = np.sort(np.append(z, h))
    r = RHO * a
    _, model, path = FEMMethod().solve_full(case)
    err = np.abs(sample(model, path.x, r, z) - AxisymStresses(case, res).field(r, z).sigma).max() / p0
    assert err < 1e-3, f"E = {E}, H = {H}: max |FE - exact| / p0 = {err:.2e}"
