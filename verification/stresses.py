r"""Stresses inside coated bodies: first-yield load versus friction, where yield starts, and the
coating-cracking and interface-shear maps (DC-FFT stresses, Hamilton's closed form).

Not a figure of the paper: an extension (issue 18, item 7). A rigid sphere (or ellipsoid,
:math:`R_x/R_y` with :math:`\sqrt{R_x R_y} = R`) slides along :math:`+x` in full sliding
(:math:`q = \mu p`, Amontons; the pressure is the frictionless normal solution: no
normal--tangential coupling) on a steel half-space (:math:`E_s = 200` GPa, :math:`\nu = 0.3`)
with a coating (:math:`E = E_c^*/E_s^*`, :math:`\nu_c = 0.3`, thickness :math:`H = h/a_{ys}`,
bonded). One yield stress :math:`Y` for coating and substrate (von Mises). The FFT contact
solution (:class:`~coathertz.fft.method.FFTMethod`) gives the pressure; its stresses
(:func:`~coathertz.fft.stresses.contact_stresses`) are computed twice, at :math:`\mu = 0` and
:math:`\mu = 1`: the field is linear in :math:`\mu`, so one solve gives every :math:`\mu`.

First-yield load. :math:`W_{ys}` is the first-yield load of the uncoated substrate of the same
geometry (FFT, same grid; self-similar: :math:`W_{ys} = W (Y/\sigma_{vM,max})^3` from one solve,
and :math:`a_{ys}` the circular Hertz radius there). For a coated body the field is not
self-similar: the maximum von Mises stress :math:`F_\mu(W) = \max\sigma_{vM}/Y` is computed at
:math:`W_{ys}` and at the smallest and largest load the local scaling
:math:`W (1/F_\mu)^3` predicts over the :math:`\mu` values, and :math:`\ln F_\mu` is
interpolated in :math:`\ln W` (quadratic through the three loads) to :math:`F_\mu = 1`. The
maxima are refined by a parabola through the grid maximum and its neighbours along x, y and z
(not across the interface or through the surface).

Where first yield happens: ``surface`` (z = 0), ``interface`` (within 5 % of h of it, either
side), ``coating``, ``substrate``. Cracking map: the largest first principal (tensile) stress
in the coating (its surface included) over :math:`p_0` at first yield; interface map: the
largest interface shear :math:`\sqrt{\sigma_{xz}^2 + \sigma_{yz}^2}` over :math:`p_0` at first
yield (coating side of :math:`z = h`).

Claims checked: the homogeneous onset (Hertz: :math:`\sigma_{vM,max} = 0.620\,p_0` at
:math:`z = 0.481a`, i.e. :math:`p_0 = 1.61\,Y`, Johnson 1985 sec. 6.2: 1.60 Y at 0.48 a)
within 1 % (p0) and 3 % (depth); the onset load versus :math:`\mu` against Hamilton's (1983)
closed form (:mod:`coathertz.hamilton`): :math:`\max\sigma_{vM}/p_0` within 1 % for every
:math:`\mu`; the friction coefficient at which the maximum moves to the surface (Hamilton:
0.305); the coated maps (observations). Every number carries a grid-convergence uncertainty: the
same computation on a finer grid, the difference is the uncertainty (``refined``).

Resolutions (grids ``n`` / refined ``n``): ``tiny`` 24/32, homogeneous and one coating
(E = 4, H = 0.3), mu in {0, 0.25, 0.5}; ``quick`` 32/48, homogeneous, E in {1/4, 4} at H = 0.3
and one ellipse (Rx/Ry = 3, homogeneous), mu = 0 to 0.5 by 0.1; ``full`` 64/96, E in
{1/4, 1/2, 1, 2, 4} x H in {0.01, 0.03, 0.1, 0.3, 1, 3} (circular) and Rx/Ry in {3, 10}
(homogeneous and E in {1/4, 4} x H in {0.1, 1}). The study solves in ``analyse`` (its cases
are not registry rows).
"""

from __future__ import annotations

import functools
import math
import time
import warnings
from dataclasses import dataclass

import numpy as np

from coathertz import verification as C
from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.materials import RIGID, Body, Coating, Material
from coathertz.stress_summary import first_principal, von_mises
from coathertz.verification.study import fork_map

NAME = "stresses"
TITLE = "Stresses in coated bodies: first-yield load vs friction, cracking and interface-shear maps"
#: ``verify`` runs this study early: its onset searches run in ``analyse`` (in this process),
#: while the workers solve the next studies' cases.
RUN_EARLY = True
CLAIM = ("Extension (not in the paper): homogeneous onset 0.620 p0 at 0.481 a (Johnson: 1.60 Y at 0.48 a); "
         "onset vs mu against Hamilton (1983); maps of W_y/W_ys, first-yield location, coating tension "
         "and interface shear over E in [1/4, 4], H in [0.01, 3], Rx/Ry up to 10.")
