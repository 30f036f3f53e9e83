"""Layer stacks in the FE model (``fem``): the mesh puts element edges on every interface, the
identities hold to the FE's discretisation, and the FE agrees with the exact method (axisym, the
arbiter) on stacks of 2-4 layers: bonded and frictionless interfaces, elastic and rigid
substrate, neighbour modulus ratios 1/10-10, incompressible layers (mixed u-p form).

Errors against axisym measured with this code (``FEMMethod``, mesh levels coarse n_a = 20,
default 40, fine 100; relative, delta / a / p0):

=====================  ===========================  ===========================  ===========================
case                   coarse                       default                      fine (slow test)
=====================  ===========================  ===========================  ===========================
2L bonded 10:1         -5.5e-5 / +2.5e-4 / +3.6e-5  -1.3e-5 / -1.8e-5 / +3.6e-5  +4.0e-7 / -2.9e-5 / +1.4e-5
2L frictionless 1:10   -3.8e-5 / -5.6e-4 / +1.2e-4  -1.5e-5 / -2.4e-4 / +2.6e-5  -5.7e-6 / -6.4e-5 / +5.4e-6
3L rigid bonded        -5.7e-6 / -6.3e-5 / +1.1e-4  +1.5e-6 / -8.9e-5 / +2.6e-5  -1.8e-7 / -9.6e-5 / +5.9e-6
3L rigid frictionless  +3.2e-6 / +1.1e-4 / +1.2e-4  -2.3e-6 / -1.1e-4 / +2.5e-5  -1.9e-6 / -5.8e-6 / +6.7e-6
4L mixed interfaces    -6.6e-5 / +8.2e-4 / +3.5e-5  -2.2e-5 / +1.8e-4 / +2.4e-5  -8.6e-6 / +4.0e-5 / +4.4e-6
=====================  ===========================  ===========================  ===========================

The default suite checks the default mesh against the issue's bounds (delta and p0 within 2e-4,
a within 0.1 %: margins of 5x or more there) and that the error falls from coarse to default; the
slow test adds the fine level and the observed orders.
"""

from __future__ import annotations

import itertools
import math
from functools import cache

import numpy as np
import pytest

from coathertz.axisym import AxisymMethod
from coathertz.case import ContactCase
from coathertz.casefile import load_example
from coathertz.errors import CoatHertzError
from coathertz.fem.mesh import MESH_LEVELS, build_mesh, grids, mesh_size
from coathertz.fem.method import FEMMethod, axisymmetric_equivalent
from coathertz.materials import RIGID, Body, Coating, Layer, Material

STEEL = Material(200e9, 0.3)
R, W = 0.01, 100.0
A0 = ContactCase(Body.rigid_sphere(R), Body.half_space(STEEL), W).a0s  # Hertz radius on steel
QS = ("delta", "a", "p0")
#: The issue's agreement bounds: delta and p0 within 2e-4, a within 0.1 %.
BOUND = {"delta": 2e-4, "a": 1e-3, "p0": 2e-4}
N_A = {"coarse": 20, "default": 40, "fine": 100}
#: Below this the FE error against axisym is at its floor and no fall from coarse to default is
#: asked (the two levels differ in growth as well as n_a). Measured: the outer boundary's
#: point-load field, which ignores the layers, biases delta by ~1e-5 at L = 160; the contact
#: radius estimator scatters by ~1e-4 between meshes; p0 of "2L bonded 10:1" stays at 3.6e-5
#: from coarse to default (also at L = 640: not the far field) and falls at n_a = 60 (2.3e-5)
#: and 100 (1.4e-5).
FLOOR = {"delta": 1e-5, "a": 2e-4, "p0": 4e-5}


def stack(substrate: Material, *layers: tuple[float, float, float, str]) -> ContactCase:
    """Rigid sphere R = 10 mm, W = 100 N on ``layers`` = (E [GPa], nu, h / a0s, interface), top first."""
    body = Body(substrate, layers=tuple(Layer(Material(E * 1e9, nu), H * A0, f) for E, nu, H, f in layers))
    return ContactCase(Body.rigid_sphere(R), body, W)


