"""``coathertz fit-alpha``: regenerate the refitted alpha data file from a stored sweep.

Two ways in:

* ``--sweep FILE``: refit from an exported sweep (JSON, e.g. the packaged
  ``coathertz/data/alpha_refit_sweep.json.gz``; gzip-compressed JSON is read and written by the
  suffix); no solver runs. This is how the shipped
  coefficients are reproduced (``--check`` compares them).
* otherwise: design the training and validation points, solve them with ``--method``
  (circular; default ``axisym``, the exact axisymmetric method) and the FFT (ellipses) through
  the result store ``--store`` (reusing stored results), export the sweep (``--export-sweep``),
  then fit.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

NAME = "fit-alpha"
HELP = "refit the extended-Hertz alpha to exact solutions from a stored sweep; writes the refit data file"

SWEEP_FORMAT = "coathertz-refit-sweep/1"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--sweep", type=Path, help="refit from this exported sweep (JSON) instead of solving")
    parser.add_argument("--method", default="axisym", help="method for the circular sweeps (default axisym)")
    parser.add_argument("--method-settings", default="{}", help="JSON settings of --method")
    parser.add_argument("--ellipse-n", type=int, default=128, help="FFT grid (n x n) for the ellipse sweep")
    parser.add_argument("--store", type=Path, default=Path("runs/refit/store.sqlite"),
                        help="result store of the sweeps (default runs/refit/store.sqlite)")
    parser.add_argument("--elastic-grid", default="33,17,17",
                        help="elastic training grid: Chebyshev-Lobatto nodes in log10 H, log10 E and "
                             "Dundurs' "
                             "s (coathertz.closedform.refit.reduced; default 33,17,17)")
    parser.add_argument("--rigid-grid", default="65,33",
                        help="rigid-substrate training grid: nodes in log10 H and t(nu_c) (default 65,33)")
    parser.add_argument("--valid-elastic", type=int, default=1500,
                        help="elastic validation points (Sobol in log10 H, log10 E, nu_c, nu_s)")
    parser.add_argument("--valid-ring", type=int, default=300,
                        help="further elastic validation points where the peak pressure may leave the axis "
                             "(sweep.RING_BOX)")
    parser.add_argument("--valid-rigid", type=int, default=300,
                        help="rigid validation points (Sobol, uniform in nu_c)")
    parser.add_argument("--valid-rigid-spread", type=int, default=200,
                        help="further rigid validation points uniform in t(nu_c) (dense towards nu_c = 0.5)")
    parser.add_argument("--indenter-grid", default="33,11,9,9",
                        help="elastic-indenter training grid: Chebyshev-Lobatto nodes in log10 H, log10 E, "
                             "Dundurs' s and gamma = E_ref/Ec* (the ends of gamma left out; "
                             "default 33,11,9,9)")
    parser.add_argument("--valid-indenter", type=int, default=700,
                        help="elastic-indenter validation points (Sobol in log10 H, log10 E, nu_c, nu_s, "
                             "gamma)")
    parser.add_argument("--train-ellipse", type=int, default=250, help="ellipse training points (+3^d box)")
    parser.add_argument("--valid-ellipse", type=int, default=120, help="ellipse validation points")
    parser.add_argument("--fallback-settings", default='{"rtol": 1e-10}',
                        help="JSON settings of --method for a second try of cases that fail (a safety "
                             "net: the stall of the exact method's load iteration at ~1e-12 that needed "
                             "it is now accepted as converged)")
    parser.add_argument("--reuse-sweep", action="append", default=[], metavar="FILE:CONFIG[,CONFIG]",
                        help="take the rows of these configurations from an exported sweep instead of "
                             "solving (e.g. runs/refit/fft128_sweep.json:ellipse)")
    parser.add_argument("--configs", default="elastic,rigid,ellipse,indenter",
                        help="configurations to solve (default elastic,rigid,ellipse,indenter)")
    parser.add_argument("--workers", type=int, default=1, help="worker processes for the solvers")
    parser.add_argument("--export-sweep", type=Path, help="write the sweep (JSON) here")
    parser.add_argument("--out", type=Path, help="write the data file here (default: print the summary only)")
    parser.add_argument("--spot-check", type=int, default=0, metavar="N",
                        help="solve N training and N validation points per circular configuration with "
                             "--spot-method and record the differences in the data file")
    parser.add_argument("--spot-method", default="fft", help="method of the spot checks (default fft)")
    parser.add_argument("--spot-settings", default='{"n": 256, "keep_fields": false, "workers": 1}',
                        help="JSON settings of --spot-method")
    parser.add_argument("--check", type=Path,
                        help="compare the fitted coefficients with this data file; exit 1 if they differ")


def _grid(text: str, dims: int, flag: str) -> tuple[int, ...]:
    """``"33,17,17"`` -> (33, 17, 17): ``dims`` node counts, each at least 2."""
    from coathertz.errors import CoatHertzError

    try:
        shape = tuple(int(x) for x in text.split(","))
    except ValueError:
        shape = ()
    if len(shape) != dims or min(shape) < 2:
        raise CoatHertzError(f"{flag} expects {dims} comma-separated integers >= 2 (nodes per "
                             f"axis), got {text!r}")
    return shape


def _read_text(path: Path) -> str:
    if path.suffix == ".gz":
        import gzip

        return gzip.decompress(path.read_bytes()).decode()
    return path.read_text()


def load_sweep(path: Path) -> tuple[dict, dict]:
    import zlib

    from coathertz.errors import CoatHertzError

    expect = "gzip-compressed JSON" if Path(path).suffix == ".gz" else "JSON"
    if Path(path).is_dir():
        raise CoatHertzError(f"--sweep {str(path)!r} is a folder; give an exported sweep file")
    try:
        d = json.loads(_read_text(Path(path)))
    except (EOFError, zlib.error, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise CoatHertzError(f"--sweep {str(path)!r} is not {expect} ({exc}); give a sweep written "
                             "by fit-alpha --export-sweep") from None
    except OSError as exc:
        if exc.errno is None:  # gzip.BadGzipFile: not a gzip file
            raise CoatHertzError(f"--sweep {str(path)!r} is not {expect} ({exc}); give a sweep "
                                 "written by fit-alpha --export-sweep") from None
        raise
    if not isinstance(d, dict) or not isinstance(d.get("columns"), dict):
        d = {"format": None} if not isinstance(d, dict) else d
    if d.get("format") != SWEEP_FORMAT or not isinstance(d.get("columns"), dict):
        raise CoatHertzError(f"{path}: not a refit sweep (format {d.get('format')!r}, "
                             f"expected {SWEEP_FORMAT!r})")
    cols = {k: [float("nan") if v is None else v for v in col] for k, col in d["columns"].items()}
    return cols, d.get("provenance", {})


def export_sweep(path: Path, table: dict, provenance: dict) -> None:
    import math

    def clean(v):
        if isinstance(v, float):
            return None if math.isnan(v) else float(f"{v:.12g}")
        return v

    cols = {k: [clean(v) for v in col] for k, col in table.items() if k != "failed"}
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps({"format": SWEEP_FORMAT, "provenance": provenance, "columns": cols},
                      separators=(",", ":"))
    if Path(path).suffix == ".gz":
        import gzip

        Path(path).write_bytes(gzip.compress(text.encode(), mtime=0))
    else:
        Path(path).write_text(text)


def solve_sweep(args) -> tuple[dict, dict]:
    from coathertz.fitalpha import sweep as S
    from coathertz.methods import get_method
    from coathertz.store import ResultStore, code_version

    settings = json.loads(args.method_settings)
    circ = get_method(args.method, **settings)
    ell = get_method("fft", n=args.ellipse_n, keep_fields=False, workers=1)
    tables, times, reused, fallback = [], {}, {}, {}
    for spec in args.reuse_sweep:
        path, _, cfgs = spec.rpartition(":")
        cols, prov = load_sweep(Path(path))
        for cfg in cfgs.split(","):
            tab = {k: list(v) for k, v in S.select(cols, config=cfg).items()}
            tab["failed"] = []
            tables.append(tab)
            reused[cfg] = {"file": Path(path).name, "rows": len(tab["H"]),
                           "method": prov.get("ellipse_method" if cfg == "ellipse" else "circular_method"),
                           "code_version": prov.get("code_version")}
    wanted = set(args.configs.split(","))
    plan = [(c, m) for c, m in (("elastic", circ), ("rigid", circ), ("indenter", circ), ("ellipse", ell))
            if c not in reused and c in wanted]
    for cfg, m in plan:
        if cfg == "elastic":
            eshape = _grid(args.elastic_grid, 3, "--elastic-grid")
            pts = (S.design_grid_elastic(eshape) + S.design_random("elastic", args.valid_elastic, 2)  # type: ignore[arg-type]
                   + S.design_random_ring(args.valid_ring) + S.design_grid_patch() + S.design_grid_ring())
        elif cfg == "indenter":
            ishape = _grid(args.indenter_grid, 4, "--indenter-grid")
            pts = S.design_grid_indenter(ishape) + S.design_random_indenter(args.valid_indenter)  # type: ignore[arg-type]
        elif cfg == "rigid":
            rshape = _grid(args.rigid_grid, 2, "--rigid-grid")
            pts = (S.design_grid_rigid(rshape) + S.design_random("rigid", args.valid_rigid, 2)  # type: ignore[arg-type]
                   + S.design_random("rigid", args.valid_rigid_spread, 3, spread_nu=True))
        else:
            pts = (S.design(cfg, args.train_ellipse) + S.design(cfg, args.valid_ellipse, "valid")
                   + S.design_faces_ellipse())
        t0 = time.perf_counter()
        with ResultStore(args.store, version=S.method_code_version(m)) as store:
            tab = S.collect(pts, m, store, workers=args.workers, progress=True, desc=f"refit {cfg}")
        if tab["failed"] and cfg != "ellipse":
            fb = get_method(args.method, **{**settings, **json.loads(args.fallback_settings)})
            again = [S.Point(**f["point"]) for f in tab["failed"]]
            with ResultStore(args.store, version=S.method_code_version(fb)) as store:
                tab2 = S.collect(again, fb, store, workers=args.workers, desc=f"refit {cfg} (fallback)")
            fallback[cfg] = {"settings": dict(fb.settings()), "cases": len(again),
                             "solved": len(again) - len(tab2["failed"]),
                             "first_error": tab["failed"][0]["error"]}
            for k in tab:
                if k != "failed":
                    tab[k] += tab2[k]
            tab["failed"] = tab2["failed"]
        if cfg == "elastic":
            S.add_axis_and_ring(tab)
        times[cfg] = round(time.perf_counter() - t0, 1)
        if tab["failed"]:
            print(f"fit-alpha: {len(tab['failed'])} {cfg} case(s) failed and are left out; first: "
                  f"{tab['failed'][0]}", file=sys.stderr)
        tables.append(tab)
    if not tables:
        from coathertz.errors import CoatHertzError

        raise CoatHertzError("fit-alpha: nothing to fit (check --configs and --reuse-sweep)")
    table = {k: [v for t in tables for v in t[k]] for k in tables[0] if k != "failed"}
    prov = {
        "code_version": code_version(),
        "method_code_version": {"circular": S.method_code_version(circ),
                                "ellipse": S.method_code_version(ell)},
        "circular_method": {"name": circ.name, "settings": dict(circ.settings())},
        "ellipse_method": {"name": ell.name, "settings": dict(ell.settings())},
        "solve_seconds": times,
        "fallback": fallback,
        "reused": reused,
        "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "store": str(args.store),
    }
    return table, prov


def compare(new: dict, old: dict) -> float:
    """Largest |difference| of alpha predicted by two data files on a fixed probe grid (relative)."""
    import numpy as np

    from coathertz.closedform.refit.rule import RefitRule

    a, b = RefitRule(new), RefitRule(old)
    E = np.geomspace(0.1, 10, 9)[:, None, None]
    H = np.geomspace(1e-3, 10, 13)[None, :, None]
    nu = np.array([0.0, 0.25, 0.49])[None, None, :]
    worst = 0.0
    for cfg in new["surfaces"]:
        if cfg not in old["surfaces"]:
            return float("inf")
        for q in new["surfaces"][cfg]:
            if cfg == "ellipse":
                from coathertz.closedform.refit import ellipse as EL

                x = EL.log_correction(a.ellipse_surfaces(), q, 2.0, H.ravel(), 3.0)
                y = EL.log_correction(b.ellipse_surfaces(), q, 2.0, H.ravel(), 3.0)
                worst = max(worst, float(np.max(np.abs(x - y))))
                continue
            ma, mb = a.model(cfg), b.model(cfg)
            x = ma.alpha(q, E, H, nu, 0.3) if cfg == "elastic" else ma.alpha(q, None, H, nu)
            y = mb.alpha(q, E, H, nu, 0.3) if cfg == "elastic" else mb.alpha(q, None, H, nu)
            worst = max(worst, float(np.max(np.abs(x / y - 1))))
    for cfg, v in new.get("corrected", {}).items():  # the corrected forms: coefficients
        for q, sd in v.get("surfaces", {}).items():
            od = old.get("corrected", {}).get(cfg, {}).get("surfaces", {}).get(q)
            if od is None or len(od["coef"]) != len(sd["coef"]):
                return float("inf")
            c1, c2 = np.asarray(sd["coef"]), np.asarray(od["coef"])
            worst = max(worst, float(np.max(np.abs(c1 - c2)) / max(np.max(np.abs(c2)), 1e-300)))
    for q, c in new.get("indenter", {}).get("coef", {}).items():  # the elastic-indenter form
        oc = old.get("indenter", {}).get("coef", {}).get(q)
        if oc is None or len(oc) != len(c) or old["indenter"]["degrees"] != new["indenter"]["degrees"]:
            return float("inf")
        c1, c2 = np.asarray(c), np.asarray(oc)
        worst = max(worst, float(np.max(np.abs(c1 - c2)) / max(np.max(np.abs(c2)), 1e-300)))
    if "indenter" in old and "indenter" not in new:
        return float("inf")
    return worst


def run(args: argparse.Namespace) -> int:
    from coathertz.fitalpha.build import build

    _grid(args.elastic_grid, 3, "--elastic-grid")  # before any solving
    _grid(args.rigid_grid, 2, "--rigid-grid")
    if args.sweep:
        table, prov = load_sweep(args.sweep)
        prov = {**prov, "sweep_file": args.sweep.name}
    else:
        table, prov = solve_sweep(args)
        if args.export_sweep:
            export_sweep(args.export_sweep, table, prov)
            print(f"sweep written to {args.export_sweep} ({len(table['H'])} points)")
    prov["command"] = "coathertz fit-alpha " + " ".join(sys.argv[2:]) if sys.argv[1:2] == [NAME] else NAME
    from coathertz.fitalpha.fit import FitSettings

    # a sweep may carry its own fit settings (the small test fixture does: fewer terms for fewer rows)
    settings = {k: FitSettings.from_dict(v) for k, v in prov.get("fit_settings", {}).items()}
    data = build(table, provenance=prov, settings=settings)
    if args.spot_check:
        from coathertz.fitalpha import sweep as S
        from coathertz.fitalpha.sweep import spot_check
        from coathertz.methods import get_method
        from coathertz.store import ResultStore

        m = get_method(args.spot_method, **json.loads(args.spot_settings))
        with ResultStore(args.store, version=S.method_code_version(m)) as store:
            data["spot_checks"] = spot_check(table, m, store, args.spot_check)
    print(summary(data))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(data, indent=1))
        print(f"data file written to {args.out}")
    if args.check:
        old = json.loads(args.check.read_text())
        diff = compare(data, old)
        ok = diff < 1e-6
        print(f"check against {args.check}: largest relative difference of alpha {diff:.2e} "
              f"({'matches' if ok else 'DIFFERS'})")
        return 0 if ok else 1
    return 0


def summary(data: dict) -> str:
    """Table of fit and validation errors next to the paper's rule."""
    from coathertz.cli._common import format_table

    rows = []
    for cfg, qs in data["validation_error"].items():
        for q, v in qs.items():
            p = data["paper_error"].get(cfg, {}).get(q, {})
            f = data["fit_error"][cfg][q]
            rows.append([cfg, q, str(v["n"]), f"{f['max']:.3f}", f"{v['max']:.3f}", f"{v['p99']:.3f}",
                         *(f"{p[k]:.2f}" if k in p else "" for k in ("max", "p99"))])
    for cfg, v in data.get("corrected", {}).items():
        for q, e in v.get("validation_error", {}).items():
            f = v["fit_error"][q]
            rows.append([f"{cfg} (corrected)", q, str(e["n"]), f"{f['max']:.3f}", f"{e['max']:.3f}",
                         f"{e['p99']:.3f}", "", ""])
    head = ["config", "quantity", "n valid", "train max %", "valid max %", "valid p99 %",
            "paper max %", "paper p99 %"]
    text = format_table(head, rows)
    best = data.get("best_form", {})
    if best:
        text += "\nform used by the predictor: " + ", ".join(f"{c} {f}" for c, f in best.items())
    floors = []
    for cfg, qs in data.get("single_alpha_floor", {}).items():
        for q, v in qs.items():
            if v["n_above_target"]:
                w = ", ".join(f"{k} = {x:.3g}" for k, x in v["worst"].items())
                floors.append(f"  {cfg} {q}: {v['n_above_target']} of {v['n']} points beyond "
                              f"{v['target_percent']} % for every alpha; worst {v['max_percent']:.2f} % "
                              f"at {w}")
    sc = data.get("spot_checks")
    if sc:
        text += f"\nspot checks against {sc['method']} ({sc['settings']}): max |difference| [%] of the bars"
        for k, v in sc["per_set"].items():
            d = ", ".join(f"{q} {x:.3g}" for q, x in v["max_abs_diff_percent"].items())
            text += f"\n  {k}: {v['n']} points ({v['failed']} failed): {d}"
    if floors:
        text += ("\nwhere no single alpha reaches the target (one-alpha structure, eqs 17-18):\n"
                 + "\n".join(floors))
    return text