R = 10e-3
ES, NU, Y = 200e9, 0.3, 1e9
CLASSES = ("surface", "coating", "interface", "substrate")
SHORT = {"surface": "surf", "coating": "coat", "interface": "intf", "substrate": "subs"}
COLOURS = {"surface": "tab:orange", "coating": "tab:red", "interface": "tab:purple", "substrate": "tab:blue"}
JUDGED = "DC-FFT stresses (full sliding, q = mu p)"
#: (base grid, refined grid) per resolution
GRIDS = {"tiny": (24, 32), "quick": (32, 48), "full": (64, 96)}
#: loads solved per coated case (2: W_ys and one more, see :func:`onset`; 3: W_ys and both ends of the
#: predicted onsets)
LOADS = {"tiny": 2, "quick": 2, "full": 3}


def mus(resolution: str) -> list[float]:
    C.check_resolution(resolution)
    return [0.0, 0.25, 0.5] if resolution == "tiny" else [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]


def grid(resolution: str) -> tuple[list[float], list[float], list[tuple[float, float, float]]]:
    """``(E values, H values, extra (ratio, E, H) cases)`` of the circular map and the ellipses."""
    C.check_resolution(resolution)
    if resolution == "full":
        ell = [(k, 1.0, 0.0) for k in (3.0, 10.0)] + [(k, E, H) for k in (3.0, 10.0) for E in (0.25, 4.0)
                                                       for H in (0.1, 1.0)]
        return [0.25, 0.5, 1.0, 2.0, 4.0], [0.01, 0.03, 0.1, 0.3, 1.0, 3.0], ell
    if resolution == "quick":
        return [0.25, 4.0], [0.3], [(3.0, 1.0, 0.0)]
    return [4.0], [0.3], []


@functools.cache
def substrate_reference() -> tuple[float, float]:
    """``(W_ys, a_ys)`` of the circular contact from Hertz's field (closed form,
    :func:`coathertz.hamilton.von_mises_max_xz` at mu = 0: p0 = Y / 0.6200)."""
    from coathertz.hamilton import von_mises_max_xz

    p0y = 1.0 / von_mises_max_xz(NU, 0.0)[0]
    Es_star = Material(ES, NU).E_star
    W = (p0y * Y) ** 3 * math.pi**3 * R**2 / (6.0 * Es_star**2)  # Johnson eq 4.23 inverted
    return W, float(hertz_circular(W, R, Es_star).a0)


def make_case(ratio: float, E: float, H: float, W: float) -> ContactCase:
    """Rigid ellipsoid ``Rx/Ry = ratio`` (``sqrt(Rx Ry) = R``) on the coated (or bare) steel."""
    _, a_ys = substrate_reference()
    steel = Material(ES, NU)
    coat = None if H == 0 else Coating(Material(E * steel.E_star * (1.0 - NU**2), NU), H * a_ys)
    k = math.sqrt(ratio)
    indenter = Body(RIGID, None, R * k, R / k, name="rigid indenter")
    return ContactCase(indenter, Body.half_space(steel, coat), W)


def case_id(ratio: float, E: float, H: float) -> str:
    geo = "" if ratio == 1 else f"Rx/Ry={ratio:g},"
    return f"{geo}homogeneous" if H == 0 else f"{geo}E={E:g},H={H:g}"


def cases(resolution: str) -> list[C.StudyCase]:
    """The homogeneous sphere, the (E, H) map and the ellipses; ``tier = "none"``: the study
    solves them itself (two stress fields per load, :func:`onset`)."""
    Es_, Hs, ell = grid(resolution)
    W_ys, _ = substrate_reference()
    specs = [(1.0, 1.0, 0.0)] + [(1.0, E, H) for E in Es_ for H in Hs] + ell
    return [C.StudyCase(case_id(*s), make_case(*s, W_ys), {"ratio": s[0], "E": s[1], "H": s[2]}, tier="none")
            for s in specs]


# -- one load: the maxima of every mu -------------------------------------------------------------
@dataclass(frozen=True)
class Peak:
    value: float
    at: tuple[float, float, float]  # x, y, z [m]


def _parabola(f0: float, f1: float, f2: float, x0: float, x1: float, x2: float) -> tuple[float, float]:
    """Vertex ``(x, f)`` of the parabola through three points (``f1`` the largest), else ``(x1, f1)``."""
    d0, d2 = x0 - x1, x2 - x1
    den = d0 * d2 * (d0 - d2)
    if den == 0:
        return x1, f1
    a = (d2 * (f0 - f1) - d0 * (f2 - f1)) / den  # f = f1 + b t + a t^2, t = x - x1
    b = (d0 * d0 * (f2 - f1) - d2 * d2 * (f0 - f1)) / den
    if a >= 0:
        return x1, f1
    t = min(max(-b / (2 * a), d0), d2)
    return x1 + t, f1 + b * t + a * t * t


def peak(v: np.ndarray, x, y, z, h: float | None) -> Peak:
    """Largest value of ``v`` (shape ``(nz, ny, nx)``) refined by a parabola in each direction
    through the grid maximum and its two neighbours (not across the interface ``z = h``, not
    past an end of the sampled box): the peak's value rises by the sum of the three increments."""
    k, j, i = np.unravel_index(np.argmax(v), v.shape)
    best = float(v[k, j, i])
    pos = [float(x[i]), float(y[j]), float(z[k])]
    gain = 0.0
    for axis, coords, idx in ((2, x, i), (1, y, j), (0, z, k)):
        if not 0 < idx < len(coords) - 1:
            continue
        if axis == 0 and h is not None and (coords[idx - 1] <= h) != (coords[idx + 1] <= h):
            continue
        sl = [k, j, i]
        f = []
        for d in (-1, 0, 1):
            sl[axis] = idx + d
            f.append(float(v[tuple(sl)]))
        xs3 = [float(coords[idx + d]) for d in (-1, 0, 1)]
        xv, fv = _parabola(f[0], f[1], f[2], *xs3)
        gain += fv - best
        pos[2 - axis] = xv
    return Peak(best + gain, (pos[0], pos[1], pos[2]))


