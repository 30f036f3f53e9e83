"""FFT stresses in layer stacks (coathertz.fft.stack_stresses): one layer equals the coating,
identical layers equal one, traction conditions at every interface, and the field against the
exact axisymmetric method with grid convergence."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from coathertz.axisym.method import AxisymMethod
from coathertz.axisym.stresses import AxisymStresses
from coathertz.case import ContactCase
from coathertz.casefile import load_example
from coathertz.errors import CoatHertzError
from coathertz.fft.frf import Layer as CoatLayer
from coathertz.fft.method import FFTMethod
from coathertz.fft.stack_stresses import StackStressFRF
from coathertz.fft.stresses import CoatedStressFRF, contact_stresses
from coathertz.materials import RIGID, Body, Coating, Layer, Material
from coathertz.stack import StackLayer

COAT = Material(210e9, 0.3)
STEEL = Material(200e9, 0.3)
HARD = Material(400e9, 0.25)
AL = Material(70e9, 0.33)
RUBBERY = Material(20e9, 0.5)  # incompressible layer
SUBSTRATES = {"soft": Material(70e9, 0.33), "stiff": Material(400e9, 0.22), "rigid": RIGID}
LOADS = ("normal", "tangential", "antiplane")


def _rows(frf, w, z):
    r = frf.at(w, z, frf.coefficients(w))
    return {k: np.array(getattr(r, k)) for k in LOADS}


def _rel(a, b):
    """Largest difference of two row sets, relative to the rows' size at each ``w`` (a frictionless
    interface's tangential rows grow like 1/(w h) at long waves: a layer carrying the load as a
    membrane)."""
    return max(float(np.max(np.abs(a[k] - b[k]) / np.maximum(1.0, np.abs(b[k]).max(axis=0))))
               for k in LOADS)


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
@pytest.mark.parametrize("sub", list(SUBSTRATES))
def test_one_layer_equals_coating_and_split_layer_equals_one(sub, interface):
    """Against the Papkovich--Neuber coating responses (an independent 6 x 6 solve): measured
    <= 1.7e-14 bonded, <= 1.2e-8 frictionless (at w h <= 1e-4, where the membrane rows reach 1e6
    and both solves lose digits); the coating split 0.3/0.7 likewise (3.8e-8)."""
    substrate = SUBSTRATES[sub]
    h = 1e-5
    w = np.geomspace(1e-4, 60.0, 300) / h
    old = CoatedStressFRF(CoatLayer(COAT, substrate, interface), h)
    one = StackStressFRF((StackLayer(COAT, h, interface),), substrate)
    split = StackStressFRF((StackLayer(COAT, 0.3 * h), StackLayer(COAT, 0.7 * h, interface)), substrate)
    zs = [0.0, 0.2 * h, 0.5 * h, h] + ([] if substrate.is_rigid else [1.01 * h, 3 * h])
    tol = 1e-12 if interface == "bonded" else 1e-6
    for z in zs:
        ref = _rows(old, w, z)
        e1, e2 = _rel(_rows(one, w, z), ref), _rel(_rows(split, w, z), ref)
        assert e1 < tol and e2 < tol, f"z = {z / h:.2f} h: one layer {e1:.2e}, split {e2:.2e}"


MIXED = (StackLayer(HARD, 4e-6, "bonded"), StackLayer(AL, 2e-6, "frictionless"),
         StackLayer(RUBBERY, 3e-6, "bonded"), StackLayer(COAT, 1e-6, "bonded"))


@pytest.mark.parametrize("substrate", [STEEL, RIGID], ids=["elastic", "rigid"])
@pytest.mark.parametrize("last", ["bonded", "frictionless"])
def test_stack_interface_tractions(substrate, last):
    """sigma_zz, sigma_kz, sigma_pz continuous at every interface (both faces: the depth and 1e-9
    of it deeper), sigma_kz = sigma_pz = 0 on both faces of a frictionless one, the surface
    tractions of each load. Measured <= 2.3e-9 (the 1e-9 step times the rows' slope)."""
    layers = (*MIXED[:-1], StackLayer(COAT, 1e-06, last))
    frf = StackStressFRF(layers, substrate)
    w = np.geomspace(1e-3, 40.0, 200) / frf.depth
    coef = frf.coefficients(w)
    top = frf.at(w, 0.0, coef)
    for load, surf in (("normal", (-1.0, 0.0)), ("tangential", (0.0, 1.0))):
        rows = np.array(getattr(top, load))
        assert np.abs(rows[2] - surf[0]).max() < 1e-12 and np.abs(rows[3] - surf[1]).max() < 1e-12
    assert np.abs(np.array(top.antiplane[1]) + 1.0).max() < 1e-12
    bottoms = frf.tops[1:] if not substrate.is_rigid else frf.tops[1:-1]
    for i, zb in enumerate(bottoms):
        up, down = frf.at(w, zb, coef), frf.at(w, zb * (1 + 1e-9), coef)
        scale = 1e-6  # of the unit load; the 1e-9 step moves the rows by ~1e-9 of their slope
        for load in ("normal", "tangential"):
            u, d = np.array(getattr(up, load)), np.array(getattr(down, load))
            big = np.maximum(1.0, np.abs(u).max(axis=0))
            assert np.max(np.abs(u[2:] - d[2:]) / big) < scale, f"interface {i + 1}, {load}"
            if layers[i].interface == "frictionless":
                assert np.max(np.abs(u[3]) / big) < scale and np.max(np.abs(d[3]) / big) < scale
        ua, da = np.array(up.antiplane[1]), np.array(down.antiplane[1])
        assert np.max(np.abs(ua - da)) < scale, f"interface {i + 1}, antiplane"
        if layers[i].interface == "frictionless":
            assert np.abs(ua).max() < scale and np.abs(da).max() < scale
    if substrate.is_rigid and last == "frictionless":  # no shear on a frictionless base either
        bot = frf.at(w, frf.depth, coef)
        assert np.abs(np.array(bot.normal[3])).max() < 1e-8
        assert np.abs(np.array(bot.antiplane[1])).max() < 1e-8


def _stack_case(layers, substrate=STEEL, W=100.0) -> ContactCase:
    return ContactCase(Body.rigid_sphere(10e-3), Body(substrate, layers=layers), W)


def test_field_identities_and_interface_tractions():
    """Through the contact solution (64^2, sliding mu = 0.3): a one-layer stack equals the coating
    (measured 4.9e-13 p0), the coating in two identical layers equals one layer (5.7e-13 p0), and
    in the 3-D field of a mixed stack sigma_zz, sigma_xz, sigma_yz are continuous at each
    interface and the shear is zero on both faces of the frictionless one (measured <= 3.2e-10
    p0: the 1e-9 step between the faces times the field's slope)."""
    m = FFTMethod(n=64)
    coat = Coating(HARD, 60e-6)
    c0 = ContactCase(Body.rigid_sphere(10e-3), Body(STEEL, coat), 100.0)
    c1 = _stack_case((Layer(HARD, 60e-6),))
    c2 = _stack_case((Layer(HARD, 25e-6), Layer(HARD, 35e-6)))
    r0 = m.solve(c0)
    p0 = r0.p0
    z = np.array([0.0, 20e-6, 60e-6, 90e-6, 200e-6])
    s0 = contact_stresses(c0, r0, depths=z, mu=0.3).sigma
    s1 = contact_stresses(c1, m.solve(c1), depths=z, mu=0.3).sigma
    s2 = contact_stresses(c2, m.solve(c2), depths=z, mu=0.3).sigma
    e1, e2 = np.abs(s1 - s0).max() / p0, np.abs(s2 - s0).max() / p0
    assert e1 < 1e-9 and e2 < 1e-9, f"one layer {e1:.2e} p0, two identical layers {e2:.2e} p0"
    layers = (Layer(HARD, 30e-6), Layer(AL, 20e-6, "frictionless"), Layer(RUBBERY, 25e-6))
    case = _stack_case(layers)
    res = m.solve(case)
    zb = np.cumsum([L.h for L in layers])
    F = contact_stresses(case, res, depths=np.ravel(np.c_[zb, zb * (1 + 1e-9)]), mu=0.3)
    for i, L in enumerate(layers):
        up, down = F.sigma[2 * i], F.sigma[2 * i + 1]
        jump = np.abs(up[[2, 3, 4]] - down[[2, 3, 4]]).max() / res.p0
        assert jump < 1e-8, f"interface {i + 1}: traction jump {jump:.2e} p0"
        if L.interface == "frictionless":
            shear = max(np.abs(up[[3, 4]]).max(), np.abs(down[[3, 4]]).max()) / res.p0
            assert shear < 1e-8, f"interface {i + 1} (frictionless): shear {shear:.2e} p0"
    # the in-plane stresses do jump (different materials): the check above is not vacuous
    assert np.abs(F.sigma[0, 0] - F.sigma[1, 0]).max() / res.p0 > 0.01


EXACT_STACKS = {
    "tin_ti": lambda: load_example("tin_ti_on_steel"),
    "frictionless_nu05": lambda: _stack_case((Layer(HARD, 50e-6, "frictionless"),
                                              Layer(Material(70e9, 0.5), 80e-6))),
    "rigid_base": lambda: _stack_case((Layer(STEEL, 60e-6), Layer(AL, 100e-6, "frictionless")),
                                      substrate=RIGID),
}


def _errors_against_exact(case: ContactCase, ns) -> tuple[np.ndarray, dict]:
    """Max |FFT - exact| / p0 per depth on the row y = 0, 0 <= x <= 2a, away from interfaces:
    0.1a, the middle of each layer, 0.5a and a (elastic substrate)."""
    res = AxisymMethod().solve(case)
    a, p0 = res.a, res.p0
    hs = np.array([L.h for L in case.body2.layers])
    z = [0.1 * a, *(np.cumsum(hs) - hs / 2)]
    if not case.body2.material.is_rigid:
        z += [0.5 * a, a]
    z = np.unique(z)
    exact = AxisymStresses(case, res)
    errs = {}
    for n in ns:
        rf = FFTMethod(n=n).solve(case)
        F = contact_stresses(case, rf, depths=z)
        j = int(np.argmin(np.abs(F.y)))
        sel = (F.x >= 0) & (F.x <= 2 * a)
        ref = exact.field(F.x[sel], z).voigt()[:, :, 0, :]
        errs[n] = np.abs(F.sigma[:, :, j, :][:, :, sel] - ref).max(axis=(1, 2)) / p0
    return z / a, errs


def _message(name, zr, errs) -> str:
    ns = sorted(errs)
    lines = [f"{name}: max |FFT - exact| / p0 at z/a = {np.round(zr, 3)}"]
    lines += [f"  n = {n}: {' '.join(f'{e:.2e}' for e in errs[n])}" for n in ns]
    for n1, n2 in itertools.pairwise(ns):
        lines.append(f"  observed order {n1} -> {n2}: {np.round(np.log2(errs[n1] / errs[n2]), 2)}")
    return "\n".join(lines)


@pytest.mark.parametrize("name", list(EXACT_STACKS))
def test_stack_field_against_exact(name):
    """FFT (64^2, 128^2, default period) against the exact field. Measured at 128^2 (max over
    depths): tin_ti 2.7e-3 (z = 0.05a, 2.4 cells), frictionless/nu = 0.5 4.1e-4, rigid base
    4.1e-4 p0; near the surface the error falls like dx^2 (observed orders at 0.1a 1.8, 2.0,
    2.9), deep down it stops at the period's floor (1e-4 level)."""
    zr, errs = _errors_against_exact(EXACT_STACKS[name](), (64, 128))
    msg = _message(name, zr, errs)
    assert errs[128].max() < 0.005, msg
    assert math.log2(errs[64][0] / errs[128][0]) > 1.4, msg


@pytest.mark.slow
@pytest.mark.parametrize("name", list(EXACT_STACKS))
def test_stack_field_converges_to_exact(name):
    """64 / 128 / 256: the error falls at every depth until the period's floor, second order
    near the surface (measured at 0.1a: tin_ti 9.3e-3, 2.7e-3, 6.3e-4; frictionless/nu = 0.5
    1.6e-3, 4.1e-4, 9.1e-5; rigid base 3.0e-3, 4.1e-4, 3.7e-4 p0 (there the floor of the
    frictionless base's long-range membrane field is reached at 128^2: 2.4e-4 with pad 8)."""
    zr, errs = _errors_against_exact(EXACT_STACKS[name](), (64, 128, 256))
    msg = _message(name, zr, errs)
    assert errs[256].max() < 0.001, msg
    assert np.all(errs[256] <= 1.1 * errs[128]) and np.all(errs[128] <= 1.1 * errs[64]), msg
    assert math.log2(errs[64][0] / errs[128][0]) > 1.4, msg


def test_stack_bad_input():
    """One clear line: a depth below a rigid base, an interface= setting on a stack."""
    case = _stack_case((Layer(STEEL, 60e-6), Layer(AL, 100e-6)), substrate=RIGID)
    res = FFTMethod(n=32).solve(case)
    with pytest.raises(CoatHertzError, match="rigid substrate"):
        contact_stresses(case, res, depths=[200e-6])
    with pytest.raises(CoatHertzError, match="set per layer"):
        contact_stresses(case, res, depths=[10e-6], interface="frictionless")
    with pytest.raises(CoatHertzError, match="layer 2 thickness"):
        StackStressFRF((StackLayer(STEEL, 1e-6), StackLayer(AL, 0.0)), STEEL)


@pytest.mark.slow
def test_cli_fft_stack_matches_axisym(capsys):
    """``coathertz stresses`` on a two-layer stack with ``--method fft`` (128^2) and ``axisym``:
    measured |difference| of the von Mises maxima 2.4e-5 p0, interface shear 1.8e-5 p0 (both on
    the lower interface at 25 um), surface tension 2.2e-3 p0 (the FFT's cells at the edge)."""
    import json

    from coathertz.cli import main

    base = ["--substrate", "200 GPa,0.3", "--W", "100 N", "--R", "10 mm",
            "--coating", "300 GPa,0.2,10 um", "--coating", "150 GPa,0.3,15 um"]
    d = {}
    for m in ("axisym", "fft"):
        assert main(["stresses", *base, "--method", m, "--json"]) == 0
        d[m] = json.loads(capsys.readouterr().out)
    ax, ff = d["axisym"], d["fft"]
    for k in ("vm_max", "vm_max_coating", "vm_max_substrate", "interface_shear_max"):
        assert ff[k]["over_p0"] == pytest.approx(ax[k]["over_p0"], abs=2e-4), k
    assert ff["interface_shear_max"]["at"][2] == pytest.approx(25e-6)
    assert ff["tensile_max_surface"]["over_p0"] == pytest.approx(
        ax["tensile_max_surface"]["over_p0"], abs=0.01)