CASES = {
    "2L bonded 10:1": lambda: stack(STEEL, (1000, 0.25, 0.2, "bonded"), (100, 0.3, 0.3, "bonded")),
    "2L frictionless 1:10": lambda: stack(STEEL, (40, 0.3, 0.3, "frictionless"), (400, 0.25, 0.2, "bonded")),
    "3L rigid bonded": lambda: stack(RIGID, (200, 0.3, 0.2, "bonded"), (20, 0.25, 0.2, "bonded"),
                                     (200, 0.3, 0.1, "bonded")),
    "3L rigid frictionless": lambda: stack(RIGID, (300, 0.25, 0.15, "bonded"), (60, 0.3, 0.2, "frictionless"),
                                           (400, 0.2, 0.15, "frictionless")),
    "4L mixed interfaces": lambda: stack(STEEL, (300, 0.25, 0.1, "bonded"), (30, 0.3, 0.1, "frictionless"),
                                         (300, 0.25, 0.2, "bonded"), (100, 0.3, 0.2, "frictionless")),
    "2L incompressible top": lambda: stack(STEEL, (100, 0.5, 0.2, "bonded"),
                                           (1000, 0.25, 0.2, "frictionless")),
    "3L rigid incompressible mid": lambda: stack(RIGID, (400, 0.25, 0.1, "bonded"), (40, 0.5, 0.2, "bonded"),
                                                 (200, 0.3, 0.1, "bonded")),
}


@cache
def exact(name: str):
    c = load_example(name) if name in ("tin_ti_on_steel", "dlc_crn_cr_on_steel") else CASES[name]()
    return AxisymMethod(keep_fields=False).solve(c)


@cache
def fe(name: str, mesh: str):
    c = load_example(name) if name in ("tin_ti_on_steel", "dlc_crn_cr_on_steel") else CASES[name]()
    return FEMMethod(mesh=mesh).solve(c)


def err(r, s, q: str) -> float:
    return abs(getattr(r, q) / getattr(s, q) - 1.0)


def half_space(substrate: Material, layers=(), coating=None) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R), Body(substrate, coating, layers=layers), W)


# --- the mesh ---------------------------------------------------------------------------------
@pytest.mark.parametrize("level", ["coarse", "default"])
@pytest.mark.parametrize("rigid", [False, True])
def test_mesh_has_an_edge_line_on_every_interface_and_resolves_every_layer(level, rigid):
    """Each interface depth is a grid point; each layer has at least n_coat elements, and a layer
    starting in the fine zone at least ceil(h_i / min(s0, edge h_i / n_a)) (the coating's rules);
    adjacent intervals within the growth factor (measured <= 1.49 at growth 1.4)."""
    spec = MESH_LEVELS[level]
    hs = (0.05, 0.5, 0.01, 0.2)  # units of a_ref: thin, thick, very thin (below t_fine), thin
    _, t = grids(1.0, hs, spec, rigid)
    s0 = 1.0 / spec.n_a
    d = np.concatenate([[0.0], np.cumsum(hs)])
    for i, h_i in enumerate(hs):
        k0, k1 = (int(np.argmin(np.abs(t - x))) for x in d[i : i + 2])
        assert abs(t[k0] - d[i]) < 1e-12 and abs(t[k1] - d[i + 1]) < 1e-12, f"layer {i + 1}: no edge line"
        need = spec.n_coat
        if d[i] < spec.t_fine:
            s_c = min(s0, spec.edge * h_i / spec.n_a)
            need = max(need, math.ceil(min(h_i, spec.t_fine - d[i]) / s_c - 1e-9))
        assert k1 - k0 >= need, f"layer {i + 1}: {k1 - k0} elements through it, need {need}"
    dt = np.diff(t)
    worst = float(np.max(np.maximum(dt[1:] / dt[:-1], dt[:-1] / dt[1:])))
    assert worst <= 1.1 * spec.growth, f"adjacent size ratio {worst:.3g} > 1.1 x growth {spec.growth}"
    assert (t[-1] == pytest.approx(sum(hs), rel=1e-12)) if rigid else (t[-1] > 100 * sum(hs))
    size = mesh_size(1.0, hs, spec, rigid)
    assert size.n_t_layers == tuple(int(np.sum((t[1:] > a) & (t[1:] <= b * (1 + 1e-12))))
                                    for a, b in itertools.pairwise(d))