def depths(a: float, h: float | None) -> np.ndarray:
    """Depths [m] of the stress planes: 0 to a (denser around the Hertz maximum at 0.48a); in
    a coating, 4 steps to ``h``, both sides of the interface and 0.05a, 0.15a below it (points
    within 0.02a of the interface dropped, so that no parabola spans it)."""
    zs = list(a * np.r_[0.0, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.55, 0.6, 0.7, 0.85, 1.0])
    if h is not None:
        zs = [z for z in zs if abs(z - h) >= 0.02 * a]
        zs += [*np.linspace(0, h, 5), h * (1 + 1e-9), *(h + a * np.r_[0.05, 0.15])]
    return np.unique(np.asarray(zs))


def classify(z: float, h: float | None) -> str:
    if z == 0:
        return "surface"
    if h is None:
        return "substrate"
    if abs(z - h) <= 0.05 * h:
        return "interface"
    return "coating" if z < h else "substrate"


def maxima(case: ContactCase, n: int, mu_values, keep: bool = False) -> dict:
    """FFT solve at ``case.W`` on an ``n`` grid, then for each ``mu``: the von Mises peak (value,
    location, class), the largest coating tension and interface shear, all over p0 (``keep``:
    also the fields at the largest ``mu``, for a slice figure)."""
    from coathertz.fft.method import FFTMethod
    from coathertz.fft.stresses import contact_stresses

    b = case.body2
    h = b.coating.h if b.coating is not None else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = FFTMethod(n=n, workers=1, layer_cells=None, keep_fields=True).solve(case)
        scale = min(v for v in (r.r_a, r.r_b, r.a) if math.isfinite(v))
        z = depths(scale, h)
        F0 = contact_stresses(case, r, depths=z)
        # the sliding part only where some mu > 0 needs it (the field is linear in mu)
        F1 = contact_stresses(case, r, depths=z, mu=1.0) if any(m > 0 for m in mu_values) else F0
    Sp, Sq = F0.sigma, F1.sigma - F0.sigma
    p0 = float(r.p0)
    out = {"W": case.W, "p0": p0, "a": float(r.a), "scale": scale, "n": n, "by_mu": {}}
    coat = z <= h if h is not None else z == 0
    iface = int(np.flatnonzero(z == h)[0]) if h is not None else None
    for mu in mu_values:
        S = Sp + mu * Sq
        pk = peak(von_mises(S), F0.x, F0.y, z, h)
        s1 = first_principal(S[coat])
        tens = peak(s1, F0.x, F0.y, z[coat], None)
        row = {"vm": pk.value, "vm_over_p0": pk.value / p0, "at": pk.at, "where": classify(pk.at[2], h),
               "tensile_over_p0": tens.value / p0, "tensile_at": tens.at}
        if iface is not None:
            shear = np.hypot(S[iface, 3], S[iface, 4])[None]
            sh = peak(shear, F0.x, F0.y, z[iface:iface + 1], None)
            row["iface_shear_over_p0"], row["iface_shear_at"] = sh.value / p0, sh.at
        out["by_mu"][mu] = row
    if keep:
        mu = max(mu_values)
        out["field"] = {"x": F0.x, "y": F0.y, "z": z, "vm": von_mises(Sp + mu * Sq), "mu": mu, "h": h}
    return out


# -- the onset load ---------------------------------------------------------------------------------
def onset(sc: C.StudyCase, n: int, mu_values, W_ref: float, n_loads: int = 3) -> dict:
    """First-yield load of every ``mu`` (see the module docstring) and the maxima there.

    ``W_ref``: the load of the first solve. Homogeneous bodies: one solve (self-similar)."""
    p = sc.params
    first = maxima(make_case(p["ratio"], p["E"], p["H"], W_ref), n, mu_values, keep=True)
    loads = [first]
    if p["H"] > 0:
        est = [W_ref * (Y / first["by_mu"][m]["vm"]) ** 3 for m in mu_values]
        lo, hi = min(est), max(est)
        if n_loads > 2 and hi > 1.05 * lo:
            extra = [lo, hi]
        elif lo < W_ref < hi:  # one more load: the end farther from W_ref (the roots lie between)
            extra = [max(lo, hi, key=lambda w: abs(math.log(w / W_ref)))]
        else:  # the predicted range lies to one side of W_ref: its middle (the roots close to it)
            extra = [math.sqrt(lo * hi)]
        for W in extra:
            loads.append(maxima(make_case(p["ratio"], p["E"], p["H"], W), n, mu_values))
    loads.sort(key=lambda d: d["W"])
    lnW = np.log([d["W"] for d in loads])
    out = {}
    for m in mu_values:
        lnF = np.log([d["by_mu"][m]["vm"] / Y for d in loads])
        Wy, spread = _root(lnW, lnF)
        near = min(loads, key=lambda d: abs(math.log(d["W"] / Wy)))
        row = dict(near["by_mu"][m])
        for key in ("tensile_over_p0", "iface_shear_over_p0"):
            if key in row:
                row[key] = _interp(lnW, [d["by_mu"][m][key] for d in loads], math.log(Wy))
        # p0 and the length scale at W_y: Hertz's W^(1/3) from the nearest solved load
        grow = (Wy / near["W"]) ** (1.0 / 3.0)
        row.update(W_y=Wy, interp=spread, a_over=near["scale"], p0_y=near["p0"] * grow)  # "at": near load
        out[m] = row
    per_load = [{k: v for k, v in d.items() if k != "field"} for d in loads]
    return {"by_mu": out, "loads": [d["W"] for d in loads], "per_load": per_load, "field": first["field"]}


