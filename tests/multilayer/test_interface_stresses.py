"""Interface stresses of the ``multilayer`` study (``analyse_interfaces``), from the exact method's
stresses: a stack of one material is Huber's half-space at the interface depths."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.axisym import AxisymMethod
from coathertz.axisym.stresses import AxisymStresses
from coathertz.case import ContactCase
from coathertz.materials import Body, Layer
from coathertz.verification import get_study


def _huber():
    """Huber's field from ``tests/stresses/huber.py`` (independent of the package)."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).parents[1] / "stresses" / "huber.py"
    spec = importlib.util.spec_from_file_location("huber", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.huber


@pytest.fixture(scope="module")
def study():
    return get_study("multilayer")


def test_steel_stack_interfaces_are_huber(study):
    """Two steel layers on steel: the interface maxima are Huber's (Johnson eq 3.44-3.46) at
    z = 3 and 4 um (z/a = 0.098, 0.13). Scan + refinement against Huber's maximum over 20001
    radii: |sigma_rz| within 5e-5 p0 and its radius within 1e-3 a (measured 6e-6 p0, 1e-4 a:
    the exact stresses are at round-off, so this is the scan's own error); sigma_zz < 0 everywhere,
    its largest value the scan's end (2.5 a), to 1e-9 p0; tractions continuous to 1e-12 p0."""
    steel = study.STEEL
    body = Body(steel, layers=(Layer(steel, 3e-6), Layer(steel, 1e-6)))
    case = ContactCase(Body.rigid_sphere(study.R), body, study.W)
    res = AxisymMethod(keep_fields=False).solve(case)
    rows, jump = study.interface_stresses(AxisymStresses(case, res, cut=study.CUT))
    assert jump < 1e-12, jump
    rho = np.linspace(0.0, 2.5, 20001)
    huber = _huber()
    for row in rows:
        zh = row["z"] / res.a
        _, _, sz, trz = huber(rho, zh, 1.0, steel.nu)
        j = int(np.argmax(np.abs(trz)))
        msg = (f"z = {row['z'] * 1e6:g} um: scan |tau| {row['tau_max']:.6f} at {row['r_tau']:.4f} a, "
               f"Huber {abs(trz[j]):.6f} at {rho[j]:.4f} a; sigma_zz {row['szz_max']:.3e} vs {sz[-1]:.3e}")
        assert abs(row["tau_max"] - abs(trz[j])) < 5e-5, msg
        assert abs(row["r_tau"] - rho[j]) < 1e-3, msg
        assert row["r_szz"] == 2.5 and abs(row["szz_max"] - sz[-1]) < 1e-9, msg


def test_peak_is_the_parabola_vertex(study):
    """``_peak``: a parabola's vertex between grid points is found exactly; a maximum at an end of
    the scan stays there."""
    rho = np.linspace(0.0, 1.0, 11)
    v, r = study._peak(rho, 2.0 - (rho - 0.437) ** 2)
    assert abs(v - 2.0) < 1e-14 and abs(r - 0.437) < 1e-14
    assert study._peak(rho, rho) == (1.0, 1.0)


def test_second_field_on_the_same_nodes_reuses_them(study):
    """A field on the xi nodes of the previous one (same depths, same largest radius) reuses the
    nodes' layer coefficients and g^: it equals a fresh evaluation bit for bit, on either side."""
    case = next(sc.case for sc in study.cases("tiny") if sc.id == "Ei=0.25,hi=1um")
    res = AxisymMethod(keep_fields=False).solve(case)
    z = [3e-6, 4e-6]
    r = np.array([0.0, 0.5, 1.0, 2.5]) * res.a
    S = AxisymStresses(case, res)
    S.field(np.linspace(0.0, 2.5, 7) * res.a, z)
    for side in ("below", "above"):
        again = S.field(r, z, side=side).sigma
        fresh = AxisymStresses(case, res).field(r, z, side=side).sigma
        assert np.array_equal(again, fresh), side
    assert S._on_nodes[1], "nothing kept"
