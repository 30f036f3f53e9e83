"""Contact radius of coated cases against an independent exact solution.

References: ``a`` of the exact axisymmetric method (``coathertz.axisym.AxisymMethod`` on branch
``axisym`` at commit d1dd03c: Galerkin-Legendre in Hankel space; its results with 8 and 12
modes-constants agree to < 1e-10; homogeneous: Hertz to 1e-15). They are copied here as
numbers so that the FFT tests do not import another method's solver.

The FFT reports the sub-cell gap fit (:func:`coathertz.fft.estimators.gap_fit_axes`) on a grid
re-fitted to the computed contact (``REFIT_BELOW = 0.9``, :mod:`coathertz.fft.grid`). Measured
max |error| over the 24 coated cases below: 0.36 % (n = 64), 0.128 % (128), 0.024 % (256);
without E = 4, H = 0.01 (h is half a cell at n = 128): 0.14 %, 0.051 %, 0.018 %. Before the
re-fit to the contact (grids on the Hertz estimate, radii of 26-51 cells at n = 128): 0.43 %,
0.131 %, 0.035 %, 0.012 % (n = 512); the paper's ``a_num = sqrt(S/pi)``: 1.37, 0.61, 0.29,
0.12 %; the earlier wide-band ``p^2`` fit (with its ``a_num`` fallback): 1.37, 0.80, 0.74,
0.76 %.

``A_THIN`` (55 more cases at the thin end, E = 1/4-4, H = 0.01-0.03, bonded and frictionless)
showed that E = 4, H = 0.01 is not alone: every coating thinner than a cell at n = 128 (37 of
them) has its edge boundary layer inside one cell, and stiff ones miss 0.1 % (up to +0.169 %);
with a cell or more the largest error is 0.067 % (n = 128) and 0.037 % (n = 256). The FFT
flags the former (:data:`coathertz.fft.method.LAYER_CELLS_MIN`; see :mod:`coathertz.fft.estimators`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fft.method import FFTMethod
from coathertz.materials import RIGID, Body

from .conftest import STEEL, coated

#: name -> exact a [m] (rigid 10 mm sphere, 1 N; see conftest.coated for H)
A_EXACT = {
    "el_E0.25_H0.01": 3.3159950601933e-05,
    "el_E0.25_H0.1": 3.65315928538782e-05,
    "el_E0.25_H0.5": 4.31686711782715e-05,
    "el_E0.25_H3": 5.083269616431553e-05,
    "el_E4_H0.01": 3.202730462079633e-05,
    "el_E4_H0.1": 3.002952343308796e-05,
    "el_E4_H0.5": 2.4191111783472282e-05,
    "el_E4_H3": 2.047686691454707e-05,
    "rg_nu0.3_H0.05": 1.644211168958024e-05,
    "rg_nu0.3_H0.1": 1.9386066040994214e-05,
    "rg_nu0.3_H0.2": 2.2700500353261146e-05,
    "rg_nu0.3_H0.5": 2.7332221489535854e-05,
    "rg_nu0.3_H3": 3.225268096524526e-05,
    "rg_nu0.5_H0.05": 1.1081879515072311e-05,
    "rg_nu0.5_H0.1": 1.4529472959093862e-05,
    "rg_nu0.5_H0.2": 1.849558291128215e-05,
    "rg_nu0.5_H0.5": 2.4020306916375134e-05,
    "rg_nu0.5_H3": 3.0153302559260758e-05,
    "rg_nu0.4_H0.1": 1.7774299309023617e-05,
    "rg_nu0.4_H0.2": 2.115526593070154e-05,
    "fl_el_E4_H0.1": 3.1469401720952564e-05,
    "fl_el_E0.25_H0.3": 4.261188798144576e-05,
    "fl_rg_nu0.5_H0.2": 2.2123953579994964e-05,
    "fl_rg_nu0.3_H0.05": 1.7219988018292044e-05,
}


def _case(name: str) -> tuple[ContactCase, str]:
    """Parse ``[fl_]el_E{E}_H{H}`` / ``[fl_]rg_nu{nu}_H{H}`` into a case and an interface."""
    interface = "frictionless" if name.startswith("fl_") else "bonded"
    kind, p1, p2 = name.removeprefix("fl_").split("_")
    H = float(p2[1:])
    if kind == "rg":
        return coated(0.0, H, nu_c=float(p1[2:]), substrate=RIGID), interface
    return coated(float(p1[1:]), H), interface


def _error(name: str, n: int, **kw) -> float:
    case, interface = _case(name)
    r = FFTMethod(n=n, interface=interface, workers=1, **kw).solve(case)
    assert r.meta["radius_estimator"] == "gap-fit", r.meta["radius_estimator"]
    assert r.meta["a_num"] == pytest.approx(math.sqrt(r.meta["area"] / math.pi))
    return r.a / A_EXACT[name] - 1


#: one case per family, including the previous estimator's worst (rigid base, nu_c = 0.5,
#: H = 0.2: +0.80 %) and its area fallback (rigid base, H = 0.05: +0.23 %, +0.61 %), and the two
#: cases over 0.1 % before the re-fit to the contact (E = 1/4, H = 0.01: -0.131 % -> -0.028 %;
#: rigid base, nu_c = 0.4, H = 0.1: -0.103 % -> -0.031 %)
WITHIN_GOAL = ["el_E0.25_H0.5", "el_E4_H0.1", "el_E4_H3", "rg_nu0.5_H0.2", "rg_nu0.3_H0.05",
               "rg_nu0.3_H3", "fl_rg_nu0.5_H0.2", "fl_el_E0.25_H0.3", "fl_rg_nu0.3_H0.05",
               "el_E0.25_H0.01", "rg_nu0.4_H0.1"]


@pytest.mark.parametrize("name", WITHIN_GOAL)
def test_radius_within_0p1_percent_at_n128(name):
    err = _error(name, 128)
    assert abs(err) < 1e-3, f"{name}: a error {err:+.2e} at n = 128 (measured <= 5.1e-4)"


def test_radius_converges_at_second_order_on_a_sub_cell_coating():
    """E = 4, H = 0.01: h is half a cell at n = 128. On the grid itself (``layer_cells=None``)
    +0.128 % at n = 128, converging; by default the coating is resolved (n = 252): +0.033 %."""
    ns = (64, 128, 256)
    with pytest.warns(UserWarning, match="cells thick"):  # the two sub-cell grids say so
        errs = [abs(_error("el_E4_H0.01", n, layer_cells=None)) for n in ns]
    order = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    msg = f"observed order {order:.2f}, |errors| {errs} on n = {ns}"
    assert order >= 1.5, msg  # measured 1.97
    assert errs[1] < 1.5e-3 and errs[2] < 3e-4, msg
    err = _error("el_E4_H0.01", 128)
    assert abs(err) < 1e-3, f"a error {err:+.2e} at n = 128 with the coating resolved (measured +3.3e-4)"


#: h is half a cell at n = 128: the one case over the 0.1 % goal (+0.128 %, see the report)
SUB_CELL_STIFF = "el_E4_H0.01"


@pytest.mark.slow
def test_radius_all_families_slow():
    """All 24 cases at n = 64, 128, 256 on the grids themselves (``layer_cells=None``;
    measured max |error| 0.36 %, 0.128 %, 0.024 %; at n = 128 0.051 % without E = 4, H = 0.01,
    the coating half a cell thick); the family maximum falls at order >= 1.5. With the
    default coating resolution every case is within the goal at n = 128 (0.051 %)."""
    ns = (64, 128, 256)
    errs = {n: {name: _error(name, n, layer_cells=None) for name in A_EXACT} for n in ns}
    worst = [max(abs(e) for e in errs[n].values()) for n in ns]
    order = -np.polyfit(np.log(ns), np.log(worst), 1)[0]
    msg = f"max |error| {worst} on n = {ns}, observed order {order:.2f}; all {errs}"
    assert order >= 1.5, msg  # measured 1.97
    others = max(abs(e) for name, e in errs[128].items() if name != SUB_CELL_STIFF)
    assert others < 1e-3, msg  # the goal: measured 5.1e-4
    assert abs(errs[128][SUB_CELL_STIFF]) < 1.5e-3, msg  # measured 1.28e-3
    assert worst[2] < 3.5e-4, msg  # measured 2.4e-4
    default = {name: _error(name, 128) for name in A_EXACT}
    assert max(abs(e) for e in default.values()) < 1e-3, default


@pytest.mark.slow
def test_radius_order_three_grids_slow():
    ns = (128, 256, 512)
    for name in ("el_E4_H0.01", "rg_nu0.4_H0.2"):
        errs = [abs(_error(name, n, layer_cells=None)) for n in ns]  # the grids themselves
        order = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
        assert order >= 1.5, f"{name}: observed order {order:.2f}, |errors| {errs}"


def test_homogeneous_radius_uses_the_hertz_pressure_fit():
    case = ContactCase(Body.rigid_sphere(10e-3), Body.half_space(STEEL), 1.0)
    r = FFTMethod(n=128, workers=1).solve(case)
    assert r.meta["radius_estimator"] == "pressure-fit"
    assert abs(r.a / float(case.hertz_s.a0) - 1) < 2e-4


def test_area_estimator_is_kept():
    case = coated(4.0, 0.5)
    r = FFTMethod(n=64, radius="area", workers=1).solve(case)
    assert r.meta["radius_estimator"] == "area" and r.a == pytest.approx(r.meta["a_num"])
    assert r.meta["a_fit"] != r.a


# -- thin coatings over the paper's range, and the sub-cell note ---------------------------

#: (interface, E, H = h/a0s) -> exact a [m] of the exact axisymmetric method (default
#: settings; its refined settings agree to < 1e-9), for the thin end of the paper's range:
#: E = 1/4-4, H = 0.01-0.03 (h is 0.5-1.5 cells at n = 128), bonded and frictionless. A
#: bonded coating of the substrate's material is the homogeneous body and is left out.
A_THIN = {
    ("bonded", 4.0, 0.01): 3.2027304621477325e-05,
    ("bonded", 4.0, 0.0125): 3.19476418297144e-05,
    ("bonded", 4.0, 0.015): 3.187186347201117e-05,
    ("bonded", 4.0, 0.02): 3.17292977538323e-05,
    ("bonded", 4.0, 0.03): 3.146952341280028e-05,
    ("bonded", 3.0, 0.01): 3.210827079430698e-05,
    ("bonded", 3.0, 0.0125): 3.2043425722845084e-05,
    ("bonded", 3.0, 0.015): 3.198157459185296e-05,
    ("bonded", 3.0, 0.02): 3.1864865495864795e-05,
    ("bonded", 3.0, 0.03): 3.1651478662574e-05,
    ("bonded", 2.0, 0.01): 3.2221840904235284e-05,
    ("bonded", 2.0, 0.0125): 3.2178875795716564e-05,
    ("bonded", 2.0, 0.015): 3.213778398067773e-05,
    ("bonded", 2.0, 0.02): 3.206001061234465e-05,
    ("bonded", 2.0, 0.03): 3.191727692417478e-05,
    ("bonded", 0.5, 0.01): 3.2722117264355896e-05,
    ("bonded", 0.5, 0.0125): 3.277962413833878e-05,
    ("bonded", 0.5, 0.015): 3.283459812316776e-05,
    ("bonded", 0.5, 0.02): 3.293854227054581e-05,
    ("bonded", 0.5, 0.03): 3.312875594567534e-05,
    ("bonded", 0.25, 0.01): 3.3159950600814114e-05,
    ("bonded", 0.25, 0.0125): 3.33023394703411e-05,
    ("bonded", 0.25, 0.015): 3.34377887616557e-05,
    ("bonded", 0.25, 0.02): 3.3692255041128796e-05,
    ("bonded", 0.25, 0.03): 3.415289740009071e-05,
    ("frictionless", 4.0, 0.01): 3.2370533847475717e-05,
    ("frictionless", 4.0, 0.0125): 3.2350605230101123e-05,
    ("frictionless", 4.0, 0.015): 3.233001507694195e-05,
    ("frictionless", 4.0, 0.02): 3.228724928550789e-05,
    ("frictionless", 4.0, 0.03): 3.2196945141276415e-05,
    ("frictionless", 3.0, 0.01): 3.242154728027324e-05,
    ("frictionless", 3.0, 0.0125): 3.241317765039356e-05,
    ("frictionless", 3.0, 0.015): 3.240393311662375e-05,
    ("frictionless", 3.0, 0.02): 3.2383355398176286e-05,
    ("frictionless", 3.0, 0.03): 3.233596199041625e-05,
    ("frictionless", 2.0, 0.01): 3.2501869256348263e-05,
    ("frictionless", 2.0, 0.0125): 3.2511187170458915e-05,
    ("frictionless", 2.0, 0.015): 3.2519200846939366e-05,
    ("frictionless", 2.0, 0.02): 3.253212389619032e-05,
    ("frictionless", 2.0, 0.03): 3.254875453195757e-05,
    ("frictionless", 1.0, 0.01): 3.268272321704321e-05,
    ("frictionless", 1.0, 0.0125): 3.2730071016448805e-05,
    ("frictionless", 1.0, 0.015): 3.277482292065021e-05,
    ("frictionless", 1.0, 0.02): 3.285816154571743e-05,
    ("frictionless", 1.0, 0.03): 3.3006616956473027e-05,
    ("frictionless", 0.5, 0.01): 3.2967139946873336e-05,
    ("frictionless", 0.5, 0.0125): 3.307124251560209e-05,
    ("frictionless", 0.5, 0.015): 3.3170172655102843e-05,
    ("frictionless", 0.5, 0.02): 3.335576569065217e-05,
    ("frictionless", 0.5, 0.03): 3.369079160336936e-05,
    ("frictionless", 0.25, 0.01): 3.3440160916419436e-05,
    ("frictionless", 0.25, 0.0125): 3.363393307840452e-05,
    ("frictionless", 0.25, 0.015): 3.3817431015348864e-05,
    ("frictionless", 0.25, 0.02): 3.4160118159377964e-05,
    ("frictionless", 0.25, 0.03): 3.477415409675056e-05,
}


def _thin_error(key, n, **kw):
    interface, E, H = key
    r = FFTMethod(n=n, interface=interface, workers=1, **kw).solve(coated(E, H))
    return r.a / A_THIN[key] - 1, r.meta


def test_frictionless_coating_of_the_substrate_material_is_not_hertzian():
    """A frictionless interface slips even between equal materials: the pressure is not
    Hertzian, and the ``p^2`` fit for homogeneous bodies (used for it before) missed ``a`` by
    -0.176 / -0.184 / -0.187 % at n = 128 / 256 / 512. The gap fit: +0.029 / +0.020 / +0.003 %."""
    errs = []
    for n in (128, 256):
        err, meta = _thin_error(("frictionless", 1.0, 0.01), n)
        assert meta["radius_estimator"] == "gap-fit", meta["radius_estimator"]
        errs.append(err)
    assert max(abs(e) for e in errs) < 1e-3, f"a errors {errs} at n = 128, 256 (measured 2.9e-4, 2.0e-4)"


def test_sub_cell_coating_is_flagged_and_resolved_by_the_suggested_grid():
    key = ("bonded", 4.0, 0.0125)  # the worst thin case at n = 128: +0.169 %
    with pytest.warns(UserWarning, match="cells thick") as rec:
        err, meta = _thin_error(key, 128, layer_cells=None)
    assert meta["layer_cells"] == pytest.approx(0.64, abs=0.01)
    assert meta["accuracy"] == str(rec[0].message)
    n_need = int(meta["accuracy"].split("n >= ")[1].split()[0])
    assert abs(err) < 0.003, f"{err:+.3e}: the note's bound is 0.3 %"
    err2, meta2 = _thin_error(key, n_need)
    assert meta2["layer_cells"] >= 1.0 and "accuracy" not in meta2, meta2.get("accuracy")
    assert abs(err2) < 1e-3, f"a error {err2:+.2e} at n = {n_need} (goal 0.1 %)"
    # a coating of 5 cells carries no note
    _, meta3 = _thin_error(("bonded", 4.0, 0.03), 256)
    assert meta3["layer_cells"] > 3 and "accuracy" not in meta3


def test_sub_cell_coating_is_resolved_by_default():
    """The default ``layer_cells = 1``: the case is solved again on the same domain with the n
    that gives the coating one cell (202 here, solved at the fast transform length 216), from
    the grid solution."""
    key = ("bonded", 4.0, 0.0125)
    err, meta = _thin_error(key, 128)
    ref = meta["layer_refinement"]
    assert ref["n_requested"] == 128 and ref["n"] == meta["grid"]["nx"] > 128, ref
    assert ref["layer_cells_before"] < 1.0 <= meta["layer_cells"], (ref, meta["layer_cells"])
    assert "accuracy" not in meta
    assert abs(err) < 1e-3, (f"a error {err:+.2e} (goal 0.1 %; measured +2.4e-4 at n = 216, "
                             "+3.8e-4 at 202, +0.169 % before)")
    assert abs(ref["a_before"] / A_THIN[key] - 1) > 1.5e-3  # the grid's own radius, kept


def test_refinement_beyond_the_memory_budget_is_left_to_the_note():
    """A refinement whose estimated memory exceeds ``max_memory_gb`` is not made; the note says
    so, with the n that would do and the memory it would take."""
    with pytest.warns(UserWarning, match="cells thick") as rec:
        _, meta = _thin_error(("bonded", 4.0, 0.01), 128, max_memory_gb=0.11)  # n = 128 fits, 252 not
    assert "layer_refinement" not in meta and meta["grid"]["nx"] == 128 and "accuracy" in meta
    msg = str(rec[0].message)
    assert "beyond max_memory_gb = 0.11" in msg and "0.3% (1.5 x the largest measured" in msg, msg
    n_need = int(msg.split("n >= ")[1].split()[0])
    assert n_need > 128, n_need


def test_stiff_thin_coating_is_refined_as_far_as_memory_allows():
    """E = 10, H = 0.005 at the default n = 128 needs n = 752 (0.25 cells before; refined to the
    fast transform length 768): refined now
    (the fixed cap of 4n left it at +0.665 % with a note quoting 0.59 %), a within 0.1 % of the
    exact method (measured +0.0047 % at 768, +0.004 % at 752)."""
    from coathertz.axisym import AxisymMethod
    from coathertz.fitalpha.sweep import Point, make_case

    case = make_case(Point("elastic", 10.0, 0.005))
    exact = AxisymMethod().solve(case)
    r = FFTMethod(workers=1).solve(case)
    assert r.meta["layer_refinement"]["n"] == 768, r.meta["layer_refinement"]
    assert "accuracy" not in r.meta
    assert abs(r.a / exact.a - 1) < 1e-3, f"a error {r.a / exact.a - 1:+.2e} (goal 0.1 %)"


@pytest.mark.parametrize("E,H,bound", [(10.0, 0.005, 0.010), (4.0, 0.005, 0.003), (0.25, 0.003, 0.003)])
def test_unrefined_note_quotes_a_bound_that_holds(E, H, bound):
    """Left unrefined (``layer_cells=None``), the note's bound holds: measured 0.666 / 0.159 /
    0.100 % here against the bounds 1.0 / 0.3 / 0.3 % (1.5 x the largest of 70 measured cases)."""
    from coathertz.axisym import AxisymMethod
    from coathertz.fitalpha.sweep import Point, make_case

    case = make_case(Point("elastic", E, H))
    exact = AxisymMethod().solve(case)
    with pytest.warns(UserWarning, match="cells thick") as rec:
        r = FFTMethod(workers=1, layer_cells=None).solve(case)
    assert f"{bound:.1%}" in str(rec[0].message), str(rec[0].message)
    err = abs(r.a / exact.a - 1)
    assert err <= bound, f"a error {err:.3%} beyond the quoted {bound:.1%}"


def test_memory_guard_refuses_before_allocating():
    """A grid whose estimate exceeds the budget is refused with the estimate, the limit and a
    grid that fits (4096^2 took 5.5 GB without a word before)."""
    from coathertz.fft.method import estimate_memory

    want = r"4096 x 4096 grid needs about 7.1\d GiB .* max_memory_gb = 4 GiB"
    with pytest.raises(CoatHertzError, match=want):
        FFTMethod(n=4096, max_memory_gb=4).solve(coated(1.0, 0.1))
    assert estimate_memory(1024, 1024) > 1.2 * 361 * 1024**2  # measured peak at n = 1024
    with pytest.raises(CoatHertzError, match="max_memory_gb"):
        FFTMethod(max_memory_gb=-1)


@pytest.mark.parametrize("bad", [0.0, -1.0, 100.0, True, "1", float("nan")])
def test_layer_cells_is_checked(bad):
    with pytest.raises(CoatHertzError, match="layer_cells"):
        FFTMethod(layer_cells=bad)


@pytest.mark.slow
def test_radius_thin_coatings_slow():
    """All of ``A_THIN`` at n = 128 and 256 on the grids themselves (``layer_cells=None``):
    within the goal (0.1 %) wherever the coating spans a cell or more, within the note's bound
    (0.17 %) below; max |error| falls from n = 128 to 256 at observed order >= 1.5 (measured:
    see ``LAYER_CELLS_MIN``). With the default coating resolution all are within the goal at
    n = 128."""
    from coathertz.fft.method import LAYER_CELLS_MIN, SUB_CELL_RADIUS_ERROR

    default = {key: _thin_error(key, 128)[0] for key in A_THIN}
    assert max(abs(e) for e in default.values()) < 1e-3, default
    worst = {}
    for n in (128, 256):
        resolved, sub = [], []
        for key in A_THIN:
            err, meta = _thin_error(key, n, layer_cells=None)
            (resolved if meta["layer_cells"] >= LAYER_CELLS_MIN else sub).append((abs(err), key))
            assert ("accuracy" in meta) == (meta["layer_cells"] < LAYER_CELLS_MIN), key
        msg = f"n = {n}: resolved max {max(resolved)}, sub-cell max {max(sub, default=None)}"
        assert max(resolved)[0] < 1e-3, msg
        assert not sub or max(sub)[0] <= SUB_CELL_RADIUS_ERROR, msg
        worst[n] = max(resolved + sub)[0]
    order = math.log2(worst[128] / worst[256])
    assert order >= 1.5, f"max |error| {worst}, observed order {order:.2f}"


def test_a_grid_given_by_the_caller_is_kept_and_flagged():
    from coathertz.fft.grid import Grid

    m = FFTMethod(n=128, workers=1)
    case = coated(4.0, 0.0125)
    g = Grid(**m.solve(case).meta["grid"])  # the refined grid: the coating spans a cell
    assert g.nx > 128
    coarse = Grid(128, 128, g.dx * (g.nx / 2 - 0.5) / 63.5, g.dy * (g.ny / 2 - 0.5) / 63.5)
    with pytest.warns(UserWarning, match="cells thick"):
        r = m.solve(case, grid=coarse)
    assert r.meta["grid"]["nx"] == 128 and "layer_refinement" not in r.meta and "accuracy" in r.meta


def test_a_much_stiffer_coating_needs_one_and_a_half_cells():
    """E = 10 (outside the paper's range), H = 0.02: the coating spans 1.02 cells at n = 128
    and a is off by +0.195 % there; coatings more than 4 times stiffer than their substrate
    get 1.5 cells (n = 190 here, solved at the fast transform length 192): +0.026 % (+0.046 % at
    190). Exact a: 3.128466981798888e-05 m (the exact
    method; its refined settings agree to 5e-11)."""
    case = coated(10.0, 0.02)
    with pytest.warns(UserWarning, match=r"fewer than the 1\.5 .*Ec\*/Es\* 4-10"):
        raw = FFTMethod(n=128, workers=1, layer_cells=None).solve(case)
    r = FFTMethod(n=128, workers=1).solve(case)
    errs = [x.a / 3.128466981798888e-05 - 1 for x in (raw, r)]
    assert r.meta["layer_refinement"]["n"] == 192 and r.meta["layer_cells"] >= 1.5, r.meta["layer_refinement"]
    assert abs(errs[0]) > 1.5e-3 and abs(errs[1]) < 1e-3, f"a errors raw / refined {errs}"