def refine_at(sc: C.StudyCase, n: int, mu_values, picked, base: dict) -> dict:
    """The onset of the ``picked`` mu values on the grid ``n``, from one solve.

    Homogeneous body (self-similar): at the base grid's W_y, and ``W_y = W (Y / vm)^3``.
    Coated: at the base grid's solved load nearest the first picked mu's W_y; every quantity is
    compared with the base grid at that same load and the difference carried to the onset:
    ``W_y`` shifts by the factor ``(vm_base / vm_fine)^3`` (the local scaling; its error is
    second order in the few-percent grid difference), the tension and the shear over p0 by
    their differences."""
    p = sc.params
    out = {}
    if p["H"] == 0:
        W = base["by_mu"][0.0]["W_y"]
        d = maxima(make_case(p["ratio"], p["E"], p["H"], W), n, mu_values)
        for m in mu_values:
            row = dict(d["by_mu"][m])
            grow = Y / row["vm"]
            row.update(W_y=W * grow**3, interp=0.0, a_over=d["scale"], p0_y=d["p0"] * grow)
            out[m] = row
        return {"by_mu": out, "loads": [W]}
    Wy0 = base["by_mu"][picked[0]]["W_y"]
    ref = min(base["per_load"], key=lambda d: abs(math.log(d["W"] / Wy0)))
    d = maxima(make_case(p["ratio"], p["E"], p["H"], ref["W"]), n, picked)
    for m in picked:
        b, f, o = ref["by_mu"][m], d["by_mu"][m], base["by_mu"][m]
        row = dict(f)
        row.update(W_y=o["W_y"] * (b["vm"] / f["vm"]) ** 3, interp=0.0, a_over=d["scale"],
                   p0_y=o["p0_y"] * (b["vm"] / f["vm"]))
        for key in ("tensile_over_p0", "iface_shear_over_p0"):
            if key in f:
                row[key] = o[key] + f[key] - b[key]
        out[m] = row
    return {"by_mu": out, "loads": [ref["W"]]}


def _root(lnW: np.ndarray, lnF: np.ndarray) -> tuple[float, float]:
    """Root of ``lnF(lnW)``: one point: the self-similar scaling ``W F^-3``; else a quadratic
    (three points) or line through them; also the relative difference to the line through the
    two points nearest the root (an interpolation uncertainty of W_y; with two points: the
    difference between the line and the scaling from the nearer one)."""
    if len(lnW) == 1:
        return float(math.exp(lnW[0] - 3 * lnF[0])), 0.0
    order = np.argsort(np.abs(lnF))[:2]
    x0, x1 = lnW[order]
    f0, f1 = lnF[order]
    lin = x0 - f0 * (x1 - x0) / (f1 - f0) if f1 != f0 else x0 - 3 * f0
    if len(lnW) < 3:  # against the local scaling W F^-3 from the nearer point
        return float(math.exp(lin)), abs(math.expm1(x0 - 3 * f0 - lin))
    c = np.polyfit(lnW, lnF, 2)
    roots = [float(t.real) for t in np.roots(c) if abs(t.imag) < 1e-12]
    quad = min(roots, key=lambda t: abs(t - lin)) if roots else lin
    return float(math.exp(quad)), abs(math.expm1(quad - lin))


def _interp(lnW: np.ndarray, vals, x: float) -> float:
    vals = np.asarray(vals, dtype=float)
    if len(lnW) == 1:
        return float(vals[0])
    deg = min(2, len(lnW) - 1)
    return float(np.polyval(np.polyfit(lnW, vals, deg), x))