def test_mesh_of_random_stacks():
    """60 random stacks (2-6 layers, h_i / a_ref from 1e-4 to 10, elastic or rigid substrate,
    every mesh level): an edge line on every interface, >= n_coat elements through every layer,
    adjacent depth intervals within a factor 2 (measured <= 1.52; the mesh guard refuses > 4)."""
    rng = np.random.default_rng(19)
    worst = 1.0
    for k in range(60):
        hs = tuple(10 ** rng.uniform(-4, 1, int(rng.integers(2, 7))))
        rigid = bool(rng.integers(0, 2))
        spec = MESH_LEVELS[("coarse", "default", "fine")[k % 3]]
        _, t = grids(1.0, hs, spec, rigid)
        d = np.concatenate([[0.0], np.cumsum(hs)])
        k_at = [int(np.argmin(np.abs(t - x))) for x in d]
        assert np.allclose(t[k_at], d, rtol=1e-12, atol=0), f"{hs}: interfaces off the grid"
        assert min(np.diff(k_at)) >= spec.n_coat, f"{hs}: elements per layer {np.diff(k_at)}"
        dt = np.diff(t)
        worst = max(worst, float(np.max(np.maximum(dt[1:] / dt[:-1], dt[:-1] / dt[1:]))))
    assert worst <= 2.0, f"largest adjacent depth-interval ratio {worst:.3g}"


def test_mesh_regions_and_frictionless_node_sets():
    """Per-layer element sets, top first; every frictionless interface over an elastic body has
    its own second node row (none for the frictionless bottom face on a rigid base)."""
    spec = MESH_LEVELS["coarse"]
    hs, ifs = (0.1, 0.2, 0.05), ("frictionless", "bonded", "frictionless")
    bonded = build_mesh(1.0, hs, spec)
    fr = build_mesh(1.0, hs, spec, interface=ifs)
    n_r = len(np.unique(bonded.mesh.p[0]))
    assert fr.mesh.p.shape[1] - bonded.mesh.p.shape[1] == 2 * n_r  # two duplicated node rows
    rigid = build_mesh(1.0, hs, spec, rigid_base=True, interface=ifs)
    rigid_b = build_mesh(1.0, hs, spec, rigid_base=True)
    assert rigid.mesh.p.shape[1] - rigid_b.mesh.p.shape[1] == n_r  # the bottom face is not split
    assert rigid.split_depths() == pytest.approx((0.1,)) and rigid.bottom_interface == "frictionless"
    zc = fr.mesh.p[1, fr.mesh.t].mean(axis=0)
    tops = (0.0, 0.1, 0.3)
    for els, top, h in zip(fr.layers, tops, hs, strict=True):
        assert len(els) and np.all((zc[els] < -top) & (zc[els] > -(top + h)))
    assert sum(len(x) for x in fr.layers) == len(fr.coating)
    assert len(fr.coating) + len(fr.substrate) == fr.n_elements
    with pytest.raises(CoatHertzError, match="layer 2 interface must be"):
        build_mesh(1.0, hs, spec, interface=("bonded", "glued", "bonded"))
    with pytest.raises(CoatHertzError, match="layer 3 thickness must be"):
        build_mesh(1.0, (0.1, 0.2, -1.0), spec)


# --- identities -------------------------------------------------------------------------------
TOP, MID = Material(800e9, 0.25), Material(100e9, 0.3)


@pytest.mark.parametrize(("substrate", "coat"), [
    (STEEL, Coating(TOP, 0.3 * A0)),
    (STEEL, Coating(TOP, 0.3 * A0, "frictionless")),
    (RIGID, Coating(TOP, 0.3 * A0)),
    (RIGID, Coating(TOP, 0.3 * A0, "frictionless")),
    (STEEL, Coating(Material(100e9, 0.5), 0.3 * A0)),  # mixed u-p layer
])
def test_one_layer_stack_is_the_coating(substrate, coat):
    """Same mesh, same regions, same numbers: equal to round-off (measured: bit for bit)."""
    m = FEMMethod(mesh="coarse")
    rc = m.solve(half_space(substrate, coating=coat))
    rs = m.solve(half_space(substrate, layers=(Layer(coat.material, coat.h, coat.interface),)))
    assert rs.meta["dofs"] == rc.meta["dofs"]
    for q in QS:
        assert err(rs, rc, q) <= 1e-12, f"{q}: {err(rs, rc, q):.2e}"


