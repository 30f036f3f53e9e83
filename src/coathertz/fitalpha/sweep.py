"""Training and validation sweeps: design points, their cases, and their bars from a method.

A sweep is a table (dict of equal-length columns) of

* inputs: ``config`` (``elastic``, ``rigid``, ``ellipse``, ``indenter``: an elastic ball), ``E``,
  ``H``, ``nu_c``, ``nu_s``, ``rho`` (= Rx/Ry, 1 for circles), ``gamma`` (the elastic indenter's
  ``E_ref/Ec*``, 1 for a rigid one), ``set`` (``train`` or ``valid``);
* outputs: the bars of eq (7) ``a_bar, delta_bar, p_bar`` (and ``r_a_bar, r_b_bar``; NaN in
  the circular ``indenter`` rows, where they equal ``a_bar``),
  ``r_p0_bar`` (radius of the maximum pressure over the contact radius, where the method
  reports it; NaN otherwise), and where computed (:func:`axis_and_ring`) ``p_axis_bar`` (the
  pressure on the axis) and ``p_ring_bar`` (the largest pressure on 0.2 a <= r <= a).

Sets: ``train`` (the tensor design grids), ``valid`` (Sobol points, never on a grid), ``patch``
and ``ring`` (local grids of the p0 branches of the corrected form).

Training points lie on Chebyshev--Lobatto tensor grids (elastic: in the reduced coordinates
of :mod:`coathertz.closedform.refit.reduced`), validation points come from scrambled Sobol sequences of the
original box, so no validation point is ever a training point. Results are computed through the result store
(:func:`coathertz.runner.run_tasks`): a rerun reuses them.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from coathertz.case import ContactCase, bars
from coathertz.closedform.hertz import hertz_circular
from coathertz.closedform.refit.rule_format import RING_BOX
from coathertz.errors import CoatHertzError
from coathertz.materials import RIGID, Body, Coating, Material

R_SPHERE = 10e-3  # [m]
W_LOAD = 1.0  # [N]
E_SUBSTRATE = 200e9  # [Pa]
#: Poisson's ratio of the elastic indenter of the ``indenter`` sweep (frictionless contact: only
#: its plane-strain modulus enters the normal problem).
NU_INDENTER = 0.3
W_ELLIPSE = 400.0  # [N] (Section 5)
RY_ELLIPSE = 3e-3  # [m] (Section 5), Rx = rho * Ry

#: Default boxes of each configuration: (log10 H), (log10 E), nu_c, nu_s, (log10 rho).
#: Elastic training covers H in [0.01, 10]: the exact axisymmetric method costs ~H^-1.5 (tens of
#: seconds per case at H = 0.001 on the shared cores), so there the thin band H in [0.001, 0.01) is
#: covered by validation points only (:data:`THIN`), where alpha is held at its H = 0.01 value (the
#: bars differ from 1 by < 3 % there). On a rigid substrate the thin band is where the bars change
#: most (alpha follows a power of H), so rigid training covers H in [0.001, 10].
BOX = {
    "elastic": {"log10_H": (-2.0, 1.0), "log10_E": (-1.0, 1.0), "nu_c": (0.0, 0.49), "nu_s": (0.0, 0.49)},
    "rigid": {"log10_H": (-3.0, 1.0), "nu_c": (0.0, 0.5)},
    "ellipse": {"log10_H": (-2.0, math.log10(3.0)), "log10_E": (math.log10(0.25), math.log10(4.0)),
                "log10_rho": (0.0, 1.0)},
}
#: The thin band (validation only).
THIN = {
    "elastic": {**BOX["elastic"], "log10_H": (-3.0, -2.0)},
}
OUTPUTS = ("a_bar", "delta_bar", "p_bar", "r_a_bar", "r_b_bar", "r_p0_bar", "p_axis_bar", "p_ring_bar")
INPUTS = ("config", "set", "E", "H", "nu_c", "nu_s", "rho", "gamma")


@dataclass(frozen=True)
class Point:
    """One sweep point (inputs only)."""

    config: str
    E: float
    H: float
    nu_c: float = 0.3
    nu_s: float = 0.3
    rho: float = 1.0
    set: str = "train"
    #: The elastic indenter's share of the thick-coating compliance, ``gamma = E_ref/Ec*``
    #: (:mod:`coathertz.closedform.refit.indenter`); 1 for a rigid indenter.
    gamma: float = 1.0

    def case(self) -> ContactCase:
        return make_case(self)


def make_case(p: Point) -> ContactCase:
    """The contact case of a sweep point: a rigid indenter on a coated half-space.

    Elastic and ellipse: substrate 200 GPa, ``Ec* = E Es*``, ``h = H a0s`` (eq 7a);
    rigid: coating 200 GPa on a rigid substrate, ``h = H a0c`` (eq 7b). Circles: sphere of
    10 mm, W = 1 N; ellipses: Ry = 3 mm, Rx = rho Ry, W = 400 N (Section 5's load).
    """
    if p.config == "rigid":
        coat = Material(E_SUBSTRATE, p.nu_c)
        h = p.H * float(hertz_circular(W_LOAD, R_SPHERE, coat.E_star).a0)
        return ContactCase(Body.rigid_sphere(R_SPHERE), Body.half_space(RIGID, Coating(coat, h)), W_LOAD)
    sub = Material(E_SUBSTRATE, p.nu_s)
    coat = Material(p.E * sub.E_star * (1.0 - p.nu_c**2), p.nu_c)
    if p.config == "elastic":
        a0s = float(hertz_circular(W_LOAD, R_SPHERE, sub.E_star).a0)
        return ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, coat, p.H * a0s, sub)
    if p.config == "indenter":
        if not 0.0 < p.gamma < 1.0:
            raise CoatHertzError(f"indenter sweep point: gamma must lie in (0, 1), got {p.gamma!r}")
        Ei_star = p.gamma * coat.E_star / (1.0 - p.gamma)  # gamma = E_ref/Ec*, 1/E_ref = 1/Ec* + 1/Ei*
        ind = Material(Ei_star * (1.0 - NU_INDENTER**2), NU_INDENTER)
        a0s = float(hertz_circular(W_LOAD, R_SPHERE, 1.0 / (1.0 / Ei_star + 1.0 / sub.E_star)).a0)
        return ContactCase.sphere_on_coated_half_space(R_SPHERE, W_LOAD, coat, p.H * a0s, sub, indenter=ind)
    if p.config == "ellipse":
        ind = Body(RIGID, None, p.rho * RY_ELLIPSE, RY_ELLIPSE, name="rigid ellipsoid")
        base = ContactCase(ind, Body.half_space(sub, Coating(coat, 0.0)), W_ELLIPSE)
        return ContactCase(ind, Body.half_space(sub, Coating(coat, p.H * base.a0s)), W_ELLIPSE)
    raise CoatHertzError(f"config must be elastic, rigid or ellipse; got {p.config!r}")


def _unit_points(d: int, n: int, seed: int, corners: bool) -> np.ndarray:
    from scipy.stats import qmc

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # balance properties need n = 2^m; not needed here
        u = qmc.Sobol(d, scramble=True, seed=seed).random(n) if n else np.empty((0, d))
    if corners:
        grid = np.array(np.meshgrid(*([[0.0, 0.5, 1.0]] * d), indexing="ij")).reshape(d, -1).T
        u = np.vstack([grid, u])
    return u


def design(config: str, n: int, which: str = "train", seed: int | None = None,
           box: Mapping[str, tuple[float, float]] | None = None, nu: float = 0.3) -> list[Point]:
    """``n`` quasi-random points of ``config`` (``train`` adds the 3^d box grid points).

    Training and validation use different Sobol seeds (``seed`` default: 1 for train,
    2 for valid). Variables absent from a configuration's box are fixed (``nu`` for the
    Poisson's ratios of ellipses, E = 1 for the rigid substrate where E plays no role).
    """
    if which not in ("train", "valid"):
        raise CoatHertzError(f"which must be 'train' or 'valid', got {which!r}")
    if config not in BOX:
        raise CoatHertzError(f"config must be one of {sorted(BOX)}, got {config!r}")
    box = dict(box or BOX[config])
    names = list(box)
    seed = (1 if which == "train" else 2) if seed is None else seed
    u = _unit_points(len(names), n, seed, corners=which == "train")
    pts = []
    for row in u:
        v = {k: box[k][0] + r * (box[k][1] - box[k][0]) for k, r in zip(names, row, strict=True)}
        pts.append(Point(
            config,
            E=round(10 ** v["log10_E"], 10) if "log10_E" in v else 1.0,
            H=round(10 ** v["log10_H"], 10),
            nu_c=round(v.get("nu_c", nu), 10),
            nu_s=round(v.get("nu_s", nu), 10),
            rho=round(10 ** v.get("log10_rho", 0.0), 10),
            set=which,
        ))
    return pts


def bars_of(p: Point, case: ContactCase, res: Mapping) -> dict[str, float]:
    """The bars (eq 7 normalisation) of a stored result dict."""
    r_p0 = (res.get("meta") or {}).get("r_p0")
    return {**bars(case, res), "r_p0_bar": math.nan if r_p0 is None else float(r_p0) / res["a"]}


def collect(points: Sequence[Point], method, store, *, workers: int = 1, progress: bool = False,
            desc: str = "refit sweep") -> dict[str, list]:
    """Solve every point with ``method`` through ``store`` and return the sweep table."""
    from coathertz.runner import Task, run_tasks

    cases = [make_case(p) for p in points]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        outcome = run_tasks([Task(c, method) for c in cases], store, workers=workers,
                            progress=progress, desc=desc)
    table: dict[str, list] = {k: [] for k in (*INPUTS, *OUTPUTS)}
    failed = []
    for p, c in zip(points, cases, strict=True):
        sr = outcome.get(c, method)
        if sr is None or not sr.ok:
            failed.append((p, None if sr is None else sr.error))
            continue
        for k in INPUTS:
            table[k].append(getattr(p, k))
        b = bars_of(p, c, sr.result)
        if p.config == "indenter":  # circular: r_a = r_b = a; not stored (keeps the shipped sweep small)
            b = {**b, "r_a_bar": math.nan, "r_b_bar": math.nan}
        for k in OUTPUTS:
            table[k].append(float(b.get(k, math.nan)))
    table["failed"] = [{"point": p.__dict__, "error": e} for p, e in failed]  # type: ignore[assignment]
    return table


def select(table: Mapping[str, Sequence], **equal) -> dict[str, np.ndarray]:
    """Columns (as arrays) of the rows whose inputs equal ``equal`` (e.g. config="rigid")."""
    keep = np.ones(len(table["H"]), dtype=bool)
    for k, v in equal.items():
        keep &= np.asarray(table[k]) == v
    return {k: np.asarray(table[k])[keep] for k in (*INPUTS, *OUTPUTS) if k in table}


def table_hash(table: Mapping[str, Sequence]) -> str:
    """SHA-256 (first 16 hex) of the input and output columns, rounded to 12 digits."""
    cols = {k: [round(float(x), 12) if not isinstance(x, str) else x for x in table[k]]
            for k in (*INPUTS, *OUTPUTS) if k in table}
    text = json.dumps(cols, sort_keys=True, default=str).replace("NaN", "null")
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def spot_check(table: Mapping[str, Sequence], method, store, n: int = 12, seed: int = 0) -> dict:
    """Solve ``n`` training and ``n`` validation points of each circular configuration with another
    ``method`` (e.g. the FFT) and return the largest |difference| [%] of its bars from the sweep's.

    An independent check that the training data (the exact axisymmetric method) and the
    validation data are right, on both sets.
    """
    rng = np.random.default_rng(seed)
    out: dict = {"method": method.name, "settings": dict(method.settings()), "per_set": {}}
    for config in ("elastic", "rigid"):
        for which in ("train", "valid"):
            cols = select(table, config=config, set=which)
            if len(cols["H"]) == 0:
                continue
            idx = rng.choice(len(cols["H"]), size=min(n, len(cols["H"])), replace=False)
            pts = [Point(config, float(cols["E"][i]), float(cols["H"][i]), float(cols["nu_c"][i]),
                         float(cols["nu_s"][i]), 1.0, which) for i in idx]
            got = collect(pts, method, store)
            keyed = {(float(cols["E"][i]), float(cols["H"][i]), float(cols["nu_c"][i]),
                      float(cols["nu_s"][i])): i for i in idx}
            rows = [keyed[k] for k in zip(got["E"], got["H"], got["nu_c"], got["nu_s"], strict=True)]
            diffs: dict[str, float] = {}
            for q in ("a_bar", "delta_bar", "p_bar"):
                d = 100.0 * np.abs(np.asarray(got[q]) / np.asarray(cols[q])[rows] - 1.0)
                diffs[q] = round(float(d.max()), 4) if d.size else float("nan")
            out["per_set"][f"{config}/{which}"] = {"n": len(got["H"]), "failed": len(got["failed"]),
                                                   "max_abs_diff_percent": diffs}
    return out


def method_code_version(method) -> str:
    """Version key of a method's numbers in the sweep: the store's per-method
    :func:`coathertz.store.code_version` (its source packages, the shared case model and the
    validity rule), so that editing the fitting code does not invalidate stored solutions."""
    from coathertz.store import code_version

    return code_version(method.name)


def lobatto(n: int, lo: float, hi: float) -> np.ndarray:
    """``n`` Chebyshev--Lobatto nodes (the extrema of T_{n-1}, ends included) on ``[lo, hi]``,
    ascending. Grids of ``2^k + 1`` nodes nest: every other node of 33 is the grid of 17."""
    x = -np.cos(np.pi * np.arange(n) / (n - 1))
    x[np.abs(x) < 1e-15] = 0.0
    return lo + 0.5 * (x + 1.0) * (hi - lo)


#: Box of the reduced elastic coordinates (log10 H, log10 E, s); s of
#: :mod:`coathertz.closedform.refit.reduced` covers nu_c, nu_s in [0, 1/2].
REDUCED_BOX = {"log10_H": (-3.0, 1.0), "log10_E": (-1.0, 1.0), "s": (0.0, 1.0)}
#: Box of the rigid substrate: (log10 H, nu_c) with nu_c in [0, 1/2] (incompressible included).
RIGID_BOX = {"log10_H": (-3.0, 1.0), "nu_c": (0.0, 0.5)}


def design_grid_elastic(shape: tuple[int, int, int] = (33, 17, 17), which: str = "train") -> list[Point]:
    """Tensor Chebyshev--Lobatto design grid of the elastic substrate in the reduced coordinates
    ``(log10 H, log10 E, s)`` (:data:`REDUCED_BOX`); each ``s`` is realised by the pair
    ``(nu_c, nu_s)`` of :func:`coathertz.closedform.refit.reduced.poisson_of` (any pair with the same s
    gives the same bars)."""
    from coathertz.closedform.refit.reduced import poisson_of

    lh = lobatto(shape[0], *REDUCED_BOX["log10_H"])
    le = lobatto(shape[1], *REDUCED_BOX["log10_E"])
    ss = lobatto(shape[2], *REDUCED_BOX["s"])
    pts = []
    for x in le:
        E = round(10.0 ** float(x), 12)
        for s in ss:
            nu_c, nu_s = poisson_of(E, float(s))
            pts += [Point("elastic", E, round(10.0 ** float(h), 12), nu_c, nu_s, 1.0, which) for h in lh]
    return pts


def design_grid_rigid(shape: tuple[int, int] = (65, 33), which: str = "train") -> list[Point]:
    """Tensor Chebyshev--Lobatto design grid of the rigid substrate in ``(log10 H, t(nu_c))``
    with ``t`` of :func:`coathertz.closedform.refit.model.t_nu` (which spreads the incompressible end)."""
    from coathertz.closedform.refit.model import NU_EPS, T_NU

    lh = lobatto(shape[0], *RIGID_BOX["log10_H"])
    tt = lobatto(shape[1], *T_NU)
    nus = np.clip(0.5 * (1.0 + NU_EPS - 10.0 ** tt), 0.0, 0.5)
    return [Point("rigid", 1.0, round(10.0 ** float(h), 12), round(float(nu), 12), 0.3, 1.0, which)
            for nu in nus for h in lh]


def design_random(config: str, n: int, seed: int, which: str = "valid",
                  spread_nu: bool = False) -> list[Point]:
    """``n`` scrambled-Sobol points of the *original* box (never on a design grid): elastic
    (log10 H, log10 E, nu_c, nu_s) over :data:`REDUCED_BOX`'s H and E and nu in [0, 1/2];
    rigid (log10 H, nu_c) over :data:`RIGID_BOX`, uniform in nu_c or (``spread_nu``) uniform in
    ``t(nu_c)`` of :func:`coathertz.closedform.refit.model.t_nu` (dense towards the incompressible end)."""
    from coathertz.closedform.refit.model import NU_EPS, T_NU

    if config == "elastic":
        box = {"log10_H": REDUCED_BOX["log10_H"], "log10_E": REDUCED_BOX["log10_E"], "nu_c": (0.0, 0.5),
               "nu_s": (0.0, 0.5)}
    else:
        box = {"log10_H": RIGID_BOX["log10_H"], "nu_c": T_NU if spread_nu else RIGID_BOX["nu_c"]}
    pts = design(config, n, "valid", seed=seed, box=box)
    if config == "rigid" and spread_nu:
        nus = np.clip(0.5 * (1.0 + NU_EPS - 10.0 ** np.array([p.nu_c for p in pts])), 0.0, 0.5)
        pts = [dataclasses.replace(p, nu_c=round(float(nu), 10)) for p, nu in zip(pts, nus, strict=True)]
    return [dataclasses.replace(p, set=which) for p in pts]


#: The two branches of p0: the largest pressure on ``r <= RING_RHO a`` (the axis branch; the peak can
#: move off the axis continuously) and on ``RING_RHO a <= r <= a`` (the ring branch); p0 is the larger.
RING_RHO = 0.4


def design_grid_ring(shape: tuple[int, int, int] = (33, 17, 17), which: str = "ring") -> list[Point]:
    """Chebyshev--Lobatto grid of :data:`~coathertz.closedform.refit.rule_format.RING_BOX` (rows of
    set ``ring``: the pressure on the axis and on the ring, :func:`axis_and_ring`)."""
    from coathertz.closedform.refit.reduced import poisson_of

    pts = []
    for x in lobatto(shape[1], *RING_BOX["log10_E"]):
        E = round(10.0 ** float(x), 12)
        for s in lobatto(shape[2], *RING_BOX["s"]):
            nu_c, nu_s = poisson_of(E, float(s))
            pts += [Point("elastic", E, round(10.0 ** float(h), 12), nu_c, nu_s, 1.0, which)
                    for h in lobatto(shape[0], *RING_BOX["log10_H"])]
    return pts


def design_random_ring(n: int, seed: int = 4) -> list[Point]:
    """``n`` Sobol validation points of :data:`~coathertz.closedform.refit.rule_format.RING_BOX`'s
    H and E with nu_c, nu_s in [0, 1/2]
    (where the peak pressure leaves the axis: the kink of p0)."""
    box = {"log10_H": RING_BOX["log10_H"], "log10_E": RING_BOX["log10_E"], "nu_c": (0.0, 0.5),
           "nu_s": (0.0, 0.5)}
    return design("elastic", n, "valid", seed=seed, box=box)


def axis_and_ring(points: Sequence[Point], method=None) -> dict[str, list[float]]:
    """The largest pressure on ``r <= RING_RHO a`` and on ``RING_RHO a <= r <= a`` (bars: over
    p0s) of each point, from the exact method's pressure profile (the largest sample refined by a
    parabola through it and its neighbours). Not stored in the result store: the profiles are
    not part of a stored result."""
    from coathertz.axisym.method import AxisymMethod

    m = method or AxisymMethod(keep_fields=True)
    out: dict[str, list[float]] = {"p_axis_bar": [], "p_ring_bar": []}
    for p in points:
        case = make_case(p)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = m.solve(case)
        r = np.asarray(res.fields["r"]) / res.a
        pr = np.asarray(res.fields["pressure"])
        branch = [_largest(r, pr, np.flatnonzero(r <= RING_RHO)),
                  _largest(r, pr, np.flatnonzero((r >= RING_RHO) & (r <= 1.0)))]
        p0 = case.normalisers.p0
        out["p_axis_bar"].append(float(branch[0] / p0))
        out["p_ring_bar"].append(float(branch[1] / p0))
    return out


def _largest(r: np.ndarray, p: np.ndarray, sel: np.ndarray) -> float:
    """Largest ``p`` on the samples ``sel``, refined by the vertex of a parabola through the best
    sample and its neighbours where it is inside."""
    k = sel[int(np.argmax(p[sel]))]
    best = float(p[k])
    if sel[0] < k < sel[-1]:
        x0, x1, x2 = r[k - 1 : k + 2]
        y0, y1, y2 = p[k - 1 : k + 2]
        den = (x0 - x1) * (x0 - x2) * (x1 - x2)
        A = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / den
        B = (x2**2 * (y0 - y1) + x1**2 * (y2 - y0) + x0**2 * (y1 - y2)) / den
        if A < 0:  # vertex of the parabola A x^2 + B x + C through the three samples
            best = max(best, float(y1 - A * x1**2 - B * x1 - B * B / (4.0 * A)))
    return best


#: The stiff-coating patch of p0's axis branch (:mod:`coathertz.closedform.refit.corrected`): E >= 2 (log10 E
#: in [log10 2, 1]) over the whole H range, with H through the stretched coordinate ``xi_H``
#: (:func:`coathertz.closedform.refit.model.xi_H`), which puts the nodes where p0 rises steeply (H ~ 0.1-1).
PATCH_BOX = {"log10_E": (math.log10(2.0), 1.0), "s": (0.0, 1.0)}


def design_grid_patch(shape: tuple[int, int, int] = (49, 17, 17), which: str = "patch") -> list[Point]:
    """Chebyshev--Lobatto grid in ``(xi_H, log10 E, s)`` over :data:`PATCH_BOX` (set ``patch``)."""
    from coathertz.closedform.refit.model import XI_H, log10_H_of_xi
    from coathertz.closedform.refit.reduced import poisson_of

    pts = []
    for x in lobatto(shape[1], *PATCH_BOX["log10_E"]):
        E = round(10.0 ** float(x), 12)
        for s in lobatto(shape[2], *PATCH_BOX["s"]):
            nu_c, nu_s = poisson_of(E, float(s))
            pts += [Point("elastic", E, round(10.0 ** float(log10_H_of_xi(xi)), 12), nu_c, nu_s, 1.0, which)
                    for xi in lobatto(shape[0], *XI_H)]
    return pts


def add_axis_and_ring(table: dict[str, list]) -> int:
    """Fill ``p_axis_bar`` and ``p_ring_bar`` (:func:`axis_and_ring`) in the elastic rows that need
    them: every ``ring`` row, and the ``train``/``patch`` rows whose peak lies beyond
    ``RING_RHO a``. Returns how many rows were solved again (with the pressure profile)."""
    cols = zip(table["config"], table["set"], table["r_p0_bar"], strict=True)
    rows = [i for i, (c, w, r) in enumerate(cols)
            if c == "elastic" and (w == "ring" or (w in ("train", "patch") and r > RING_RHO))]
    pts = [Point("elastic", table["E"][i], table["H"][i], table["nu_c"][i], table["nu_s"][i]) for i in rows]
    got = axis_and_ring(pts)
    for j, i in enumerate(rows):
        table["p_axis_bar"][i] = got["p_axis_bar"][j]
        table["p_ring_bar"][i] = got["p_ring_bar"][j]
    return len(rows)


def design_faces_ellipse(n_H: int = 13, n_other: int = 9, n_valid: int = 40) -> list[Point]:
    """Points on the faces of the ellipse box where the correction does not vanish: Rx/Ry = 10 and
    E = 1/4, E = 4. Training: Chebyshev--Lobatto grids (``n_H`` in log10 H times ``n_other`` in the
    other free variable); validation: ``n_valid`` Sobol points per face. A polynomial fitted to
    interior points is least constrained on the faces (a random validation set seldom reaches them)."""
    box = BOX["ellipse"]
    faces = (("log10_rho", box["log10_rho"][1]), ("log10_E", box["log10_E"][0]),
             ("log10_E", box["log10_E"][1]))
    pts = []
    for k, (fixed, value) in enumerate(faces):
        free = "log10_E" if fixed == "log10_rho" else "log10_rho"
        sub = {"log10_H": box["log10_H"], free: box[free]}
        grid = [(h, x) for x in lobatto(n_other, *sub[free]) for h in lobatto(n_H, *sub["log10_H"])]
        rand = [(p.H, p.E if free == "log10_E" else p.rho)
                for p in design("ellipse", n_valid, "valid", seed=10 + k, box=sub)]
        for which, rows in (("train", [(10.0**h, 10.0**x) for h, x in grid]), ("valid", rand)):
            for H, x in rows:
                v = {fixed: 10.0**value, free: x}
                E = v.get("log10_E", 1.0)
                rho = v.get("log10_rho", 1.0)
                pts.append(Point("ellipse", round(float(E), 10), round(float(H), 10), 0.3, 0.3,
                                 round(float(rho), 10), which))
    return pts


#: Box of the elastic-indenter sweep (config ``indenter``): the elastic box plus the indenter's
#: share ``gamma`` of the thick-coating compliance (:mod:`coathertz.closedform.refit.indenter`).
INDENTER_BOX = {**REDUCED_BOX, "gamma": (0.0, 1.0)}


def design_grid_indenter(shape: tuple[int, int, int, int] = (33, 11, 9, 9),
                         which: str = "train") -> list[Point]:
    """Tensor Chebyshev--Lobatto grid of the elastic indenter in ``(log10 H, log10 E, s, gamma)``
    over :data:`INDENTER_BOX`; the ends gamma = 0 (Hertz) and 1 (the rigid indenter, the
    ``elastic`` rows) are left out, where the correction vanishes."""
    from coathertz.closedform.refit.reduced import poisson_of

    box = INDENTER_BOX
    gs = lobatto(shape[3], *box["gamma"])[1:-1]
    pts = []
    for x in lobatto(shape[1], *box["log10_E"]):
        E = round(10.0 ** float(x), 12)
        for s in lobatto(shape[2], *box["s"]):
            nu_c, nu_s = poisson_of(E, float(s))
            for g in gs:
                pts += [Point("indenter", E, round(10.0 ** float(h), 12), nu_c, nu_s, 1.0, which,
                              round(float(g), 12)) for h in lobatto(shape[0], *box["log10_H"])]
    return pts


def design_random_indenter(n: int, seed: int = 5, which: str = "valid") -> list[Point]:
    """``n`` scrambled-Sobol validation points of the elastic indenter: log10 H, log10 E over
    :data:`INDENTER_BOX`, nu_c, nu_s in [0, 1/2], gamma in [0.02, 0.98]."""
    box = {"log10_H": INDENTER_BOX["log10_H"], "log10_E": INDENTER_BOX["log10_E"], "nu_c": (0.0, 0.5),
           "nu_s": (0.0, 0.5), "gamma": (0.02, 0.98)}
    u = _unit_points(len(box), n, seed, corners=False)
    pts = []
    for row in u:
        v = {k: lo + r * (hi - lo) for (k, (lo, hi)), r in zip(box.items(), row, strict=True)}
        pts.append(Point("indenter", round(10 ** v["log10_E"], 10), round(10 ** v["log10_H"], 10),
                         round(v["nu_c"], 10), round(v["nu_s"], 10), 1.0, which, round(v["gamma"], 10)))
    return pts