# -- analyse ------------------------------------------------------------------------------------
def analyse(result: C.StudyResult) -> None:
    from coathertz.hamilton import von_mises_max_xz

    t0, c0 = time.perf_counter(), time.process_time()
    res = result.resolution
    n, n_fine = GRIDS[res]
    mu_values = mus(res)
    W_ys_cf, a_ys = substrate_reference()
    scs = cases(res)
    solved: dict[str, dict] = {}
    # every case's onset search is independent: side by side on the run's worker count
    found = fork_map(_onset_job, [(sc, n, mu_values, W_ys_cf, LOADS[res]) for sc in scs], result.workers)
    for sc, o in zip(scs, found, strict=True):
        if isinstance(o, Exception):  # reported, not fatal: one case must not sink the map
            result.failures.append({"case": sc.id, **sc.params, "method": "fft-stresses", "error": repr(o)})
        else:
            solved[sc.id] = o
    # W_ys per geometry: the homogeneous body's first-yield load at mu = 0 on the same grid
    W_ys = {sc.params["ratio"]: solved[sc.id]["by_mu"][0.0]["W_y"] for sc in scs
            if sc.params["H"] == 0 and sc.id in solved}
    rows = []
    for sc in scs:
        if sc.id not in solved or sc.params["ratio"] not in W_ys:
            continue
        for m, o in solved[sc.id]["by_mu"].items():
            rows.append({"case": sc.id, **sc.params, "mu": m, "W_y": o["W_y"],
                         "W_bar": o["W_y"] / W_ys[sc.params["ratio"]], "where": o["where"],
                         "vm_over_p0": o["vm_over_p0"], "p0_over_Y": o["p0_y"] / Y,
                         "x_over_a": o["at"][0] / o["a_over"], "z_over_a": o["at"][2] / o["a_over"],
                         "tensile_over_p0": o["tensile_over_p0"], "tensile_z": o["tensile_at"][2],
                         "iface_shear_over_p0": o.get("iface_shear_over_p0", math.nan),
                         "interp": o["interp"]})
    result.extra["onset"] = rows
    result.extra["W_ys"], result.extra["a_ys"] = W_ys, a_ys
    result.extra["grids"] = {"n": n, "n_refined": n_fine}
    result.extra["mu"] = mu_values
    hom = next((s for s in scs if s.params["H"] == 0 and s.params["ratio"] == 1.0), None)
    if hom is not None and hom.id in solved:
        f = solved[hom.id]["field"]
        result.extra["slice"] = _slice(f)
    # refined grid: the homogeneous sphere (one load, self-similar) and, for each coated extreme
    # of a map, one load: the base grid's W_y of that (case, mu) (refine_at)
    coated = [r for r in rows if r["H"] > 0]
    picks: dict[str, set] = {hom.id: set(mu_values)} if hom is not None and hom.id in solved else {}
    for key, pick in (("W_bar", min), ("W_bar", max), ("tensile_over_p0", max), ("iface_shear_over_p0", max)):
        sel = [r for r in coated if math.isfinite(r[key])]
        if sel:
            w = pick(sel, key=lambda r, k=key: r[k])
            picks.setdefault(w["case"], set()).add(w["mu"])
    fine: dict[str, dict] = {}
    by_id = {sc.id: sc for sc in scs}
    found = fork_map(_refine_job, [(by_id[cid], n_fine, mu_values, sorted(mset), solved[cid])
                                   for cid, mset in picks.items()], result.workers)
    for cid, o in zip(picks, found, strict=True):
        if isinstance(o, Exception):
            result.failures.append({"case": cid, **by_id[cid].params, "method": "fft-stresses-refined",
                                    "error": repr(o)})
        else:
            fine[cid] = o
    result.extra["refined"] = {cid: {m: {k: v for k, v in o.items() if not isinstance(v, tuple | list)}
                                     for m, o in d["by_mu"].items()} for cid, d in fine.items()}
    _claims(result, solved, fine, rows, hom, von_mises_max_xz)
    result.methods = [*result.methods, "fft-stresses"]
    result.computed += len(solved) + len(fine)
    result.method_time["fft-stresses"] = time.perf_counter() - t0
    result.extra["cpu_s"] = time.process_time() - c0  # this process (not the forked searches)


def _onset_job(job: tuple) -> dict:
    return onset(*job)


def _refine_job(job: tuple) -> dict:
    return refine_at(*job)


