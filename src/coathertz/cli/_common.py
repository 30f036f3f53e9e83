"""Helpers shared by the subcommands: reading a case from a file or flags, printing tables."""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import RIGID, Body, Coating, Material
from coathertz.units import parse_quantity


def add_case_arguments(parser: argparse.ArgumentParser) -> None:
    """CASE (TOML file or example:NAME) or a case given by flags."""
    parser.add_argument("case", nargs="?", help="TOML case file, or example:NAME (see --list-examples)")
    parser.add_argument("--list-examples", action="store_true", help="list the built-in example cases")
    g = parser.add_argument_group("case by flags (rigid sphere on a coated half-space)")
    g.add_argument("--W", help="load, e.g. '1 N'")
    g.add_argument("--R", help="sphere radius, e.g. '10 mm'")
    g.add_argument("--indenter", default="rigid", help="'rigid' or 'E,nu', e.g. '200 GPa,0.3'")
    g.add_argument("--substrate", help="'rigid' or 'E,nu', e.g. '200 GPa,0.3'")
    g.add_argument("--coating", help="'E,nu,h', e.g. '380 GPa,0.17,40 um'")


def _material_flag(text: str, flag: str) -> Material:
    if text.strip() == "rigid":
        return RIGID
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2:
        raise CoatHertzError(f"{flag} expects 'rigid' or 'E,nu' (e.g. '200 GPa,0.3'), got {text!r}")
    try:
        nu = float(parts[1])
    except ValueError as exc:
        raise CoatHertzError(f"{flag}: Poisson's ratio {parts[1]!r} is not a number") from exc
    return Material(parse_quantity(parts[0], "pressure", name=f"{flag} E"), nu)


def case_from_args(args: argparse.Namespace) -> ContactCase:
    """The case named by ``args.case`` or assembled from the flags."""
    from coathertz.casefile import load_case

    if args.case:
        return load_case(args.case)
    missing = [f"--{k}" for k in ("W", "R", "substrate") if getattr(args, k) is None]
    if missing:
        raise CoatHertzError(f"give a case file or the flags {', '.join(missing)}")
    W = parse_quantity(args.W, "force", name="--W")
    R = parse_quantity(args.R, "length", name="--R")
    indenter = _material_flag(args.indenter, "--indenter")
    substrate = _material_flag(args.substrate, "--substrate")
    coating = None
    if args.coating:
        parts = [p.strip() for p in args.coating.split(",")]
        if len(parts) != 3:
            raise CoatHertzError(
                f"--coating expects 'E,nu,h' (e.g. '380 GPa,0.17,40 um'), got {args.coating!r}"
            )
        cmat = _material_flag(",".join(parts[:2]), "--coating")
        coating = Coating(cmat, parse_quantity(parts[2], "length", name="--coating h"))
    return ContactCase(Body(indenter, None, R, R), Body(substrate, coating), W)


def list_examples() -> int:
    from coathertz.casefile import examples, load_example

    for name in examples():
        print(f"example:{name:22s} {load_example(name).label}")
    return 0


def to_json(obj: Any) -> str:
    """JSON with inf/nan written as strings (strict JSON)."""

    def fix(v: Any) -> Any:
        if isinstance(v, float) and not math.isfinite(v):
            return str(v)
        if isinstance(v, dict):
            return {k: fix(x) for k, x in v.items()}
        if isinstance(v, list | tuple):
            return [fix(x) for x in v]
        return v

    return json.dumps(fix(obj), indent=2)


def format_table(header: list[str], rows: list[list[str]]) -> str:
    """A plain-text table with aligned columns."""
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    line = "  ".join(h.ljust(w) for h, w in zip(header, widths, strict=True))
    out = [line, "  ".join("-" * w for w in widths)]
    for r in rows:
        out.append("  ".join(str(c).rjust(w) if j else str(c).ljust(w)
                             for j, (c, w) in enumerate(zip(r, widths, strict=True))))
    return "\n".join(out)


def result_summary(case, res) -> dict[str, Any]:
    """JSON-ready summary of a method's :class:`~coathertz.results.ContactResult` for ``case``,
    with the paper's bars (eq 7 normalisation)."""
    norm = case.normalisers
    return {
        "case": case.describe(),
        "label": case.label,
        "units": "SI (m, Pa, N)",
        "delta": res.delta,
        "a": res.a,
        "p0": res.p0,
        "r_a": res.r_a,
        "r_b": res.r_b,
        "normalisation": norm.kind,
        "delta_bar": res.delta / norm.delta0,
        "a_bar": res.a / norm.a0,
        "p_bar": res.p0 / norm.p0,
        "meta": dict(res.meta),
    }


def print_json_or_header(case, res, as_json: bool) -> bool:
    """Print the JSON summary (and return True) or the human-readable case header (False)."""
    if as_json:
        print(to_json(result_summary(case, res)))
        return True
    print(f"case: {case.label or '(unnamed)'}\n  {case.describe()}")
    return False
