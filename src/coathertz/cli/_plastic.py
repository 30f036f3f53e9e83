"""``coathertz fem CASE --plastic [--unload] [--reload] [--steps N]``: the elastic-plastic load path.

Kept out of :mod:`coathertz.cli.fem` (which only dispatches here) so the CLI module stays small;
the numerics (:mod:`coathertz.fem.plastic.method`) neither print nor write files.
"""

from __future__ import annotations

import argparse
import json
import sys

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError


def run_plastic(case: ContactCase, args: argparse.Namespace) -> int:
    from coathertz.fem.method import axisymmetric_equivalent, refuse_plastic_stack
    from coathertz.fem.plastic.method import PLASTIC_MESHES, solve_plastic, write_vtu_series

    refuse_plastic_stack(case, "--plastic")
    eq = axisymmetric_equivalent(case)
    mats = eq.body.deformable_materials if eq is not None else ()
    if not any(m.plasticity is not None for m in mats):
        raise CoatHertzError("--plastic needs yield data in the case: add Y = \"1 GPa\" (and optionally "
                             "hardening) to the body's material or coating table")
    if args.mesh not in PLASTIC_MESHES:
        raise CoatHertzError(f"--mesh with --plastic must be one of {', '.join(PLASTIC_MESHES)}, "
                             f"got {args.mesh!r}")
    mesh = args.mesh
    total = args.steps * (1 + bool(args.unload or args.reload) + bool(args.reload))
    count = [0]

    def progress(inc, phase) -> None:
        count[0] += 1
        print(f"\r  {phase:9s} W = {inc.W:10.4g} N  delta = {inc.delta:10.4g} m  "
              f"Newton {inc.newton_iterations:2d}  cutbacks {inc.cutbacks}  "
              f"[{count[0]} increments, {total} targets]", end="", file=sys.stderr, flush=True)

    delta_max = None
    if getattr(args, "approach", None):
        from coathertz.units import parse_quantity

        delta_max = parse_quantity(args.approach, "length", name="--approach")
    res = solve_plastic(case, mesh=mesh, n_steps=args.steps, unload=args.unload, reload=args.reload,
                        keep_snapshots=bool(args.vtu_dir), progress=progress, delta_max=delta_max,
                        follow_contact=bool(getattr(args, "follow_contact", False)))
    print(file=sys.stderr)
    if args.vtu_dir:
        paths = write_vtu_series(res, args.vtu_dir)
        print(f"{len(paths)} VTU files written to {args.vtu_dir}", file=sys.stderr)
    if args.out_json:
        from coathertz.cli._common import writing

        with writing(args.out_json, "--out-json"):
            res.write_json(args.out_json)
    if getattr(args, "out_csv", None):
        res.write_csv(args.out_csv)
    if getattr(args, "plot_dir", None):
        from pathlib import Path

        from coathertz.fem.plastic.plot import plot_load_approach, plot_plastic_zone

        d = Path(args.plot_dir)
        d.mkdir(parents=True, exist_ok=True)
        label = case.describe() if hasattr(case, "describe") else ""
        plot_load_approach(res, d / "load_approach.png", f"load-approach, elastic-plastic FE ({mesh} mesh)")
        plot_plastic_zone(res, d / "plastic_zone.png", f"plastic zone, elastic-plastic FE ({mesh} mesh)")
        print(f"figures written to {d} ({label})" if label else f"figures written to {d}", file=sys.stderr)
    if args.json:
        print(json.dumps(res.to_json()["curves"] | {"meta": res.to_json()["meta"]}, indent=1))
        return 0
    c, m = res.curves, res.meta
    print(f"elastic-plastic FE ({mesh} mesh: {m['elements']} Q2 elements, {m['dofs']} dofs, B-bar), "
          f"{m['increments']} increments, {m['newton_iterations_total']} Newton iterations, "
          f"{m['wall_time']:.1f} s")
    print(f"{'phase':10s} {'W [N]':>10s} {'delta [um]':>11s} {'a [um]':>9s} {'p_max [MPa]':>12s} "
          f"{'p_mean [MPa]':>13s} {'ep_max':>9s} {'Newton':>6s} {'elem/a':>6s}")
    for k in range(len(c["W"])):
        print(f"{c['phase'][k]:10s} {c['W'][k]:10.4g} {c['delta'][k] * 1e6:11.5g} {c['a'][k] * 1e6:9.4g} "
              f"{c['p_max'][k] / 1e6:12.5g} {c['p_mean'][k] / 1e6:13.5g} {c['ep_max'][k]:9.3g} "
              f"{c['newton_iterations'][k]:6d} {c['elements_across_a'][k]:6.1f}")
    z = res.final["plastic_zone"]
    if z["plastic_points"]:
        print(f"plastic zone: max ep = {z['ep_max']:.3g}, r <= {z['zone_r'] * 1e6:.4g} um, "
              f"depth {z['zone_top'] * 1e6:.4g}-{z['zone_depth'] * 1e6:.4g} um")
    else:
        print("plastic zone: none (no quadrature point yielded along the path)")
    if res.final.get("residual_depth") is not None:
        print(f"residual depth {res.final['residual_depth'] * 1e6:.5g} um")
        ex = res.final["residual"]["stress_extrema"]
        for side in ("coating", "substrate"):
            if f"interface_{side}" in ex:
                d = ex[f"interface_{side}"]
                print(f"residual interface stress ({side} side): max sigma_1 "
                      f"{d['max_sigma_1'] / 1e6:.5g} MPa at r = {d['r_max_sigma_1'] * 1e6:.4g} um, "
                      f"max |sigma_rz| {d['max_abs_sigma_rz'] / 1e6:.5g} MPa")
    if m.get("remeshes"):
        ch = max(abs(r_["change"]) for r_ in m["remeshes"])
        what = "load" if m["control"] == "approach" else "approach"
        print(f"contact-following meshes: {len(m['remeshes'])} remeshes (a_ref "
              f"{m['remeshes'][0]['a_ref_old'] * 1e6:.4g} -> {m['a_ref'] * 1e6:.4g} um); "
              f"the {what} moved by at most "
              f"{100 * ch:.2g} % in a remesh's rebalance (the history transfer's error)")
    if m.get("zone_growths"):
        print(f"coathertz fem: note: the contact reached its candidate zone's edge "
              f"(r <= {', '.join(f'{r * 1e6:.4g}' for r in m['zone_growths'])} um); the path was solved "
              f"again on a grown mesh (a_ref = {m['a_ref'] * 1e6:.4g} um)", file=sys.stderr)
    if "validity" in m:
        print(f"coathertz fem: warning: {m['validity']}", file=sys.stderr)
    return 0
