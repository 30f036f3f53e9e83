"""``coathertz stresses CASE``: stresses inside the bodies and what designers read from them."""

from __future__ import annotations

import argparse

from coathertz.cli._common import add_case_arguments

NAME = "stresses"
HELP = "stress field inside the coated body (FFT, exact or FE) and its maxima (von Mises, tension, interface)"


def _depths(text: str) -> list[float]:
    try:
        return [float(v) * 1e-6 for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected comma-separated depths in um, got {text!r}") from None


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_case_arguments(parser)  # with --interface (the case's coating)
    from coathertz.stress_methods import STRESS_METHODS

    parser.add_argument("--method", default="fft", choices=tuple(STRESS_METHODS),
                        help="fft (DC-FFT, friction allowed, any layer stack), axisym (exact, "
                             "frictionless, circular; any layer stack) or fem (axisymmetric FE, "
                             "frictionless) (default: fft)")
    parser.add_argument("--grid", type=int, default=128, metavar="N",
                        help="FFT cells per side (axisym: the lattice of --png/--vtu)")
    parser.add_argument("--mu", type=float, default=0.0, metavar="M",
                        help="full sliding friction q = mu p along x on body2 (0 <= mu <= 1)")
    parser.add_argument("--Q", default=None, metavar="F",
                        help="tangential load along x with partial slip, 0 <= Q < mu W "
                             "(force with units, e.g. '2 N'; needs --mu > 0; homogeneous bodies)")
    parser.add_argument("--depths", type=_depths, default=None, metavar="Z1,Z2,...",
                        help="depths below body2's surface [um] (default: through the coating, "
                             "both sides of its interface, down to 3a)")
    parser.add_argument("--png", metavar="OUT.png",
                        help="von Mises stress on the x-z and y-z slices through its maximum")
    parser.add_argument("--vtu", metavar="OUT.vtu",
                        help="the whole field (six components, von Mises, first principal) for ParaView")
    parser.add_argument("--json", action="store_true", help="machine-readable output")


def run(args: argparse.Namespace) -> int:
    import math

    from coathertz.cli._common import (
        case_from_args,
        check_output_file,
        format_table,
        list_examples,
        to_json,
    )
    from coathertz.errors import CoatHertzError
    from coathertz.stress_methods import StressOptions, check_depths, stress_method
    from coathertz.stress_summary import summarise

    if args.list_examples:
        return list_examples()
    if not (math.isfinite(args.mu) and 0 <= args.mu <= 1):
        raise CoatHertzError(f"--mu: friction coefficient must be in [0, 1], got {args.mu!r}")
    for flag, path, suffix in (("--png", args.png, ".png"), ("--vtu", args.vtu, ".vtu")):
        if path:  # before any computing
            if not str(path).lower().endswith(suffix):
                raise CoatHertzError(f"{flag} {path!r}: the file name must end in {suffix}")
            check_output_file(path, flag)
    Q = None
    if args.Q is not None:
        from coathertz.casefile import quantity

        Q = quantity(args.Q, "force", "--Q: tangential load Q", minimum=">=0")
        if not args.mu > 0:
            raise CoatHertzError("--Q: partial slip needs a friction coefficient --mu > 0")
    case = case_from_args(args)
    body = case.body2
    if args.depths is not None:
        check_depths(case, args.depths)
    opt = StressOptions(grid=args.grid, mu=args.mu, Q=Q,
                        depths=None if args.depths is None else tuple(args.depths),
                        lattice=bool(args.png or args.vtu))
    res = stress_method(args.method)(case, opt)
    summary = summarise(body, res.x, res.y, res.z, res.sigma, res.p0, interfaces=res.interfaces)
    _write_files(args, case, res)
    if args.json:
        print(to_json({"method": args.method, "mu": args.mu, "Q": Q, "a": res.a, "p0": res.p0,
                       "depths": res.z.tolist(), **summary}))
        return 0
    grid = f"FFT {args.grid}^2" if args.method == "fft" else f"{res.label}, {res.x.size} radii"
    print(f"coathertz stresses: {case.label or 'case'}, {grid}, {res.z.size} depths,"
          f" mu = {args.mu:g}, a = {res.a * 1e6:.4g} um, p0 = {res.p0 / 1e6:.5g} MPa")
    rows = []
    for key, e in summary.items():
        if e is None:
            rows.append([key, "-", "-", "-"])
            continue
        at = ", ".join(f"{v * 1e6:.3g}" for v in e["at"])
        rows.append([key, f"{e['value'] / 1e6:.5g}", f"{e['over_p0']:.4f}", at])
    print(format_table(["", "value [MPa]", "/ p0", "at x, y, z [um]"], rows))
    return 0


def _write_files(args: argparse.Namespace, case, res) -> None:
    from coathertz.cli._common import writing
    from coathertz.stress_output import slice_figure, write_png, write_vtu

    if res.lattice is None:
        return
    x, y, z, sigma = res.lattice
    if args.png:
        H = sum(L.h for L in case.body2.stack)
        on = "" if args.method == "fft" else f" on {args.grid}^2"
        title = (f"{case.label or 'case'}: von Mises stress in body2, {res.label}{on}, "
                 f"mu = {args.mu:g}, p0 = {res.p0 / 1e6:.4g} MPa")
        fig = slice_figure(x, y, z, sigma, a_x=res.r_a, a_y=res.r_b, h=H if H > 0 else None,
                           title=title)
        with writing(args.png, "--png"):
            write_png(args.png, fig)
    if args.vtu:
        with writing(args.vtu, "--vtu"):
            write_vtu(args.vtu, x, y, z, sigma)
