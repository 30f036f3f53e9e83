"""Frictionless coating/substrate interface: elastic and rigid
substrate, against the exact axisymmetric method (quoted, branch ``axisym`` commit 36b7740) and
the DC-FFT (``FFTMethod(interface="frictionless")``, used here only as a reference)."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.fem.method import FEMMethod
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)
EXACT = {
    ("E4H0.3", "bonded"): (9.552684500358693e-08, 2.679974904185491e-05, 528007944.4010849),
    ("E4H0.3", "frictionless"): (1.050375265765103e-07, 2.8908022238145368e-05, 431556758.0417738),
    ("E0.25H0.5", "frictionless"): (1.516771581439251e-07, 4.5330124961784384e-05, 254030921.20264825),
    ("rigid H0.3", "bonded"): (3.40972554206399e-08, 2.475531202165743e-05, 923798391.2066553),
    ("rigid H0.3", "frictionless"): (3.7376183822799274e-08, 2.5641003419080564e-05, 845231606.4652389),
}


def _case(name: str) -> ContactCase:
    if name == "rigid H0.3":
        layer = Material(200e9, 0.3)
        c0 = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 1e-6)), 1.0)
        return ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 0.3 * c0.a0c)), 1.0)
    E, H = {"E4H0.3": (4.0, 0.3), "E0.25H0.5": (0.25, 0.5)}[name]
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(E * 200e9, 0.3), 1.0, STEEL)
    return c0.with_thickness(H * c0.a0s)


@pytest.mark.parametrize("name", ["E4H0.3", "E0.25H0.5", "rigid H0.3"])
def test_frictionless_interface_matches_exact_and_fft(name):
    """Coarse mesh, measured against exact: E = 4, H = 0.3: delta -6.7e-5, a -7.8e-5, p0 +2.7e-5;
    E = 1/4, H = 0.5: -2.9e-5, -3.7e-4, +1.2e-4; rigid base, H = 0.3: -2.4e-6, -5.1e-4, +1.2e-4.
    Against the FFT (256^2): delta and p0 within 1.1e-4, a within 1.6e-3 (the FFT's radius bias)."""
    from coathertz.fft.method import FFTMethod

    case = _case(name)
    fe = FEMMethod(mesh="coarse", interface="frictionless").solve(case)
    d, a, p = EXACT[(name, "frictionless")]
    assert fe.delta == pytest.approx(d, rel=2e-4)
    assert fe.a == pytest.approx(a, rel=1e-3)
    assert fe.p0 == pytest.approx(p, rel=3e-4)
    ff = FFTMethod(interface="frictionless").solve(case)
    assert fe.delta == pytest.approx(ff.delta, rel=3e-4)
    assert fe.p0 == pytest.approx(ff.p0, rel=5e-4)
    assert fe.a == pytest.approx(ff.a, rel=3e-3)
    assert fe.meta["settings"]["interface"] == "frictionless"


@pytest.mark.parametrize("name", ["E4H0.3", "rigid H0.3"])
def test_interface_changes_the_answer(name):
    """The frictionless interface is softer: delta +10 % (exact) against bonded; the FE sees it."""
    case = _case(name)
    b = FEMMethod(mesh="coarse").solve(case)
    f = FEMMethod(mesh="coarse", interface="frictionless").solve(case)
    exact_ratio = EXACT[(name, "frictionless")][0] / EXACT[(name, "bonded")][0]
    assert f.delta / b.delta == pytest.approx(exact_ratio, rel=3e-4)
    assert exact_ratio > 1.05


def test_tangential_slip_and_normal_continuity():
    """Elastic substrate: u_z continuous across z = -h, u_r jumps (slip)."""
    case = _case("E4H0.3")
    _, model, path = FEMMethod(mesh="coarse", interface="frictionless").solve_full(case)
    a, b = model.tie
    u = path.x
    assert np.max(np.abs(u[a] - u[b])) <= 1e-10 * np.max(np.abs(u[a]))
    h = model.lm.h
    on = np.nonzero((np.abs(model.z_dof + h) < 1e-9 * model.lm.a_ref) & (model.comp == 0))[0]
    on = on[np.lexsort((on, model.r_dof[on]))].reshape(-1, 2).T
    slip = np.abs(u[on[0]] - u[on[1]])
    assert slip.max() > 0.01 * np.abs(u[a]).max()