def _claims(result, solved, fine, rows, hom, vm_max_xz) -> None:
    mu_values = result.extra["mu"]
    if hom is not None and hom.id in solved and hom.id in fine:
        base, ref = solved[hom.id]["by_mu"], fine[hom.id]["by_mu"]
        vm0, _, z_cf, _ = vm_max_xz(NU, 0.0)  # Hertz's (Huber's) axis maximum, 0.6200 p0 at 0.4809 a
        p0y_cf = 1.0 / vm0
        o, of = base[0.0], ref[0.0]
        z, zf = o["at"][2] / o["a_over"], of["at"][2] / of["a_over"]
        for cid, what, val, valf, exact, bound, johnson in (
                ("stresses-homogeneous-p0", "p0/Y at first yield", o["p0_y"] / Y, of["p0_y"] / Y, p0y_cf, 1.0,
                 "1.60"),
                ("stresses-homogeneous-z", "depth of first yield z/a", z, zf, z_cf, 3.0, "0.48")):
            err, unc = 100 * abs(val / exact - 1), 100 * abs(valf - val) / exact
            holds, inc = C.judge("<", err, bound, unc)
            result.claims.append(C.Claim(
                cid, f"homogeneous sphere, mu = 0: {what} vs the Hertz axis value {exact:.4f} "
                f"(Johnson: {johnson})",
                err, f"< {bound:g} %", holds, "%", 0.05,
                f"FFT {val:.4f} on {result.extra['grids']['n']}^2, {valf:.4f} on "
                f"{result.extra['grids']['n_refined']}^2 (uncertainty: the difference); at {o['where']}",
                uncertainty=unc, inconclusive=inc, judged_against=f"{JUDGED}; homogeneous sphere"))
        # Hamilton: max von Mises / p0 for every mu; below the surface (grid difference as the
        # uncertainty) and on it (the trailing contact edge: the edge cells converge at order 1/2,
        # so the Richardson estimate diff / (1 - sqrt(n / n_refined)) is the uncertainty)
        ham = {}
        for m in mu_values:
            h = vm_max_xz(NU, m)
            ham[m] = {"vm_over_p0": h[0], "x_over_a": h[1], "z_over_a": h[2], "surface": h[3]}
        result.extra["hamilton"] = ham
        n, nf = result.extra["grids"]["n"], result.extra["grids"]["n_refined"]
        for cid, sel, what, factor in (
                ("stresses-hamilton-vm", [m for m in mu_values if ham[m]["z_over_a"] > 0],
                 "below the surface", 1.0),
                ("stresses-hamilton-vm-surface", [m for m in mu_values if ham[m]["z_over_a"] == 0],
                 "on the surface (trailing edge)", 1.0 / (1.0 - math.sqrt(n / nf)))):
            if not sel:
                continue
            errs = [100 * abs(base[m]["vm_over_p0"] / ham[m]["vm_over_p0"] - 1) for m in sel]
            uncs = [100 * factor * abs(ref[m]["vm_over_p0"] - base[m]["vm_over_p0"]) / ham[m]["vm_over_p0"]
                    for m in sel]
            k = int(np.argmax(errs))
            holds, inc = C.judge("<", errs[k], 1.0, uncs[k])
            mk = sel[k]
            result.claims.append(C.Claim(
                cid, f"homogeneous sphere sliding, max von Mises {what}: FFT vs Hamilton (1983), mu = "
                + ", ".join(f"{m:g}" for m in sel) + " (W_y/W_ys = (vm(0)/vm(mu))^3)", errs[k], "< 1 %",
                holds, "%", 0.05, f"worst at mu = {mk:g}: FFT {base[mk]['vm_over_p0']:.4f} ({n}^2), "
                f"{ref[mk]['vm_over_p0']:.4f} "
                f"({nf}^2), Hamilton {ham[mk]['vm_over_p0']:.4f} p0; errors by mu: "
                + ", ".join(f"{e:.2f}" for e in errs) + " %"
                + ("" if factor == 1.0 else f"; uncertainty: grid difference x {factor:.1f} (order 1/2)"),
                uncertainty=uncs[k], inconclusive=inc,
                judged_against="Hamilton (1983) closed form; homogeneous sphere"))
        # the friction coefficient at which the maximum moves to the surface
        ham_mu = _switch(lambda m: vm_max_xz(NU, m, nx=121, nz=61)[2] == 0.0, 0.25, 0.4)
        fft_mu = _first_surface(base, mu_values)
        fft_muf = _first_surface(ref, mu_values)
        step = mu_values[1] - mu_values[0]
        result.extra["surface_switch"] = {"hamilton": ham_mu, "fft": fft_mu, "fft_refined": fft_muf}
        val = fft_mu if fft_mu is not None else math.nan
        inside = val - step < ham_mu <= val if math.isfinite(val) else False
        result.claims.append(C.Claim(
            "stresses-surface-switch", "homogeneous sphere sliding: first mu (of the sampled ones) with the "
            f"largest von Mises stress on the surface; Hamilton's switch {ham_mu:.3f} lies in "
            f"(mu - {step:g}, mu]",
            val, f"({ham_mu:.3f}, {ham_mu + step:.3f}]", inside if math.isfinite(val) else None, "", 1e-9,
            f"refined grid: {fft_muf}", judged_against="Hamilton (1983) closed form; homogeneous sphere"))
    coated = [r for r in rows if r["H"] > 0]
    if not coated:
        return
    same = [r for r in coated if r["E"] == 1.0]
    if same:  # a coating of the substrate's own material: the homogeneous onset at every mu
        hom_rows = {(r["ratio"], r["mu"]): r["W_bar"] for r in rows if r["H"] == 0}
        devs = [100 * abs(r["W_bar"] / hom_rows[(r["ratio"], r["mu"])] - 1) for r in same
                if (r["ratio"], r["mu"]) in hom_rows]
        interp = 100 * max(r["interp"] for r in same)
        if devs:
            worst = max(devs)
            holds, inc = C.judge("<", worst, 1.0, interp)
            result.claims.append(C.Claim(
                "stresses-same-material", "coatings of the substrate's own material (E = 1, bonded): W_y "
                "equals the homogeneous body's at every mu and H", worst, "< 1 %", holds, "%", 0.05,
                f"{len(same)} (case, mu); uncertainty: the largest interpolation in W ({interp:.2f} %)",
                uncertainty=interp, inconclusive=inc, judged_against=f"{JUDGED}; E = 1 coatings"))
    for cid, key, pick, text in (
            ("stresses-map-wy-min", "W_bar", min, "smallest W_y/W_ys"),
            ("stresses-map-wy-max", "W_bar", max, "largest W_y/W_ys"),
            ("stresses-map-tension", "tensile_over_p0", max, "largest coating tension / p0 at first yield"),
            ("stresses-map-iface-shear", "iface_shear_over_p0", max,
             "largest interface shear / p0 at first yield")):
        sel = [r for r in coated if math.isfinite(r[key])]
        if not sel:
            continue
        w = pick(sel, key=lambda r, k=key: r[k])
        f = fine.get(w["case"], {}).get("by_mu", {}).get(w["mu"])
        if f is not None:
            ref_val = f["W_y"] / result.extra["W_ys"][w["ratio"]] if key == "W_bar" else f[key]
            # on the surface the peak sits at the trailing contact edge, whose cells converge at
            # order 1/2: the Richardson factor 1 / (1 - sqrt(n / n_refined)) on the difference
            grids = result.extra["grids"]
            at_surface = {"W_bar": w["where"] == "surface", "tensile_over_p0": w["tensile_z"] == 0.0}
            edge = at_surface.get(key, False)
            factor = 1.0 / (1.0 - math.sqrt(grids["n"] / grids["n_refined"])) if edge else 1.0
            unc = factor * abs(ref_val - w[key]) + (w["interp"] * w[key] if key == "W_bar" else 0.0)
            note = (f"refined grid: {ref_val:.4f} ({f['where']}); uncertainty: the difference"
                    + (f" x {factor:.1f} (order 1/2 at the contact edge)" if edge else "")
                    + (f" + interpolation in W {100 * w['interp']:.1f} %" if key == "W_bar" else ""))
        else:
            unc, note = math.nan, "not re-solved"
        counts = {c: sum(r["where"] == c for r in coated) for c in CLASSES}
        result.claims.append(C.Claim(
            cid, f"coated cases: {text} (observation)", w[key], "(observation)", None, "", 0.05,
            f"at {w['case']}, mu = {w['mu']:g} (first yield: {w['where']}); {note}; first yield at surface / "
            f"coating / interface / substrate: " + " / ".join(str(counts[c]) for c in CLASSES)
            + f" of {len(coated)} (case, mu)", uncertainty=unc,
            judged_against=f"{JUDGED}; {len({r['case'] for r in coated})} coated cases"))


