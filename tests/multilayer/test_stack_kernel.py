"""The N-layer kernel definition (``coathertz.stack``): identities and the one-layer closed
forms of eq (13) and the frictionless/rigid-substrate forms of ``coathertz.axisym.kernel``."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.axisym.kernel import layer_factor_bonded, layer_factor_frictionless, stack_factor
from coathertz.errors import CoatHertzError
from coathertz.materials import RIGID, Body, Layer, Material
from coathertz.stack import StackLayer, stack_layer_factor

STEEL = Material(200e9, 0.3)
T = np.logspace(-8, 2.5, 80)  # k h of the top layer
COATINGS = [Material(800e9, 0.25), Material(50e9, 0.45), Material(300e9, 0.5), Material(2e9, 0.3)]

#: Absolute tolerance on F (F is O(1); measured <= 5.3e-15: Plücker coordinates, bounded steps).
TOL = 1e-12


@pytest.mark.parametrize("coating", COATINGS, ids=lambda m: f"E{m.E / 1e9:g}nu{m.nu:g}")
@pytest.mark.parametrize("substrate", [STEEL, RIGID], ids=["elastic", "rigid"])
@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_one_layer_equals_closed_form(coating, substrate, interface):
    ref = (layer_factor_bonded if interface == "bonded" else layer_factor_frictionless)(coating, substrate)
    F = stack_layer_factor([StackLayer(coating, 1.0, interface)], substrate, T)
    err = np.abs(F - ref(T)).max()
    assert err < TOL, f"N = 1 vs closed form: max |dF| = {err:.2e}"


@pytest.mark.parametrize("substrate", [STEEL, RIGID], ids=["elastic", "rigid"])
@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_two_identical_layers_are_one(substrate, interface):
    c = Material(400e9, 0.22)
    one = stack_layer_factor([StackLayer(c, 1.0, interface)], substrate, T)
    two = stack_layer_factor([StackLayer(c, 0.3), StackLayer(c, 0.7, interface)], substrate, T)
    err = np.abs(one - two).max()
    assert err < TOL, f"h = 0.3 + 0.7 vs h = 1: max |dF| = {err:.2e}"


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_layer_of_substrate_material_adds_nothing(interface):
    c = Material(600e9, 0.2)
    one = stack_layer_factor([StackLayer(c, 1.0, interface)], STEEL, T)
    two = stack_layer_factor([StackLayer(c, 1.0, interface), StackLayer(STEEL, 2.0)], STEEL, T)
    err = np.abs(one - two).max()
    assert err < TOL, f"extra steel layer on steel: max |dF| = {err:.2e}"


@pytest.mark.parametrize("where", [0, 1, 2])
def test_zero_thickness_bonded_layer_adds_nothing(where):
    base = [StackLayer(Material(300e9, 0.25), 1.0), StackLayer(Material(100e9, 0.35), 0.5)]
    ref = stack_layer_factor(base, STEEL, T)
    layers = list(base)
    layers.insert(where, StackLayer(Material(5e9, 0.49), 0.0))
    F = stack_layer_factor(layers, STEEL, T) if where else None
    if where == 0:  # a zero-thickness top layer changes E_top*: compare the compliance F / E_top*
        F = stack_layer_factor(layers, STEEL, T) * base[0].material.E_star / layers[0].material.E_star
    err = np.abs(F - ref).max()
    assert err < TOL, f"zero-thickness layer at position {where}: max |dF| = {err:.2e}"


@pytest.mark.parametrize("substrate", [STEEL, RIGID], ids=["elastic", "rigid"])
def test_limits_of_a_three_layer_stack(substrate):
    """``F -> 1`` (top layer as a half-space) for ``kh -> inf``; ``F -> E_1*/E_s*`` (0 on a rigid
    base) for ``kh -> 0``: the substrate, through a stack of vanishing thickness."""
    top = Material(300e9, 0.2)
    layers = [StackLayer(top, 1.0), StackLayer(Material(20e9, 0.5), 0.3, "frictionless"),
              StackLayer(Material(900e9, 0.25), 2.0)]
    F = stack_layer_factor(layers, substrate, np.array([1e-9, 200.0]))
    F0 = 0.0 if substrate.is_rigid else top.E_star / substrate.E_star
    assert abs(F[1] - 1.0) < 1e-13, F
    assert abs(F[0] - F0) < 1e-7, f"long-wave limit {F[0]!r} vs {F0!r}"


@pytest.mark.parametrize("layers,text", [
    ([], "stack is empty"),
    ([StackLayer(STEEL, 1.0), StackLayer(STEEL, -1.0)], "layer 2 thickness h must be >= 0 m"),
    ([StackLayer(STEEL, 1.0, "glued")], "layer 1 interface must be one of"),
    ([StackLayer(RIGID, 1.0)], "layer 1 must be elastic"),
])
def test_bad_stack_is_one_clear_line(layers, text):
    with pytest.raises(CoatHertzError, match=text) as exc:
        stack_layer_factor(layers, STEEL, T)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("example", ["dlc_crn_cr_on_steel", "tin_ti_on_steel", "graded_on_steel"])
def test_axisym_stack_table_matches_direct(example):
    """The exact method's interpolation table of a stack's F equals direct evaluation to 1e-13
    (measured <= 1.4e-14) from kh = 1e-14 to 1e3, and is used (not the fallback)."""
    from coathertz.axisym.kernel import stack_factor
    from coathertz.casefile import load_example

    body = load_example(example).body2
    Ft, _ = stack_factor(body)
    Fd, _ = stack_factor(body, table=False)
    t = np.exp(np.random.default_rng(0).uniform(np.log(1e-14), np.log(1e3), 3000))
    assert Ft.ok
    err = np.abs(Ft(t) - Fd(t)).max()
    assert err < 1e-13, f"table vs direct: {err:.2e}"


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_deep_bottom_layer_acts_as_substrate(interface):
    """A bottom layer 1000 times the top one is the substrate for k h_top >= 0.02 (its own depth is
    then >= 20 decay lengths): equals the one-coating closed form on that material."""
    c, mid = Material(500e9, 0.2), Material(90e9, 0.4)
    t = np.logspace(np.log10(0.02), 2, 40)
    F = stack_layer_factor([StackLayer(c, 1.0, interface), StackLayer(mid, 1000.0)], STEEL, t)
    ref = (layer_factor_bonded if interface == "bonded" else layer_factor_frictionless)(c, mid)(t)
    err = np.abs(F - ref).max()
    assert err < TOL, f"deep layer vs substrate: {err:.2e}"


def test_random_stacks_build_their_kernel_table():
    """200 seeded random stacks (1-4 layers, moduli 1/10-10 of steel, nu 0.2-0.5, 30 % of the
    interfaces frictionless, a fifth on a rigid base): the exact method's kernel table builds.
    It used to evaluate F at k = 0 exactly (an unused F0), where the 4 x 2 surface system of a
    stack with a frictionless interface is singular: 2-5 of these 200 raised LinAlgError.
    Near 0, F approaches its closed-form limit E_top*/E_s* (0 on a rigid base) linearly."""
    steel = Material(200e9, 0.3)
    rng = np.random.default_rng(5)
    for _ in range(200):
        nl = int(rng.integers(1, 5))
        E = 200e9 * 10.0 ** rng.uniform(-1.0, 1.0, nl)
        H = 10.0 ** rng.uniform(-2.0, 0.5, nl) * 1e-4
        nu = rng.uniform(0.2, 0.5, nl)
        fr = rng.random(nl) < 0.3
        sub = steel if rng.random() < 0.8 else RIGID
        body = Body(sub, layers=tuple(
            Layer(Material(float(e), float(v)), float(h), "frictionless" if f else "bonded")
            for e, h, v, f in zip(E, H, nu, fr, strict=True)))
        F, h_min = stack_factor(body)
        F0 = 0.0 if sub.is_rigid else body.layers[0].material.E_star / steel.E_star
        t_tot = 1e-6 * sum(L.h for L in body.layers) / h_min  # k * (total thickness) at t = 1e-6
        assert abs(float(F(np.array([1e-6]))[0]) - F0) < 50 * t_tot, body


def test_thin_incompressible_layer_on_rigid_base_keeps_its_digits():
    """A bonded incompressible layer on a rigid base has ``F ~ (2/3) t^3`` (kernel module), a
    cancellation of order-one terms. The transfer-matrix step errs by ~1e-16 t absolute (relative
    ``~ 1e-15 / t^2``; measured 4.8e-10 at t = 1e-3, 1.6e-8 at 1e-4, 2.3e-6 at 1e-5); the former
    null-space form erred by ~1e-16 absolute (2.4e-7, 2.0e-5, 0.14)."""
    c = Material(300e9, 0.5)
    t = np.logspace(-5, -1, 25)
    F = stack_layer_factor([StackLayer(c, 1.0)], RIGID, t)
    ref = layer_factor_bonded(c, RIGID)(t)
    err = np.abs(F / ref - 1.0) * t**2
    assert err.max() < 1e-14, f"relative error of F ~ t^3 times t^2: {err.max():.2e}"


@pytest.mark.parametrize("substrate", [STEEL, RIGID], ids=["elastic", "rigid"])
def test_steps_agree_where_they_meet(substrate, monkeypatch):
    """The three steps through a layer (transfer matrix below |kh| = T_THIN, bounded basis above,
    the layer's own half-space from Re kh = T_DEEP) give the same F where each could serve: moving
    the switches changes a 3-layer stack's F by round-off only (measured <= 1.3e-14); complex k
    with zero imaginary part gives the real values to round-off (3.3e-15; analytic continuation)."""
    from coathertz import stack

    layers = [StackLayer(Material(300e9, 0.2), 1.0), StackLayer(Material(20e9, 0.5), 0.5, "frictionless"),
              StackLayer(Material(900e9, 0.25), 2.0)]
    k = np.logspace(-2, 2.5, 200)
    ref = stack_layer_factor(layers, substrate, k)
    for thin, deep in ((0.3, 25.0), (3.0, 25.0), (1.0, 22.0), (1.0, 60.0)):
        monkeypatch.setattr(stack, "T_THIN", thin)
        monkeypatch.setattr(stack, "T_DEEP", deep)
        err = np.abs(stack_layer_factor(layers, substrate, k) - ref).max()
        assert err < 1e-13, f"switches at |kh| = {thin}, Re kh = {deep}: max |dF| = {err:.2e}"
    monkeypatch.undo()
    Fc = stack_layer_factor(layers, substrate, k + 0j)
    assert np.abs(Fc - ref).max() < 1e-14 and np.abs(Fc.imag).max() == 0.0


def test_table_long_wave_end_is_the_chord_to_the_exact_limit():
    """Below ``k h_total = 1e-8`` the table uses the chord from the exact limit ``E_1*/E_s*`` (0 on
    a rigid base): no direct evaluation per call (a thin stack's small xi nodes used to cost one
    kernel evaluation each), and it equals direct evaluation to 1e-13 of max(|F|, 1) from
    kh_min = 1e-18 up, for a 1 nm layer over 10 um (thickness ratio 1e4; measured <= 3.1e-15)."""
    for sub in (STEEL, RIGID):
        body = Body(sub, layers=(Layer(Material(800e9, 0.3), 1e-9),
                                 Layer(Material(30e9, 0.45), 1e-5, "frictionless")))
        Ft, _ = stack_factor(body)
        Fd, _ = stack_factor(body, table=False)
        assert Ft.ok, Ft.err
        calls = []
        Ft.F_direct = calls.append  # any direct evaluation is recorded (and fails the test)
        t = np.logspace(-18, np.log10(Ft.t_min) - 1e-9, 60)
        got = Ft(t)
        assert not calls
        ref = Fd(t)
        err = np.max(np.abs(got - ref) / np.maximum(np.abs(ref), 1.0))
        assert err < 1e-13, f"chord vs direct below t_min = {Ft.t_min:.1e}: {err:.2e}"
