r"""Layer stacks: an interlayer's modulus and thickness against delta, a and p0.

Not a figure of the paper: an extension. Configuration: a rigid sphere (R = 5 mm, W = 2 N) on a
3 um TiN top layer (450 GPa, nu = 0.25) over an interlayer (modulus ratio
:math:`E_i/E_s`, nu = 0.3, thickness :math:`h_i`) on steel (210 GPa, 0.3), all interfaces bonded;
plus the TiN layer alone (``coating-only``, a one-layer stack: equal to the coating to 1e-15,
``tests/multilayer``), the baseline of every ratio. The closed form refuses stacks; the exact
method (axisym, where registered), the FFT and the FE model solve them (the FE, about 1 s of CPU
per case at its default mesh, on every case at ``full``, on the baseline and two interlayers at
``quick``).

Claims: an interlayer of the substrate's own material (:math:`E_i = E_s`) adds nothing (each
quantity within 1e-6 % of the coating-only case, at every :math:`h_i`: an identity of the
N-layer kernel, judged on an exact method, reference rank >= 30; measured 4e-8 %); the FFT and
the FE agree with the exact method within 0.02 % in delta and p0 and 0.1 % in a (measured at
``quick``: 0.0023 % and 0.05 %); the effect of the interlayer on delta, a, p0 is mapped
(figure ``multilayer``).

Interface stresses (where the exact method ran; :mod:`coathertz.axisym.stresses`, each case
solved again for its Galerkin solution): at every interface of every case the largest shear
``|sigma_rz|`` and the largest normal stress ``sigma_zz`` (tension positive; a negative value is
compressive over the whole scan, 0 to 2.5 a, and sits at its end) over p0, with their radii
(``extra["interface_stresses"]``, figure ``multilayer_interfaces``; the largest shear is an
observation claim). Checks: across every bonded interface ``sigma_zz`` and ``sigma_rz`` from the
layers above and below agree to round-off (< 1e-12 p0; measured 7.4e-16 at ``quick``); a
frictionless TiN/interlayer interface (an extra case, soft interlayer of 1 um) carries no shear
on either face (< 1e-12 p0; measured 6.2e-17, against 0.138 p0 bonded); equilibrium at the
deepest interface, ``-int sigma_zz 2 pi r dr = W`` to 1e-4 (measured 1.2e-5 with r to 9 a, the
load outside ~ (z/9a)^3 = 7.7e-6 W). Measured at ``quick``: a soft interlayer lowers the TiN's
interface shear (0.188 p0 alone; 0.114 p0 at :math:`E_i/E_s = 0.25`, 3 um), a stiff one raises
it (0.254 p0 at 4, 3 um); a thick soft interlayer puts the TiN's interface in tension outside
the contact (+4.1e-3 p0 at r = 1.3 a). The added cost is about 1 s of CPU at ``quick``.

Resolutions: ``full`` 5 ratios x 4 thicknesses; ``quick`` 3 x 3; ``tiny`` 2 x 1 (+ the baseline).
"""

from __future__ import annotations

import math
import time

import numpy as np

from coathertz import verification as C
from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import Body, Layer, Material
from coathertz.verification.study import fork_map

NAME = "multilayer"
#: ``verify`` runs this study early: its interface stresses are computed in ``analyse`` (in
#: processes of its own) while the workers solve the next studies' cases.
RUN_EARLY = True
TITLE = "Layer stacks: TiN over an interlayer (modulus ratio, thickness) on steel, rigid sphere"
CLAIM = ("Extension: an interlayer of the substrate's material adds nothing; the "
         "interlayer's modulus and thickness against delta, a, p0 (exact method, FFT and FE) "
         "and against the interface stresses (exact method).")
STEEL = Material(210e9, 0.3)
TIN = Material(450e9, 0.25)
H_TOP = 3e-6
R, W = 5e-3, 2.0
IDENTITY_BOUND = 1e-6  # percent
#: Agreement asked of every stack-capable method with the exact one [%]: delta and p0 2e-4, a 1e-3.
AGREE_BOUND = {"delta": 0.02, "p0": 0.02, "a": 0.1}
QS = ("delta", "a", "p0")
#: Methods ranked this high are exact (the axisymmetric integral-equation method): they judge the identity.
EXACT_RANK = 30


