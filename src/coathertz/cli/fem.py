"""``coathertz fem CASE``: solve one case with the axisymmetric finite-element model."""

from __future__ import annotations

import argparse

NAME = "fem"
HELP = "axisymmetric finite-element solution of one case (delta, a, p0, stresses, VTU output)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", help="TOML case file, or example:NAME")
    parser.add_argument("--mesh", default="default", choices=["coarse", "default", "fine"],
                        help="mesh level: 20 / 40 / 100 elements across the contact radius")
    parser.add_argument("--contact", default="active-set", choices=["active-set", "penalty"],
                        help="contact formulation (default: active-set, exact)")
    parser.add_argument("--solver", default="direct", choices=["direct", "amg"],
                        help="linear solver (default: direct)")
    parser.add_argument("--vtu", metavar="OUT.vtu", help="write mesh, displacement and stresses")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    g = parser.add_argument_group("elastic-plastic (J2) load path; yield data from the case's materials")
    g.add_argument("--plastic", action="store_true", help="incremental elastic-plastic solution")
    g.add_argument("--unload", action="store_true", help="unload to zero after loading (residual state)")
    g.add_argument("--reload", action="store_true", help="reload to W after unloading")
    g.add_argument("--steps", type=int, default=10, help="load increments to W (default 10)")
    g.add_argument("--approach", metavar="DELTA", help="approach control to DELTA (e.g. '20 um') instead of "
                   "load control (deep indentation); W only sizes the mesh")
    g.add_argument("--vtu-dir", metavar="DIR", help="--plastic: one VTU per increment (plastic strain)")
    g.add_argument("--out-json", metavar="OUT.json", help="--plastic: write the curves and profiles")


def run(args: argparse.Namespace) -> int:
    from coathertz.casefile import load_case
    from coathertz.cli._common import format_table, print_json_or_header
    from coathertz.fem.method import FEMMethod

    case = load_case(args.case)
    if args.plastic:
        from coathertz.fem.plastic_cli import run_plastic

        return run_plastic(case, args)
    method = FEMMethod(mesh=args.mesh, contact=args.contact, solver=args.solver, stresses=True)
    res, model, path = method.solve_full(case)
    if args.vtu:
        from coathertz.fem.io import write_vtu

        write_vtu(args.vtu, model, path.x)
    if print_json_or_header(case, res, args.json):
        return 0
    norm = case.normalisers
    m = res.meta
    print(f"  mesh {args.mesh}: {m['elements']} Q2 elements, {m['dofs']} dofs, "
          f"{m['elements_across_a']:.0f} elements across a; solver {m['solver']}, "
          f"{m['contact']} {m['contact_iterations']} iterations, {m['wall_time']:.2f} s")
    rows = [
        ["delta [um]", f"{res.delta * 1e6:.5g}", f"{res.delta / norm.delta0:.5f}"],
        ["a [um] (gap fit)", f"{res.a * 1e6:.5g}", f"{res.a / norm.a0:.5f}"],
        ["p0 [MPa]", f"{res.p0 / 1e6:.5g}", f"{res.p0 / norm.p0:.5f}"],
    ]
    ax = m["axis_max_von_mises"]
    rows.append(["max von Mises on axis [MPa]", f"{ax['value'] / 1e6:.5g}", f"z = {ax['z'] * 1e6:.2f} um"])
    for side in ("coating", "substrate"):
        if f"interface_{side}" in m:
            d = m[f"interface_{side}"]
            rows.append([f"interface ({side} side) max von Mises [MPa]", f"{d['max_von_mises'] / 1e6:.5g}",
                         f"r = {d['r_max_von_mises'] * 1e6:.2f} um"])
            rows.append([f"interface ({side} side) max sigma_1 [MPa]", f"{d['max_sigma_1'] / 1e6:.5g}",
                         f"r = {d['r_max_sigma_1'] * 1e6:.2f} um"])
    print(format_table(["", "value", f"/ Hertz ({norm.kind})"], rows))
    if args.vtu:
        print(f"VTU written to {args.vtu}")
    return 0
