"""``coathertz fft CASE``: solve one case with the DC-FFT contact solver."""

from __future__ import annotations

import argparse
import math

from coathertz.cli._common import add_case_arguments, add_fields_argument

NAME = "fft"
HELP = "DC-FFT contact solution of one case (delta, a, p0, iterations, residual)"
#: What to lower when the command runs out of memory (named in the error).
MEMORY_HINT = "a coarser grid (--grid)"


def _layer_cells(text: str) -> float | None:
    if text.strip().lower() == "off":
        return None
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of cells or 'off', got {text!r}") from None


def add_arguments(parser: argparse.ArgumentParser) -> None:
    from coathertz.fft.grid import DEFAULT_N
    from coathertz.fft.method import LAYER_CELLS_MIN

    add_case_arguments(parser)
    parser.add_argument("--grid", type=int, default=None, metavar="N",
                        help=f"cells along each side of the domain (default {DEFAULT_N}, >= 16)")
    parser.add_argument("--spacing-ratio", type=float, default=None,
                        help="dy/dx (default: r_b/r_a; the paper's ellipses use 1/3)")
    parser.add_argument("--layer-cells", type=_layer_cells, default=LAYER_CELLS_MIN, metavar="C|off",
                        help="cells the thinnest coating must span for the sub-cell radius "
                             "(1.5 times that for a coating over 4 times stiffer than its "
                             "substrate); a thinner one is solved again on a finer grid (default "
                             f"{LAYER_CELLS_MIN:g}; off: the grid N as given, flagged)")
    parser.add_argument("--max-memory", type=_gib, default=None, metavar="GB",
                        help="memory one solve may take, in GiB (default: a quarter of the machine's, "
                             "at most 4); a larger grid is refused before it is allocated, and the "
                             "thin-coating refinement stays within it")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    add_fields_argument(parser, "x, y, pressure and displacement arrays")


def _gib(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not 0 < v < math.inf:
        raise argparse.ArgumentTypeError(f"expected a number of GiB > 0, got {text!r}")
    return v


def run(args: argparse.Namespace) -> int:
    from coathertz.cli._common import (
        case_from_args,
        check_output_file,
        finish,
        format_table,
        list_examples,
        print_json_or_header,
        save_fields,
    )
    from coathertz.fft.grid import DEFAULT_N
    from coathertz.fft.method import FFTMethod

    if args.list_examples:
        return list_examples()
    case = case_from_args(args)
    if args.save_fields:
        check_output_file(args.save_fields, "--save-fields")
    method = FFTMethod(
        n=DEFAULT_N if args.grid is None else args.grid,
        spacing_ratio=args.spacing_ratio,
        layer_cells=args.layer_cells,
        max_memory_gb=args.max_memory,
    )
    res = finish(case, method.solve(case))
    save_fields(args.save_fields, res)
    if print_json_or_header(case, res, args.json):
        return 0
    norm = case.normalisers
    m = res.meta
    g = m["grid"]
    print(f"  grid {g['nx']} x {g['ny']}, dx = {g['dx'] * 1e6:.4g} um, dy = {g['dy'] * 1e6:.4g} um;"
          f" {m['iterations']} CG iterations, residual {m['residual']:.1e},"
          f" {m['wall_time'] * 1e3:.0f} ms")
    if "layer_refinement" in m:
        lr = m["layer_refinement"]
        print(f"  grid refined from {lr['n_requested']} to {lr['n']}: the coating spanned "
              f"{lr['layer_cells_before']:.2g} cells (a there: {lr['a_before'] * 1e6:.5g} um)")
    rows = [
        ["delta [um]", f"{res.delta * 1e6:.5g}", f"{res.delta / norm.delta0:.5f}"],
        [f"a [um] ({m['radius_estimator']})", f"{res.a * 1e6:.5g}", f"{res.a / norm.a0:.5f}"],
        ["a_num = sqrt(S/pi) [um]", f"{m['a_num'] * 1e6:.5g}", f"{m['a_num'] / norm.a0:.5f}"],
        ["p0 [MPa]", f"{res.p0 / 1e6:.5g}", f"{res.p0 / norm.p0:.5f}"],
    ]
    if not case.is_circular or not math.isclose(res.r_a, res.r_b):
        rows += [["r_a [um]", f"{res.r_a * 1e6:.5g}", f"{res.r_a / norm.r_a0:.5f}"],
                 ["r_b [um]", f"{res.r_b * 1e6:.5g}", f"{res.r_b / norm.r_b0:.5f}"]]
    print(format_table(["", "value", f"/ Hertz ({norm.kind})"], rows))
    if args.save_fields:
        print(f"fields written to {args.save_fields} (NumPy .npz archive)")
    return 0