def grid(resolution: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Interlayer modulus ratios E_i/E_s and thicknesses h_i [m]."""
    C.check_resolution(resolution)
    if resolution == "full":
        return (0.25, 0.5, 1.0, 2.0, 4.0), (0.1e-6, 0.3e-6, 1e-6, 3e-6)
    if resolution == "quick":
        return (0.25, 1.0, 4.0), (0.1e-6, 1e-6, 3e-6)
    return (0.25, 1.0), (1e-6,)


def _case(layers: tuple[Layer, ...], label: str) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R), Body(STEEL, layers=layers), W, label=label)


def fe_cases(resolution: str) -> set[tuple[float, float]]:
    """The (E_i/E_s, h_i) the FE solves besides the baseline: every one at ``full`` and ``tiny``;
    at ``quick`` the soft and the stiff interlayer at the middle thickness (the FE costs about a
    second per case, the main job's budget)."""
    ratios, hs = grid(resolution)
    if resolution == "quick":
        return {(ratios[0], hs[1]), (ratios[-1], hs[1])}
    return {(Ei, hi) for Ei in ratios for hi in hs}


def cases(resolution: str) -> list[C.StudyCase]:
    ratios, hs = grid(resolution)
    fe = fe_cases(resolution)
    base = _case((Layer(TIN, H_TOP),), "TiN on steel")
    out = [C.StudyCase("coating-only", base, {"E_i": math.nan, "h_i": 0.0}, "expensive")]
    for Ei in ratios:
        for hi in hs:
            cid = f"Ei={Ei:g},hi={hi * 1e6:g}um"
            layers = (Layer(TIN, H_TOP), Layer(Material(Ei * STEEL.E, STEEL.nu), hi))
            tier = "expensive" if (Ei, hi) in fe else "moderate"
            out.append(C.StudyCase(cid, _case(layers, cid), {"E_i": Ei, "h_i": hi}, tier))
    return out


def _reference_rows(result: C.StudyResult) -> dict[str, dict]:
    return {r["case"]: r for r in result.rows if result.reference.get(r["case"]) == r["method"]}


def analyse(result: C.StudyResult) -> None:
    # the identity is a property of the kernel: judged on an exact (arbiter-rank) method only, as
    # a discretising method's grid and estimators differ between the two cases
    ref = {cid: r for cid, r in _reference_rows(result).items()
           if C.method_info(r["method"]).reference_rank >= EXACT_RANK}
    base = ref.get("coating-only")
    same = [r for cid, r in ref.items() if cid != "coating-only" and r.get("E_i") == 1.0]
    if base is None or not same:
        result.claims.append(C.Claim(
            "multilayer-substrate-interlayer-adds-nothing", "an interlayer of the substrate's material "
            "adds nothing (needs an exact method, reference rank >= 30: none ran)", math.nan,
            f"< {IDENTITY_BOUND:g} %", None, "%", 1e-6))
    else:
        worst = max(abs(r[q] / base[q] - 1.0) * 100.0 for r in same for q in QS)
        result.claims.append(C.Claim(
            "multilayer-substrate-interlayer-adds-nothing",
            "max over h_i and delta, a, p0 of |stack / coating-only - 1| for an interlayer of the "
            "substrate's material (an identity)", worst, f"< {IDENTITY_BOUND:g} %",
            worst < IDENTITY_BOUND, "%", 1e-6,
            judged_against=f"{', '.join(sorted({r['method'] for r in same}))} on {len(same)} cases"))
    checks = [d for d in result.crosscheck if not d["method"].endswith("-refined")]
    for suffix, qs, bound, what in (("delta-p0", ("delta", "p"), AGREE_BOUND["delta"], "delta and p0"),
                                    ("a", ("a",), AGREE_BOUND["a"], "a")):  # qs: the cross-checks' names
        mine = [d for d in checks if d["quantity"] in qs]
        if not mine:
            continue
        d = max(mine, key=lambda d: abs(d["diff"]))
        worst = abs(d["diff"])
        result.claims.append(C.Claim(
            f"multilayer-methods-agree-{suffix}",
            f"max |difference| of the other methods (FFT, FE) from the exact method over the stacks, "
            f"{what} (the stack issue's bound)", worst, f"< {bound:g} %", worst < bound, "%", 0.05 * bound,
            f"largest: {d['pair']}, case {d['case']}",
            judged_against=f"{len({x['case'] for x in mine})} cases, "
                           f"{', '.join(sorted({x['pair'] for x in mine}))}"))
    analyse_interfaces(result)



# --- interface stresses (exact method) ---------------------------------------------------------

#: Radii of the interface scan [units of a]; each interior maximum is refined on FINE radii an
#: eighth of a step apart and a parabola (measured at ``quick`` against a scan 8x finer with
#: ``cut = 32``: values within 7.3e-6 p0, radii within 2e-4 a; Huber's field: 6e-6 p0, 1e-4 a).
SCAN_RHO = np.linspace(0.0, 2.5, 41)
FINE = 17
#: The stresses' xi integrals stop where their integrand is e^-CUT of its size (< 1e-10 p0 left
#: out, :mod:`coathertz.axisym.stresses`; the default 32 costs 60 % more nodes).
CUT = 20.0
#: Every SCAN_STEP-th scan radius is also evaluated from the layer below (continuity check).
SCAN_STEP = 5
#: Bound of the traction jumps across a bonded interface and of the shear on a frictionless one,
#: over p0 (round-off: the kernel's linear system imposes both; measured <= 1e-15).
ROUNDOFF_BOUND = 1e-12
#: Equilibrium at an interface: Gauss panels in r [units of a] to R_EQ, 16 nodes each; the load
#: outside R_EQ is ~ W (z/R_EQ)^3 (Boussinesq's far field; < 3e-6 W here).
R_EQ_PANELS = (0.0, 0.6, 0.9, 1.1, 1.5, 2.5, 4.0, 6.0, 9.0)
EQUILIBRIUM_BOUND = 1e-4
#: The analyse-only case of the frictionless check: the soft interlayer at the middle thickness
#: with a frictionless TiN/interlayer interface.
FRICTIONLESS_CASE = (0.25, 1e-6)
SIDES = ("above", "below")


def interface_names(case: ContactCase) -> list[str]:
    """``top/bottom`` names of the interfaces of body 2 (top first)."""
    layers = case.body2.layers
    names = ["TiN" if L.material == TIN else "interlayer" for L in layers] + ["steel"]
    return [f"{names[i]}/{names[i + 1]}" for i in range(len(layers))]


def _peak(rho: np.ndarray, v: np.ndarray) -> tuple[float, float]:
    """Largest value of ``v`` on the scan and its ``rho`` (parabola through the best point and its
    neighbours where it is inside the scan)."""
    i = int(np.argmax(v))
    if 0 < i < v.size - 1:
        y0, y1, y2 = v[i - 1], v[i], v[i + 1]
        den = y0 - 2.0 * y1 + y2
        if den < 0:
            d = 0.5 * (y0 - y2) / den  # vertex offset in grid steps, |d| <= 1/2
            step = rho[i + 1] - rho[i]
            return float(y1 - 0.25 * (y0 - y2) * d), float(rho[i] + d * step)
    return float(v[i]), float(rho[i])


def interface_stresses(S) -> tuple[list[dict], float]:
    """Largest interface shear ``|sigma_rz|`` and normal stress ``sigma_zz`` (tension positive)
    over p0 at every interface of body 2, with their radii [units of a], from the exact method's
    stresses ``S`` (:class:`~coathertz.axisym.stresses.AxisymStresses`): a scan on
    :data:`SCAN_RHO`, then 17 radii an eighth of a step apart around each maximum and a parabola; and
    the largest traction jump over p0 across the bonded interfaces (``sigma_zz``, ``sigma_rz``
    from the layers above and below)."""
    case, res = S.case, S.result
    layers = case.body2.layers
    z = np.cumsum([L.h for L in layers])
    above = S.field(SCAN_RHO * res.a, z)
    below = S.field(SCAN_RHO[::SCAN_STEP] * res.a, z, side="below")
    step = SCAN_RHO[1] - SCAN_RHO[0]
    coarse = [(np.abs(above.sigma[i, 3]) / res.p0, above.sigma[i, 2] / res.p0) for i in range(len(layers))]
    # FINE radii an eighth of a step apart around every interior coarse maximum, in one field
    # (ending at the scan's last radius: the same xi nodes, whose coefficients S reuses)
    centres = [int(np.argmax(v)) for c in coarse for v in c]
    fine = [SCAN_RHO[j] + (step / 8.0) * np.arange(-8, 9) for j in centres]
    ff = S.field(np.concatenate([*fine, SCAN_RHO[-1:]]) * res.a, z).sigma / res.p0
    rows, jump = [], 0.0
    for i, (L, name) in enumerate(zip(layers, interface_names(case), strict=True)):
        out = []
        for q, (comp, absval) in enumerate(((3, True), (2, False))):
            n = 2 * i + q
            if 0 < centres[n] < SCAN_RHO.size - 1:
                v = ff[i, comp, FINE * n:FINE * (n + 1)]
                out.append(_peak(fine[n], np.abs(v) if absval else v))
            else:  # at an end of the scan: no interior maximum
                out.append((float(coarse[i][q][centres[n]]), float(SCAN_RHO[centres[n]])))
        (tau, r_tau), (szz, r_szz) = out
        rows.append({"interface": i + 1, "name": name, "z": float(z[i]), "bond": L.interface,
                     "tau_max": tau, "r_tau": r_tau, "szz_max": szz, "r_szz": r_szz})
        if L.interface == "bonded":
            d = above.sigma[i, 2:, ::SCAN_STEP] - below.sigma[i, 2:]
            jump = max(jump, float(np.abs(d).max()) / res.p0)
    return rows, jump


def shear_on_frictionless(method) -> float:
    """max |sigma_rz| / p0 on the frictionless TiN/interlayer interface of
    :data:`FRICTIONLESS_CASE`, from both sides."""
    from coathertz.axisym.stresses import AxisymStresses

    Ei, hi = FRICTIONLESS_CASE
    layers = (Layer(TIN, H_TOP, "frictionless"), Layer(Material(Ei * STEEL.E, STEEL.nu), hi))
    c = _case(layers, "frictionless")
    res = method.solve(c)
    S = AxisymStresses(c, res, cut=CUT)
    rho = SCAN_RHO[::SCAN_STEP] * res.a
    faces = (S.field(rho, [H_TOP], side=side).sigma[0, 3] for side in SIDES)
    return max(float(np.abs(f).max()) for f in faces) / res.p0


def interface_load(S) -> tuple[float, float]:
    """``-int sigma_zz 2 pi r dr / W`` at body 2's deepest interface (Gauss to ``R_EQ_PANELS[-1] a``)
    from the exact method's stresses ``S``, and the estimate ``(z / r_max)^3`` of the load
    outside (equilibrium asks 1)."""
    from numpy.polynomial import legendre as npleg

    case, res = S.case, S.result
    zg, wg = npleg.leggauss(16)
    b = np.asarray(R_EQ_PANELS) * res.a
    lo, hi = b[:-1, None], b[1:, None]
    r = (0.5 * (hi - lo) * zg + 0.5 * (hi + lo)).ravel()
    w = (0.5 * (hi - lo) * wg).ravel()
    z = float(sum(L.h for L in case.body2.layers))
    szz = S.field(r, [z]).sigma[0, 2]
    return float(-np.sum(szz * 2.0 * math.pi * r * w) / case.W), (z / b[-1]) ** 3


def _axisym_method():
    from coathertz.axisym import AxisymMethod

    return AxisymMethod(keep_fields=False)


def _deepest(by_id: dict, order: list[str]) -> str | None:
    """The case whose deepest interface :func:`analyse_interfaces` integrates (the first of the
    stacks, else of all, with the largest depth), if every case's stresses are found."""
    depth = {cid: float(np.cumsum([L.h for L in by_id[cid].case.body2.layers])[-1]) for cid in order
             if by_id[cid].case.body2.layers}
    stacks = [c for c in depth if c != "coating-only"] or list(depth)
    return max(stacks, key=depth.__getitem__) if stacks else None


def _interfaces_job(job: tuple) -> tuple | float:
    """One case's interface stresses ``(rows, jump, interface_load or None)``; ``(None, _)``: the
    frictionless check's shear."""
    from coathertz.axisym.stresses import AxisymStresses

    sc, with_load = job
    m = _axisym_method()
    if sc is None:
        return shear_on_frictionless(m)
    S = AxisymStresses(sc.case, m.solve(sc.case), cut=CUT)
    rows, jump = interface_stresses(S)
    return rows, jump, (interface_load(S) if with_load else None)


def analyse_interfaces(result: C.StudyResult) -> None:
    """Interface stresses of every case the exact method solved (re-solved here: the rows keep
    scalars only; milliseconds each), the traction continuity and shear-free checks, and the
    equilibrium of one interface."""
    done = {r["case"] for r in result.rows if r["method"] == "axisym"}
    if not done:
        return
    from coathertz.axisym.stresses import AxisymStresses

    t0 = time.process_time()
    m = _axisym_method()
    by_id = {sc.id: sc for sc in cases(result.resolution)}
    order = sorted(done, key=list(by_id).index)
    # every case's solve and stresses are independent (and the frictionless check's): side by
    # side on the run's worker count; the equilibrium integral on the case expected to have the
    # deepest interface (computed here after all if another one turns out to be it)
    deep = _deepest(by_id, order)
    found = fork_map(_interfaces_job, [(by_id[cid], cid == deep) for cid in order] + [(None, False)],
                     result.workers)
    tau = found.pop()
    rows, jump, loads = [], 0.0, {}
    for cid, o in zip(order, found, strict=True):
        sc = by_id[cid]
        if isinstance(o, CoatHertzError):  # reported, not fatal: one case must not sink the study
            result.failures.append({"case": cid, **sc.params, "method": "axisym-interfaces",
                                    "error": str(o)})
            continue
        if isinstance(o, Exception):
            raise o
        ir, j, loads[cid] = o
        jump = max(jump, j)
        rows += [{"case": cid, **sc.params, **x} for x in ir]
    result.extra["interface_stresses"] = rows
    if not rows:
        return
    if isinstance(tau, Exception):
        raise tau
    n_itf = len(rows)
    result.claims.append(C.Claim(
        "multilayer-bonded-tractions-continuous",
        "max over the cases and bonded interfaces of the jump of sigma_zz and sigma_rz between the "
        "layers above and below, over p0 (exact method's stresses)", jump, f"< {ROUNDOFF_BOUND:g}",
        jump < ROUNDOFF_BOUND, "", 1e-12,
        f"{n_itf} interfaces, {SCAN_RHO[::SCAN_STEP].size} radii each", judged_against="axisym"))
    Ei, hi = FRICTIONLESS_CASE
    bonded = next(x["tau_max"] for x in rows if x.get("E_i") == Ei and x.get("h_i") == hi
                  and x["interface"] == 1) if any(
        x.get("E_i") == Ei and x.get("h_i") == hi for x in rows) else math.nan
    result.claims.append(C.Claim(
        "multilayer-frictionless-shear-free",
        f"max |sigma_rz| / p0 on both faces of a frictionless TiN/interlayer interface "
        f"(E_i/E_s = {Ei:g}, h_i = {hi * 1e6:g} um; exact method's stresses)", tau,
        f"< {ROUNDOFF_BOUND:g}", tau < ROUNDOFF_BOUND, "", 1e-12,
        f"bonded, the same interface carries {bonded:.3f} p0", judged_against="axisym"))
    stacks = [x for x in rows if x["case"] != "coating-only"]
    eq_id = max(stacks or rows, key=lambda x: x["z"])["case"]
    if loads.get(eq_id) is None:
        sc = by_id[eq_id]
        loads[eq_id] = interface_load(AxisymStresses(sc.case, m.solve(sc.case), cut=CUT))
    load, tail = loads[eq_id]
    err = abs(load - 1.0)
    result.claims.append(C.Claim(
        "multilayer-interface-equilibrium",
        f"|-int sigma_zz 2 pi r dr / W - 1| at the deepest interface (case {eq_id}, z = "
        f"{max(x['z'] for x in rows if x['case'] == eq_id) * 1e6:g} um), r to "
        f"{R_EQ_PANELS[-1]:g} a", err, f"< {EQUILIBRIUM_BOUND:g}", err < EQUILIBRIUM_BOUND, "", 1e-5,
        f"load outside the radial rule ~ (z/r_max)^3 = {tail:.1e} W", judged_against="axisym"))
    worst = max(rows, key=lambda x: x["tau_max"])
    tens = max(rows, key=lambda x: x["szz_max"])
    result.claims.append(C.Claim(
        "multilayer-interface-stresses",
        "largest interface shear |sigma_rz| / p0 over the cases (observation; per interface: "
        "extra['interface_stresses'] and the figure)", worst["tau_max"], "(observation)", None, "",
        1e-3,
        f"{worst['name']} of {worst['case']} at r = {worst['r_tau']:.2f} a; largest sigma_zz / p0 "
        f"{tens['szz_max']:+.2e} ({tens['name']} of {tens['case']}, r = {tens['r_szz']:.2f} a)",
        judged_against=f"axisym, {len(done)} cases"))
    result.extra["interface_cpu_s"] = time.process_time() - t0  # this process (not the forked solves)


def plot(result: C.StudyResult, outdir) -> list:
    ref = _reference_rows(result)
    base = ref.get("coating-only")
    fig, axes = C.figure(3, width=3.6, height=3.2)
    ratios = sorted({r["E_i"] for r in result.rows if r["case"] != "coating-only"})
    labels = {"delta": r"$\delta$", "a": "a", "p0": r"$p_0$"}
    for j, q in enumerate(QS):
        ax = axes[0, j]
        for i, Ei in enumerate(ratios):
            col = C.colour(i, len(ratios))
            for m in sorted({r["method"] for r in result.rows}):
                pts = sorted((r["h_i"] * 1e6, 100.0 * (r[q] / base[q] - 1.0)) for r in result.rows
                             if r["method"] == m and r.get("E_i") == Ei and base is not None)
                if not pts:
                    continue
                is_ref = all(result.reference.get(r["case"]) == m for r in result.rows
                             if r["method"] == m and r.get("E_i") == Ei)
                ax.plot([p[0] for p in pts], [p[1] for p in pts],
                        **{**C.method_style(m, col), "ls": "-" if is_ref else "none"},
                        label=f"$E_i/E_s$ = {Ei:g} ({m})")
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xscale("log")
        ax.set_xlabel(r"interlayer thickness $h_i$ [$\mu$m]")
        ax.set_ylabel(f"{labels[q]} / coating-only - 1 [%]")
        ax.set_title(f"{labels[q]}", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0, -1].legend(fontsize=6, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.suptitle("Layer stacks: 3 um TiN over an interlayer on steel, rigid sphere R = 5 mm, W = 2 N; "
                 "change against TiN alone (lines: reference, markers: other methods)", fontsize=9)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    paths = C.save(fig, outdir, "multilayer")
    rows = result.extra.get("interface_stresses", [])
    if rows:
        paths += plot_interfaces(rows, outdir)
    return paths


def plot_interfaces(rows: list[dict], outdir) -> list:
    """Largest interface shear at both interfaces and largest interface sigma_zz under the TiN,
    against the interlayer's thickness, one line per modulus ratio; TiN alone dashed."""
    fig, axes = C.figure(3, width=3.6, height=3.2)
    base = [r for r in rows if r["case"] == "coating-only"]
    ratios = sorted({r["E_i"] for r in rows if r["case"] != "coating-only"})
    panels = ((1, "tau_max", r"max $|\sigma_{rz}|/p_0$", "TiN/interlayer: shear"),
              (2, "tau_max", r"max $|\sigma_{rz}|/p_0$", "interlayer/steel: shear"),
              (1, "szz_max", r"max $\sigma_{zz}/p_0$ (tension > 0)", r"TiN/interlayer: $\sigma_{zz}$"))
    for ax, (itf, key, ylabel, title) in zip(axes[0], panels, strict=True):
        for i, Ei in enumerate(ratios):
            pts = sorted((r["h_i"] * 1e6, r[key]) for r in rows
                         if r["case"] != "coating-only" and r["E_i"] == Ei and r["interface"] == itf)
            if pts:
                ax.plot(*zip(*pts, strict=True), "o-", color=C.colour(i, len(ratios)), ms=4,
                        label=f"$E_i/E_s$ = {Ei:g}")
        if base:
            ax.axhline(base[0][key], color="k", ls="--", lw=0.8, label="TiN alone (TiN/steel)")
        ax.set_xscale("log")
        if key == "szz_max":
            ax.set_yscale("symlog", linthresh=1e-4)
            ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlabel(r"interlayer thickness $h_i$ [$\mu$m]")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0, -1].legend(fontsize=6, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.suptitle("Interface stresses of the stacks (exact method's stresses, axisym): 3 um TiN over an "
                 "interlayer on steel, rigid sphere R = 5 mm, W = 2 N", fontsize=9)
    fig.set_layout_engine("tight")
    return C.save(fig, outdir, "multilayer_interfaces")