#: The identities below compare two different meshes of one body (the stack's has an extra edge
#: line and its own depth grading): they hold to the coarse mesh's discretisation error, which on
#: these bodies is <= 9e-5 (delta), 4.2e-4 (a), 1.1e-4 (p0) against axisym (measured). Measured
#: differences: <= 1.2e-5 (delta), 1.0e-4 (a), 8.7e-6 (p0); the bounds are that error's size.
IDENTITY = {"delta": 5e-5, "a": 4e-4, "p0": 5e-5}
IDENTITIES = {
    "substrate-material layer": (
        lambda: half_space(STEEL, (Layer(TOP, 0.3 * A0), Layer(STEEL, 0.2 * A0))),
        lambda: half_space(STEEL, coating=Coating(TOP, 0.3 * A0))),
    "coating in two": (
        lambda: half_space(STEEL, (Layer(TOP, 0.15 * A0), Layer(TOP, 0.15 * A0))),
        lambda: half_space(STEEL, coating=Coating(TOP, 0.3 * A0))),
    "coating in two, rigid substrate": (
        lambda: half_space(RIGID, (Layer(TOP, 0.15 * A0), Layer(TOP, 0.15 * A0))),
        lambda: half_space(RIGID, coating=Coating(TOP, 0.3 * A0))),
    "interlayer in two": (
        lambda: half_space(STEEL, (Layer(TOP, 0.2 * A0), Layer(MID, 0.1 * A0), Layer(MID, 0.2 * A0))),
        lambda: half_space(STEEL, (Layer(TOP, 0.2 * A0), Layer(MID, 0.3 * A0)))),
    "interlayer in two, frictionless": (
        lambda: half_space(STEEL, (Layer(TOP, 0.2 * A0), Layer(MID, 0.1 * A0),
                                   Layer(MID, 0.2 * A0, "frictionless"))),
        lambda: half_space(STEEL, (Layer(TOP, 0.2 * A0), Layer(MID, 0.3 * A0, "frictionless")))),
}


@pytest.mark.parametrize("name", list(IDENTITIES))
def test_identities_hold_to_the_discretisation(name):
    """Two identical layers are one of the summed thickness; a layer of the substrate's material
    adds nothing. Coarse mesh; each would move the answer by percent if the stack were wrong."""
    split, whole = (f() for f in IDENTITIES[name])
    m = FEMMethod(mesh="coarse")
    rs, rw = m.solve(split), m.solve(whole)
    for q in QS:
        assert err(rs, rw, q) <= IDENTITY[q], f"{name}, {q}: |split / whole - 1| = {err(rs, rw, q):.2e}"


# --- agreement with the exact method ----------------------------------------------------------
def _orders(name: str, levels: tuple[str, ...]) -> dict[str, list[float]]:
    ref = exact(name)
    return {q: [err(fe(name, lev), ref, q) for lev in levels] for q in QS}


def _message(name: str, levels: tuple[str, ...], errs: dict[str, list[float]]) -> str:
    parts = []
    for q, e in errs.items():
        order = (-np.polyfit(np.log([N_A[lev] for lev in levels]), np.log(np.maximum(e, 1e-16)), 1)[0])
        parts.append(f"{q}: " + ", ".join(f"{x:.2e}" for x in e) + f" (observed order {order:.2f})")
    return f"{name}, FE vs axisym at {'/'.join(levels)}: " + "; ".join(parts)


@pytest.mark.parametrize("name", [*CASES, "tin_ti_on_steel", "dlc_crn_cr_on_steel"])
def test_fe_agrees_with_exact_method(name):
    """Default mesh within the issue's bounds (delta, p0 2e-4; a 0.1 %); from coarse to default
    the error falls (or is at its floor, :data:`FLOOR`). ``dlc_crn_cr_on_steel`` has an elastic
    steel ball: the two-body FE contact on a stack."""
    levels = ("coarse", "default")
    errs = _orders(name, levels)
    msg = _message(name, levels, errs)
    for q in QS:
        e_coarse, e_default = errs[q]
        assert e_default <= BOUND[q], msg
        assert e_default < e_coarse or e_default <= FLOOR[q], msg