def _first_surface(by_mu: dict, mu_values) -> float | None:
    return next((m for m in mu_values if by_mu[m]["where"] == "surface"), None)


def _switch(on_surface, lo: float, hi: float, it: int = 10) -> float:
    """Smallest mu in ``[lo, hi]`` with ``on_surface(mu)`` (bisection)."""
    for _ in range(it):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if on_surface(mid) else (mid, hi)
    return hi


def _slice(f: dict) -> dict:
    """The x-z plane through y = 0 of the kept von Mises field (over its maximum)."""
    j = int(np.argmin(np.abs(f["y"])))
    return {"x": f["x"], "z": f["z"], "vm": f["vm"][:, j, :], "mu": f["mu"], "h": f["h"]}


# -- figures ------------------------------------------------------------------------------------
def plot(result: C.StudyResult, outdir) -> list:
    paths = []
    rows = result.extra.get("onset", [])
    if not rows:
        return paths
    paths += _plot_mu(result, rows, outdir)
    circ = [r for r in rows if r["ratio"] == 1.0 and r["H"] > 0]
    if circ:
        paths += _plot_maps(result, circ, outdir)
    if "slice" in result.extra:
        paths += _plot_slice(result, outdir)
    return paths


def _plot_mu(result, rows, outdir) -> list:
    fig, axes = C.figure(1, 1, width=5.6, height=4.0)
    ax = axes[0, 0]
    ids = list(dict.fromkeys(r["case"] for r in rows))
    if len(ids) > 12:  # full: the homogeneous bodies and the extreme moduli at two thicknesses
        Es_ = sorted({r["E"] for r in rows if r["H"] > 0})
        keep = {r["case"] for r in rows
                if r["H"] == 0 or (r["E"] in (Es_[0], Es_[-1]) and r["H"] in (0.1, 1.0))}
        ids = [i for i in ids if i in keep]
    # colour: the coating (E, H); line style: the geometry Rx/Ry; homogeneous bodies in black
    combos = sorted({(r["E"], r["H"]) for r in rows if r["case"] in ids and r["H"] > 0})
    styles = {1.0: "-", 3.0: "--", 10.0: ":"}
    tab10 = __import__("matplotlib").colormaps["tab10"]
    for cid in ids:
        sel = sorted((r for r in rows if r["case"] == cid), key=lambda r: r["mu"])
        hom = sel[0]["H"] == 0
        colour = "k" if hom else tab10(combos.index((sel[0]["E"], sel[0]["H"])) % 10)
        ax.plot([r["mu"] for r in sel], [r["W_bar"] for r in sel], styles.get(sel[0]["ratio"], "-."),
                marker="s" if hom else "o", color=colour, ms=3.5, lw=1.2, label=cid)
    ham = result.extra.get("hamilton")
    if ham:
        m = sorted(ham)
        ax.plot(m, [(ham[0.0]["vm_over_p0"] / ham[k]["vm_over_p0"]) ** 3 for k in m], "-", color="tab:red",
                lw=2.5, alpha=0.5, label="Hamilton (1983), homogeneous sphere")
    ax.set_yscale("log")
    ax.set_xlabel(r"friction coefficient $\mu$ (full sliding, $q = \mu p$)")
    ax.set_ylabel(r"$W_y / W_{ys}$ (first-yield load / uncoated substrate's)")
    ax.set_title(f"stresses study ({result.resolution}): first yield vs friction, DC-FFT "
                 f"{result.extra['grids']['n']}$^2$\nline style: Rx/Ry = 1 solid, 3 dashed, 10 dotted",
                 fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.set_layout_engine("tight")
    return C.save(fig, outdir, "stresses_onset_vs_mu")


def _plot_maps(result, circ, outdir) -> list:
    import matplotlib.colors as mcolors

    Es_ = sorted({r["E"] for r in circ})
    Hs = sorted({r["H"] for r in circ})
    mu_show = [m for m in (0.0, max(result.extra["mu"]))]
    quantities = (("W_bar", r"$W_y/W_{ys}$", True),
                  ("tensile_over_p0", r"coating tension $\sigma_1/p_0$", False),
                  ("iface_shear_over_p0", r"interface shear $\tau/p_0$", False))
    fig, axes = C.figure(len(quantities), len(mu_show), width=3.5, height=2.9)
    for col, (key, label, logc) in enumerate(quantities):
        vals = [r[key] for r in circ if math.isfinite(r[key]) and r["mu"] in mu_show]
        if not vals:
            continue
        lo, hi = min(vals), max(vals)
        norm = mcolors.LogNorm(lo, hi) if logc and lo > 0 else mcolors.Normalize(lo, hi)
        for row_i, mu in enumerate(mu_show):
            ax = axes[row_i, col]
            Z = np.full((len(Es_), len(Hs)), np.nan)
            where = {}
            for r in circ:
                if r["mu"] == mu:
                    Z[Es_.index(r["E"]), Hs.index(r["H"])] = r[key]
                    where[(Es_.index(r["E"]), Hs.index(r["H"]))] = r["where"]
            im = ax.imshow(Z, origin="lower", aspect="auto", cmap="viridis", norm=norm)
            for (ei, hi_), w in where.items():
                v = Z[ei, hi_]
                r_, g_, b_, _ = im.cmap(norm(v))
                ink = "k" if 0.299 * r_ + 0.587 * g_ + 0.114 * b_ > 0.5 else "w"  # readable on the cell
                ax.text(hi_, ei, f"{v:.2g}\n{SHORT[w]}" if key == "W_bar" else f"{v:.2g}", ha="center",
                        va="center", fontsize=6, color=ink)
            for ei in range(len(Es_)):
                for hi_ in range(len(Hs)):
                    if not math.isfinite(Z[ei, hi_]):
                        ax.text(hi_, ei, "×\nmissing", ha="center", va="center", fontsize=6, color="0.4")
            ax.set_xticks(range(len(Hs)), [f"{h:g}" for h in Hs])
            ax.set_yticks(range(len(Es_)), [f"{e:g}" for e in Es_])
            ax.set_xlabel(r"$H = h/a_{ys}$")
            ax.set_ylabel(r"$E = E_c^*/E_s^*$")
            ax.set_title(f"{label}, $\\mu$ = {mu:g}", fontsize=8)
            fig.colorbar(im, ax=ax, shrink=0.85)
    fig.suptitle(f"stresses study ({result.resolution}): circular contact, DC-FFT "
                 f"{result.extra['grids']['n']}$^2$, "
                 "at first yield\n(text: first-yield location: surf = surface, coat = coating, "
                 "intf = interface, subs = substrate)", fontsize=9)
    fig.set_layout_engine("tight")
    return C.save(fig, outdir, "stresses_maps")


def _plot_slice(result, outdir) -> list:
    s = result.extra["slice"]
    a = result.extra["a_ys"]
    fig, axes = C.figure(1, 1, width=5.6, height=3.4)
    ax = axes[0, 0]
    X, Z = np.meshgrid(s["x"] / a, s["z"] / a)
    vm = s["vm"] / Y
    cs = ax.contourf(X, Z, vm, levels=20, cmap="magma")
    ax.contour(X, Z, vm, levels=[1.0], colors="c", linewidths=1.0)
    ax.plot([], [], "c-", lw=1.0, label=r"$\sigma_{vM} = Y$ (inside: above the yield stress)")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.22), frameon=False)
    ax.invert_yaxis()
    ax.axvline(-1, color="w", lw=0.6, ls=":")
    ax.axvline(1, color="w", lw=0.6, ls=":")
    ax.set_xlabel(r"$x / a_{ys}$ (sliding along $+x$; dotted: contact edge)", labelpad=1)
    ax.set_ylabel(r"depth $z / a_{ys}$")
    fig.colorbar(cs, ax=ax, label=r"von Mises $\sigma_{vM}/Y$")
    ax.set_title(f"stresses study: homogeneous sphere at $W_{{ys}}$, $\\mu$ = {s['mu']:g}, x–z slice y = 0, "
                 f"DC-FFT {result.extra['grids']['n']}$^2$", fontsize=8)
    fig.set_layout_engine("tight")
    return C.save(fig, outdir, "stresses_slice")
