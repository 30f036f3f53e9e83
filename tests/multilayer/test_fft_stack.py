"""Layer stacks in the DC-FFT (cell coefficients from the shared N-layer kernel definition):
N = 1 equals the coating, identical layers equal one, and the FFT converges to the exact method."""

from __future__ import annotations

import math

import pytest

from coathertz.axisym import AxisymMethod
from coathertz.casefile import load_example
from coathertz.fft.method import FFTMethod
from coathertz.materials import RIGID, Body, Layer, Material

QS = ("delta", "a", "p0")


def rel(r, s, qs=QS):
    return max(abs(getattr(r, q) / getattr(s, q) - 1.0) for q in qs)


def test_one_layer_stack_equals_coating():
    """Measured 2.4e-15: the stack kernel equals eq (13) to 1e-14, the rest is the same code."""
    c = load_example("b4c_on_steel")
    b = c.body2
    c1 = c.replace(body2=Body(b.material, None, b.Rx, b.Ry, layers=(Layer(b.coating.material, b.coating.h),)))
    m = FFTMethod(n=64)
    assert rel(m.solve(c1), m.solve(c)) < 1e-9


def test_two_identical_layers_are_one():
    c = load_example("tin_ti_on_steel")
    top, ti = c.body2.layers
    split = (top, Layer(ti.material, 0.2e-6), Layer(ti.material, 0.3e-6))  # the Ti layer in two
    c2 = c.replace(body2=Body(c.body2.material, None, c.body2.Rx, c.body2.Ry, layers=split))
    m = FFTMethod(n=64)
    assert rel(m.solve(c2), m.solve(c)) < 1e-9


@pytest.mark.parametrize("example", ["tin_ti_on_steel", "dlc_crn_cr_on_steel"])
def test_fft_converges_to_exact_method(example):
    """n = 64 -> 128: delta and p0 errors against axisym fall with an observed order >= 1.5
    (measured 2.4 and 1.5-2.2); at n = 128 |d delta|, |d p0| < 5e-5 (measured <= 1.8e-5) and
    |d a| < 1e-3 (measured 3e-4: the FFT's contact-radius estimator)."""
    c = load_example(example)
    ref = AxisymMethod(keep_fields=False).solve(c)
    r64, r128 = FFTMethod(n=64).solve(c), FFTMethod(n=128).solve(c)
    for q in ("delta", "p0"):
        e1, e2 = (abs(getattr(r, q) / getattr(ref, q) - 1.0) for r in (r64, r128))
        order = math.log2(e1 / e2)
        assert order > 1.4 and e2 < 5e-5, f"{q}: errors {e1:.2e} (n = 64), {e2:.2e} (128), order {order:.2f}"
    ea = abs(r128.a / ref.a - 1.0)
    assert ea < 1e-3, f"a at n = 128: {ea:.2e}"


def test_thin_top_layer_of_a_stack_is_flagged():
    """A stack's top layer thinner than a cell is refined like a thin coating (within the memory
    budget), and flagged (meta and warning) where the refinement is off."""
    c = load_example("tin_ti_on_steel")
    b = c.body2
    thin = c.replace(body2=Body(b.material, None, b.Rx, b.Ry,
                                layers=(Layer(b.layers[0].material, 0.05e-6), b.layers[1])))
    with pytest.warns(UserWarning, match="cells thick"):
        r = FFTMethod(n=64, layer_cells=None).solve(thin)
    assert r.meta["layer_cells"] < 0.05
    r = FFTMethod(n=64).solve(thin)
    ref = r.meta.get("layer_refinement")
    assert r.meta["layer_cells"] >= 1.0 and ref["n"] > 64, ref


STEEL = Material(200e9, 0.3)


def _stack(substrate: Material, *layers: tuple[float, float, float, str]):
    """Rigid sphere R = 10 mm, W = 100 N on ``layers`` (E [GPa], nu, h/a0s, interface), top first."""
    from coathertz.case import ContactCase

    steel_case = ContactCase(Body.rigid_sphere(0.01), Body.half_space(STEEL), 100.0)
    a0 = steel_case.a0s
    body = Body(substrate, layers=tuple(Layer(Material(E * 1e9, nu), H * a0, f) for E, nu, H, f in layers))
    return ContactCase(Body.rigid_sphere(0.01), body, 100.0)


@pytest.mark.parametrize("name, case", [
    # a thin stiff top layer (1/6 of the stack): its remainder decays like exp(-2 t h_top/h); the
    # radial table cut at t = 16 (one layer's exp(-2t)) left p0 off by 5.3e-3 and 2.1e-3 at
    # n = 64 and 128 alike (not a discretisation error); now 3.0e-5 and 1.7e-5 at n = 128
    ("4L mixed", lambda: _stack(STEEL, (300, 0.25, 0.1, "bonded"), (30, 0.3, 0.1, "frictionless"),
                                (300, 0.25, 0.2, "bonded"), (100, 0.3, 0.2, "frictionless"))),
    ("4L bonded", lambda: _stack(STEEL, (300, 0.25, 0.1, "bonded"), (30, 0.3, 0.1, "bonded"),
                                 (300, 0.25, 0.2, "bonded"), (100, 0.3, 0.2, "bonded"))),
    # a stack on a rigid base: the grid's first estimate took the top layer as a half-space only
    # from `coating` (None for a stack) and raised "max() arg is an empty sequence"
    ("3L rigid", lambda: _stack(RIGID, (300, 0.25, 0.15, "bonded"),
                                (60, 0.3, 0.2, "frictionless"), (400, 0.2, 0.15, "frictionless"))),
])
def test_fft_agrees_with_exact_on_deep_stacks(name, case):
    """FFT (n = 128) against the exact method: delta and p0 within 2e-4, a within 1e-3 (the
    issue's bounds; measured delta <= 2.4e-5, p0 <= 3.1e-5, a <= 7.1e-4, the a estimator's
    scatter between grids), and delta converging from n = 64 (measured 6-9e-5 there)."""
    c = case()
    ref = AxisymMethod().solve(c)
    err = {n: {q: abs(getattr(FFTMethod(n=n).solve(c), q) / getattr(ref, q) - 1) for q in QS}
           for n in (64, 128)}
    e = err[128]
    assert e["delta"] < 2e-4 and e["p0"] < 2e-4 and e["a"] < 1e-3, f"{name}: {err}"
    assert e["delta"] < err[64]["delta"], f"{name}: delta does not converge: {err}"
