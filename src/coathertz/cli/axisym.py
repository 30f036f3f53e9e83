"""``coathertz axisym CASE``: exact axisymmetric solution of one (circular) case."""

from __future__ import annotations

import argparse

from coathertz.cli._common import add_case_arguments, add_fields_argument

NAME = "axisym"
HELP = "exact axisymmetric solution of one circular case (delta, a, p0 and its radius, profiles)"
#: What to lower when the command runs out of memory (named in the error).
MEMORY_HINT = "fewer Legendre modes (--modes)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_case_arguments(parser)  # with --interface (the case's coatings)
    parser.add_argument("--modes", type=int, default=None, metavar="N",
                        help="Legendre modes of the Galerkin basis (default: automatic from h/a)")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    add_fields_argument(parser, "r, pressure and u_z (combined surface displacement) profiles")


def run(args: argparse.Namespace) -> int:
    from coathertz.axisym import AxisymMethod
    from coathertz.cli._common import (
        case_from_args,
        check_output_file,
        finish,
        format_table,
        list_examples,
        print_json_or_header,
        save_fields,
    )
    from coathertz.errors import CoatHertzError

    if args.list_examples:
        return list_examples()
    case = case_from_args(args)
    if args.save_fields:
        check_output_file(args.save_fields, "--save-fields")
    if args.modes is not None and not 2 <= args.modes <= 400:
        raise CoatHertzError(f"--modes: Legendre modes must be an integer in [2, 400], got {args.modes}")
    method = AxisymMethod(n_modes=args.modes)
    res = finish(case, method.solve(case))
    save_fields(args.save_fields, res)
    if print_json_or_header(case, res, args.json):
        return 0
    norm = case.normalisers
    m = res.meta
    itf = "interfaces of the layer stack" if case.is_stacked else f"{m['interface']} interface"
    print(f"  {itf}; {m['n_modes']} Legendre modes, {m['n_xi']} xi nodes, "
          f"{m['iterations']} load iterations, {m['wall_time'] * 1e3:.1f} ms")
    r_p0 = m["r_p0"]
    where = "on the axis" if r_p0 == 0.0 else f"at r = {r_p0 * 1e6:.4g} um ({r_p0 / res.a:.3f} a)"
    rows = [
        ["delta [um]", f"{res.delta * 1e6:.7g}", f"{res.delta / norm.delta0:.7f}"],
        ["a [um]", f"{res.a * 1e6:.7g}", f"{res.a / norm.a0:.7f}"],
        ["p0 [MPa] (maximum)", f"{res.p0 / 1e6:.7g}", f"{res.p0 / norm.p0:.7f}"],
    ]
    print(format_table(["", "value", f"/ Hertz ({norm.kind})"], rows))
    print(f"maximum pressure {where}")
    if args.save_fields:
        print(f"fields written to {args.save_fields} (NumPy .npz archive)")
    return 0
