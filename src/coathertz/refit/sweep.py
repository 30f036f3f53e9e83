"""Training and validation sweeps: design points, their cases, and their bars from a method.

A sweep is a table (dict of equal-length columns) of

* inputs: ``config`` (``elastic``, ``rigid``, ``ellipse``), ``E``, ``H``, ``nu_c``, ``nu_s``,
  ``rho`` (= Rx/Ry, 1 for circles), ``set`` (``train`` or ``valid``);
* outputs: the bars of eq (7) ``a_bar, delta_bar, p_bar`` (and ``r_a_bar, r_b_bar``), and
  ``r_p0_bar`` (radius of the maximum pressure over the contact radius, where the method
  reports it; NaN otherwise).

Training and validation points come from two different scrambled Sobol sequences (and the
training set adds the corners and edge midpoints of the box), so no validation point is ever a
training point. Results are computed through the result store
(:func:`coathertz.runner.run_tasks`): a rerun reuses them.
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from coathertz.case import ContactCase, bars
from coathertz.errors import CoatHertzError
from coathertz.hertz import hertz_circular
from coathertz.materials import RIGID, Body, Coating, Material

R_SPHERE = 10e-3  # [m]
W_LOAD = 1.0  # [N]
E_SUBSTRATE = 200e9  # [Pa]
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
OUTPUTS = ("a_bar", "delta_bar", "p_bar", "r_a_bar", "r_b_bar", "r_p0_bar")
INPUTS = ("config", "set", "E", "H", "nu_c", "nu_s", "rho")


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
        for k, v in bars_of(p, c, sr.result).items():
            table[k].append(float(v))
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


#: Shared case-model modules hashed into every method's code version (TEAM.md interface).
CASE_MODEL = ("coathertz.case", "coathertz.materials", "coathertz.hertz", "coathertz.results",
              "coathertz.units")


def method_code_version(method) -> str:
    """Version key of a method's numbers: package version + hash of its ``source_packages`` and the
    shared case model (the store's per-method versioning of the team interface), so that editing
    the fitting code does not invalidate stored solver results. Methods without
    ``source_packages`` fall back to :func:`coathertz.store.code_version`."""
    import importlib
    from pathlib import Path

    import coathertz
    from coathertz.store import code_version

    pkgs = getattr(type(method), "source_packages", None)
    if not pkgs:
        return code_version()
    h = hashlib.sha256()
    for name in (*pkgs, *CASE_MODEL):
        mod = importlib.import_module(name)
        path = Path(mod.__file__)
        files = sorted(path.parent.rglob("*.py")) if path.name == "__init__.py" else [path]
        for f in files:
            h.update(f.name.encode())
            h.update(f.read_bytes())
    return f"{coathertz.__version__}+{method.name}-{h.hexdigest()[:12]}"


def design_lines(config: str, nu_c_values: Sequence[float], n: int, which: str = "train",
                 offset: float = 0.0) -> list[Point]:
    """``n`` log-spaced H in the box of ``config`` at each fixed ``nu_c`` (``offset`` in [0, 1)
    shifts the H grid by that fraction of a step, so validation lines fall between training
    lines). Used for the nearly incompressible end on a rigid substrate (nu_c -> 0.5), which
    uniform sampling in nu_c leaves sparse."""
    lo, hi = BOX[config]["log10_H"]
    step = (hi - lo) / max(n - 1, 1)
    logs = lo + step * (np.arange(n) + offset)
    logs = logs[logs <= hi + 1e-12]
    return [Point(config, 1.0, round(10 ** float(x), 10), float(nu), 0.3, 1.0, which)
            for nu in nu_c_values for x in logs]
