"""``coathertz fem CASE``: solve one case with the axisymmetric finite-element model."""

from __future__ import annotations

import argparse

from coathertz.cli._common import add_case_arguments

NAME = "fem"
HELP = "axisymmetric finite-element solution of one case (delta, a, p0, stresses, VTU output)"
#: What to lower when the command runs out of memory (named in the error).
MEMORY_HINT = "a coarser mesh (--mesh)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    from coathertz.fem.mesh import MESH_LEVELS
    from coathertz.fem.method import CONTACTS, SOLVERS

    add_case_arguments(parser)
    from coathertz.fem.plastic.method import PLASTIC_MESHES

    levels = " / ".join(str(s.n_a) for s in MESH_LEVELS.values())
    p_levels = " / ".join(str(s.n_a) for s in PLASTIC_MESHES.values())
    parser.add_argument("--mesh", default="default", choices=list(MESH_LEVELS),
                        help=f"mesh level: {levels} elements across the estimated contact radius "
                             "(the output counts them across the computed a, which differs a little); "
                             f"with --plastic {p_levels} across the largest contact radius estimated "
                             "for the path")
    parser.add_argument("--contact", default="active-set", choices=list(CONTACTS),
                        help="contact formulation (default: active-set, exact)")
    parser.add_argument("--solver", default="direct", choices=list(SOLVERS),
                        help="linear solver (default: direct)")
    parser.add_argument("--vtu", metavar="OUT.vtu", help="write mesh, displacement and stresses")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    g = parser.add_argument_group("elastic-plastic (J2) load path; yield data from the case's materials")
    g.add_argument("--plastic", action="store_true", help="incremental elastic-plastic solution")
    g.add_argument("--steps", type=int, default=10, help="load increments to W (default 10)")
    # the options below mean nothing without --plastic: given without it, they are an error (run)
    plastic_only: list[argparse.Action] = []

    def only(*flags: str, **kw) -> None:
        plastic_only.append(g.add_argument(*flags, **kw))

    only("--unload", action="store_true", help="unload to zero after loading (residual state)")
    only("--reload", action="store_true", help="reload to W after unloading")
    only("--approach", metavar="DELTA", help="approach control to DELTA (e.g. '20 um') instead of "
         "load control (deep indentation); the mesh is sized from DELTA")
    only("--follow-contact", action="store_true",
         help="remesh around the growing contact (the plastic history carried over), so that "
              "every loading increment has about as many elements across its contact")
    only("--vtu-dir", metavar="DIR", help="--plastic: one VTU per increment (displacement, "
         "stresses, plastic strain) and a .pvd time series")
    only("--out-json", metavar="OUT.json", help="--plastic: write the curves and profiles")
    only("--out-csv", metavar="OUT.csv", help="--plastic: write the curves (one row per increment)")
    only("--plot-dir", metavar="DIR", help="--plastic: load_approach.png and plastic_zone.png")
    parser.set_defaults(plastic_only=tuple((a.option_strings[0], a.dest) for a in plastic_only))


def _solve(method, case):
    """``method.solve_full(case)``, with a solver that does not converge reported as such."""
    from coathertz.errors import CoatHertzError, ConvergenceError
    from coathertz.validity import A_OVER_R_MAX

    try:
        return method.solve_full(case)
    except (CoatHertzError, ConvergenceError, MemoryError):
        raise
    except Exception as exc:  # scikit-fem's Newton loop raises a bare Exception
        if "converge" not in str(exc):
            raise
        ratio = case.hertz_s.a0 / case.R if case.E_star_s < float("inf") else case.hertz_c.a0 / case.R
        hint = (f"; the Hertz estimate gives a/R = {ratio:.3g} > {A_OVER_R_MAX:g}, far outside the "
                "model's small-strain range: lower the load W" if ratio > A_OVER_R_MAX else
                "; try --contact penalty or a finer --mesh")
        raise ConvergenceError(f"the FE contact solve did not converge ({exc}){hint}") from None