@pytest.mark.parametrize("name", list(CASES))
def test_three_methods_agree(name):
    """FE (default mesh), DC-FFT (n = 128) and axisym pairwise within the issue's bounds, on every
    stack here (2-4 layers, bonded and frictionless interfaces, elastic and rigid substrates,
    neighbour ratios 1/10-10, incompressible layers). FFT vs axisym measured: delta <= 2.4e-5,
    a <= 7.1e-4 (its radius estimator), p0 <= 4.1e-5. (Two FFT faults this cross-check found
    are mended: stacks on a rigid substrate raised in the grid estimate, and a thin top layer
    over the stack left the FFT's p0 off by 2-5e-3 on the 4-layer stacks.)"""
    from coathertz.fft.method import FFTMethod

    c = CASES[name]()
    results = {"axisym": exact(name), "fem": fe(name, "default"), "fft": FFTMethod(n=128).solve(c)}
    for (m1, r1), (m2, r2) in itertools.combinations(results.items(), 2):
        for q in QS:
            assert err(r1, r2, q) <= BOUND[q], f"{name}: {m1} vs {m2}, {q}: {err(r1, r2, q):.2e}"


@pytest.mark.slow
@pytest.mark.parametrize("name", [*CASES, "tin_ti_on_steel", "dlc_crn_cr_on_steel"])
def test_fe_converges_to_exact_method_slow(name):
    """Fine mesh (n_a = 100, up to 2.4e5 unknowns, <= 12 s CPU per case): delta and p0 within
    3e-5 of axisym (measured <= 1.4e-5), a within 2e-4 (measured <= 9.6e-5); the observed order
    over coarse/default/fine is in the message (measured: delta 0.3-3.1, the 0.3 where the error
    is at its 2e-6 floor; p0 0.6-1.9; a -0.3-2.4, estimator-bound below 1e-4)."""
    levels = ("coarse", "default", "fine")
    errs = _orders(name, levels)
    msg = _message(name, levels, errs)
    for q, bound in (("delta", 3e-5), ("a", 2e-4), ("p0", 3e-5)):
        assert errs[q][-1] <= bound, msg
        assert errs[q][-1] < errs[q][0] or errs[q][-1] <= FLOOR[q], msg


def test_identical_stacked_pair_is_one_body_under_twice_the_radius():
    layers = (Layer(TOP, 0.2 * A0), Layer(MID, 0.2 * A0, "frictionless"))
    body = Body(STEEL, None, R, R, layers=layers)
    pair = ContactCase(body, body, W)
    eq = axisymmetric_equivalent(pair, stacks=True)
    assert eq.body.layers == layers and eq.R == pytest.approx(R)  # relative radius R / 2, doubled
    single = ContactCase(Body.rigid_sphere(eq.R), Body(STEEL, layers=layers), W)
    m = FEMMethod(mesh="coarse")
    rp, rs = m.solve(pair), m.solve(single)
    assert rp.delta == pytest.approx(2 * rs.delta, rel=1e-12)
    assert rp.a == pytest.approx(rs.a, rel=1e-12) and rp.p0 == pytest.approx(rs.p0, rel=1e-12)


def test_interface_stresses_of_a_stack():
    """Coarse mesh, "4L mixed interfaces": across a bonded interface sigma_zz and sigma_rz are
    continuous (measured jumps <= 0.63 % of p0) and sigma_rr jumps (43-64 %); on a frictionless
    one sigma_rz vanishes on both sides (measured <= 0.16 % of p0, against 3-5 % on the bonded
    ones)."""
    c = CASES["4L mixed interfaces"]()
    r = FEMMethod(mesh="coarse", stresses=True).solve(c)
    f = r.fields
    for i, layer in enumerate(c.body2.layers, 1):
        def jump(name, i=i):
            d = f[f"interface{i}_above_{name}"] - f[f"interface{i}_below_{name}"]
            return float(np.max(np.abs(d))) / r.p0

        rz = max(float(np.max(np.abs(f[f"interface{i}_{s}_sigma_rz"]))) for s in ("above", "below")) / r.p0
        msg = (f"interface {i} ({layer.interface}): jumps / p0 sigma_zz {jump('sigma_zz'):.2e}, sigma_rz"
               f" {jump('sigma_rz'):.2e}, sigma_rr {jump('sigma_rr'):.2e}; max |sigma_rz| / p0 {rz:.2e}")
        assert jump("sigma_zz") < 0.02, msg
        assert jump("sigma_rr") > 0.2, msg
        if layer.interface == "bonded":
            assert jump("sigma_rz") < 0.02 and rz > 0.02, msg
        else:
            assert rz < 0.01, msg
    assert "interface_coating" not in r.meta and "interface4_below" in r.meta