def run(args: argparse.Namespace) -> int:
    from coathertz.cli._common import (
        case_from_args,
        check_output_file,
        finish,
        format_table,
        list_examples,
        output_dir,
        print_json_or_header,
        writing,
    )
    from coathertz.errors import CoatHertzError
    from coathertz.fem.method import FEMMethod

    if args.list_examples:
        return list_examples()
    case = case_from_args(args)
    if args.vtu:
        check_output_file(args.vtu, "--vtu")
        if not str(args.vtu).lower().endswith(".vtu"):
            raise CoatHertzError(f"--vtu {args.vtu!r}: the file name must end in .vtu (VTK "
                                 "unstructured grid for ParaView), e.g. --vtu mesh.vtu")
    if not args.plastic:
        given = [flag for flag, dest in getattr(args, "plastic_only", ()) if getattr(args, dest, None)]
        if given:
            raise CoatHertzError(f"{', '.join(given)}: elastic-plastic options; add --plastic (and "
                                 "yield data in the case)")
    if args.plastic:
        if args.reload and not args.unload:
            raise CoatHertzError("--reload reloads after unloading: give --unload as well")
        if not 1 <= args.steps <= 10_000:
            raise CoatHertzError("--steps: load increments to W must be an integer in [1, 10000], "
                                 f"got {args.steps}")
        if args.out_json:
            check_output_file(args.out_json, "--out-json")
        if args.out_csv:
            check_output_file(args.out_csv, "--out-csv")
        if args.vtu_dir:
            output_dir(args.vtu_dir, "--vtu-dir")
        if args.plot_dir:
            output_dir(args.plot_dir, "--plot-dir")
        from coathertz.cli._plastic import run_plastic

        return run_plastic(case, args)
    method = FEMMethod(mesh=args.mesh, contact=args.contact, solver=args.solver, stresses=True)
    res, model, path = _solve(method, case)
    res = finish(case, res)
    if args.vtu:
        from coathertz.fem.io import write_vtu

        with writing(args.vtu, "--vtu"):
            write_vtu(args.vtu, model, path.x)
    if print_json_or_header(case, res, args.json):
        return 0
    norm = case.normalisers
    m = res.meta
    print(f"  mesh {args.mesh}: {m['elements']} Q2 elements, {m['dofs']} dofs, "
          f"{m['elements_across_a']:.0f} elements across the computed a; solver {m['solver']}, "
          f"{m['contact']} {m['contact_iterations']} iterations, {m['wall_time']:.2f} s")
    rows = [
        ["delta [um]", f"{res.delta * 1e6:.5g}", f"{res.delta / norm.delta0:.5f}"],
        ["a [um] (gap fit)", f"{res.a * 1e6:.5g}", f"{res.a / norm.a0:.5f}"],
        ["p0 [MPa]", f"{res.p0 / 1e6:.5g}", f"{res.p0 / norm.p0:.5f}"],
    ]
    ax = m["axis_max_von_mises"]
    rows.append(["max von Mises on axis [MPa]", f"{ax['value'] / 1e6:.5g}", f"z = {ax['z'] * 1e6:.2f} um"])
    sides = [(f"interface_{s}", f"interface ({s} side)") for s in ("coating", "substrate")]
    for i in range(1, len(case.body1.layers) + len(case.body2.layers) + 1):  # a stack's interfaces
        sides += [(f"interface{i}_{s}", f"interface {i} ({s})") for s in ("above", "below")]
    for key, label in sides:
        if key in m:
            d = m[key]
            rows.append([f"{label} max von Mises [MPa]", f"{d['max_von_mises'] / 1e6:.5g}",
                         f"r = {d['r_max_von_mises'] * 1e6:.2f} um"])
            rows.append([f"{label} max sigma_1 [MPa]", f"{d['max_sigma_1'] / 1e6:.5g}",
                         f"r = {d['r_max_sigma_1'] * 1e6:.2f} um"])
    print(format_table(["", "value", f"/ Hertz ({norm.kind})"], rows))
    if args.vtu:
        print(f"VTU written to {args.vtu}")
    return 0