# --- what the FE does not model for stacks: one line each -------------------------------------
def test_unsupported_stack_options_refuse_in_one_line():
    c = CASES["2L bonded 10:1"]()
    m = FEMMethod(mesh="coarse", interface="frictionless")
    assert not m.supports(c)
    with pytest.raises(CoatHertzError, match=r"^fem: body2 has a stack of 2 layers, whose interfaces") as exc:
        m.solve(c)
    assert "\n" not in str(exc.value)
    assert FEMMethod().supports(c)
    assert axisymmetric_equivalent(c) is None  # the plastic path's view: no stacks
    from coathertz.fem.plastic.method import solve_plastic
    from coathertz.fem.plastic.onset import yield_onset

    with pytest.raises(CoatHertzError, match=r"^elastic-plastic FE: body2 has a stack of 2 layers; plastic"):
        solve_plastic(c)
    with pytest.raises(CoatHertzError, match=r"^yield onset: body2 has a stack of 2 layers; plasticity"):
        yield_onset(c, Yc=1e9, Ys=1e9)


def test_multilayer_study_runs_the_fe(tmp_path):
    """The ``multilayer`` study admits the FE on every case (tier ``expensive``); at ``tiny``
    (coarse mesh) its rows agree with axisym within the issue's bounds (measured <= 5.6e-5 in
    delta, 8.9e-4 in a, 1.1e-4 in p0)."""
    from coathertz.store import ResultStore
    from coathertz.verification import build_methods, get_study, run_study

    mod = get_study("multilayer")
    methods, notes = build_methods("tiny", ["fem", "axisym"])
    assert not notes, notes
    store = ResultStore(tmp_path / "s.sqlite")
    r = run_study(mod, "tiny", methods, store, {"workers": 1, "progress": False})
    store.close()
    assert not r.failures, r.failures
    rows = {(x["case"], x["method"]): x for x in r.rows}
    cases = {x["case"] for x in r.rows}
    assert cases and all((c, "fem") in rows for c in cases), sorted(rows)
    for c in cases:
        fe_row, ref = rows[(c, "fem")], rows[(c, "axisym")]
        for q in QS:
            e = abs(fe_row[q] / ref[q] - 1.0)
            assert e <= BOUND[q], f"{c}, {q}: FE vs axisym {e:.2e}"


def test_memory_guard_counts_each_layer():
    """The estimate has Q1 pressure unknowns for each mixed (nu >= 0.45) layer only, and a stack
    with a very thin top layer is refused before anything is built, in one line naming it."""
    c = CASES["3L rigid incompressible mid"]()
    m = FEMMethod(mesh="coarse")
    a = 1.2 * A0
    size, dofs, _ = m.check_size(a, c.body2, R)
    assert size.n_t_layers and sum(size.n_t_layers) == size.n_t  # a rigid base: the stack is the mesh
    assert dofs == size.displacement_dofs + (size.n_r + 1) * (size.n_t_layers[1] + 1)
    lm = build_mesh(a, tuple(L.h for L in c.body2.layers), MESH_LEVELS["coarse"], rigid_base=True)
    assert (size.n_r, size.n_t) == (len(np.unique(lm.mesh.p[0])) - 1, len(np.unique(lm.mesh.p[1])) - 1)
    layers = (Layer(Material(450e9, 0.25), 1e-6 * A0), Layer(MID, 0.2 * A0))
    thin = ContactCase(Body.rigid_sphere(R), Body(STEEL, layers=layers), W)
    with pytest.raises(CoatHertzError, match="the top layer of the stack is very thin") as exc:
        FEMMethod(max_memory_gb=1.0).solve(thin)
    assert "\n" not in str(exc.value)


def test_cli_fem_solves_a_stack_example(capsys):
    """``coathertz fem`` on a stack: delta, a, p0 and both sides of every interface."""
    from coathertz.cli import main

    assert main(["fem", "example:tin_ti_on_steel", "--mesh", "coarse"]) == 0
    out = capsys.readouterr().out
    for row in ("delta [um]", "interface 1 (above) max von Mises", "interface 2 (below) max sigma_1"):
        assert row in out, out
