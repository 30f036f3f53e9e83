"""Helpers shared by the subcommands: the case from a file and/or flags, output paths checked
before computing, the validity check of every printed result, JSON and tables."""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from coathertz.case import ContactCase
from coathertz.casefile import quantity
from coathertz.errors import CoatHertzError
from coathertz.jsonsafe import dumps
from coathertz.materials import INTERFACES, RIGID, Body, Coating, Layer, Material
from coathertz.results import ContactResult


def add_case_arguments(parser: argparse.ArgumentParser) -> None:
    """CASE (TOML file or example:NAME) or a case given by flags; flags given with a CASE
    override its values (:func:`case_from_args`)."""
    parser.add_argument("case", nargs="?", help="TOML case file, or example:NAME (see --list-examples)")
    parser.add_argument("--list-examples", action="store_true", help="list the built-in example cases")
    g = parser.add_argument_group(
        "case by flags (rigid sphere on a coated half-space); with a CASE they replace its values")
    g.add_argument("--W", help="load, e.g. '1 N'")
    g.add_argument("--R", help="indenter (body1) sphere radius, e.g. '10 mm'")
    g.add_argument("--indenter", help="indenter (body1) material: 'rigid' (default) or 'E,nu', "
                                      "e.g. '200 GPa,0.3'")
    g.add_argument("--substrate", help="substrate (body2) material: 'rigid' or 'E,nu', e.g. '200 GPa,0.3'")
    g.add_argument("--coating", action="append",
                   help="coating of body2: 'E,nu,h', e.g. '380 GPa,0.17,40 um'; repeat it for a layer "
                        "stack, top first (then 'E,nu,h[,frictionless]': the layer's lower interface)")
    g.add_argument("--interface", choices=INTERFACES,
                   help="coating/substrate interface of a single coating: bonded (the paper's model; the "
                        "default unless the case file says otherwise) or frictionless")


_CASE_FLAGS = ("W", "R", "indenter", "substrate", "coating")


def _material_flag(text: str, flag: str, what: str) -> Material:
    if text.strip() == "rigid":
        return RIGID
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2:
        raise CoatHertzError(f"{flag} expects 'rigid' or 'E,nu' (e.g. '200 GPa,0.3'), got {text!r}")
    try:
        nu = float(parts[1])
    except ValueError as exc:
        raise CoatHertzError(f"{flag}: {what} Poisson's ratio nu {parts[1]!r} is not a number") from exc
    E = quantity(parts[0], "pressure", f"{flag}: {what} E", allow_inf=True)
    try:
        return Material(E, nu)
    except CoatHertzError as exc:
        raise CoatHertzError(f"{flag}: {what} {exc}") from None


def _coating_flag(text: str) -> Coating:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 3:
        raise CoatHertzError(f"--coating expects 'E,nu,h' (e.g. '380 GPa,0.17,40 um'), got {text!r}")
    cmat = _material_flag(",".join(parts[:2]), "--coating", "coating")
    if cmat.is_rigid:
        raise CoatHertzError(f"--coating: the coating must be elastic ('E,nu,h'), got {text!r}")
    return Coating(cmat, quantity(parts[2], "length", "--coating: coating thickness h", minimum=">=0"))


def _coatings_flag(texts: list[str]) -> tuple[Coating | None, tuple[Layer, ...]]:
    """One ``--coating``: a coating; several: a layer stack, top first."""
    if len(texts) == 1:
        return _coating_flag(texts[0]), ()
    layers = []
    for i, text in enumerate(texts, 1):
        parts = [p.strip() for p in text.split(",")]
        if len(parts) not in (3, 4):
            raise CoatHertzError(f"--coating (layer {i}) expects 'E,nu,h[,frictionless]', got {text!r}")
        mat = _material_flag(",".join(parts[:2]), "--coating", f"layer {i}")
        h = quantity(parts[2], "length", f"--coating: layer {i} thickness h")
        layer = Layer(mat, h, parts[3] if len(parts) == 4 else "bonded")
        layer.check(f"--coating: layer {i}")
        layers.append(layer)
    return None, tuple(layers)


def _radius_flag(text: str) -> float:
    return quantity(text, "length", "--R: indenter sphere radius R", allow_inf=True)


def case_from_args(args: argparse.Namespace) -> ContactCase:
    """:func:`_case_from_flags`, with ``--interface`` (when given) set on every coating."""
    case = _case_from_flags(args)
    interface = getattr(args, "interface", None)
    if interface is not None:
        for name in ("body1", "body2"):
            if getattr(case, name).is_stacked:
                raise CoatHertzError(
                    f"--interface: {name} has a layer stack, whose interfaces are set per layer "
                    f"(interface = ... in its [[{name}.layers]] tables, or --coating "
                    "'E,nu,h,frictionless'); drop --interface")
    if interface is None or not case.is_coated:
        return case

    def body(b: Body) -> Body:
        return b if b.coating is None else dataclasses.replace(
            b, coating=dataclasses.replace(b.coating, interface=interface))

    return case.replace(body1=body(case.body1), body2=body(case.body2))


def _case_from_flags(args: argparse.Namespace) -> ContactCase:
    """The case named by ``args.case`` (with the case flags given applied to it), or the case
    assembled from the flags alone.

    With a case file, ``--W`` sets the load, ``--R`` and ``--indenter`` the radius and material
    of body1 (the indenter), ``--substrate`` and ``--coating`` the substrate material and the
    coating of body2; the label then says what was replaced.
    """
    from coathertz.casefile import load_case

    given = {k: getattr(args, k, None) for k in _CASE_FLAGS}
    given = {k: v for k, v in given.items() if v is not None}
    if args.case:
        case = load_case(args.case)
        if not given:
            return case
        b1, b2 = case.body1, case.body2
        changes: dict[str, Any] = {}
        if "W" in given:
            changes["W"] = quantity(given["W"], "force", "--W: load W")
        if "R" in given or "indenter" in given:
            R = _radius_flag(given["R"]) if "R" in given else None
            mat = _material_flag(given["indenter"], "--indenter", "indenter") if "indenter" in given \
                else b1.material
            changes["body1"] = Body(mat, b1.coating, b1.Rx if R is None else R, b1.Ry if R is None else R,
                                    b1.name, layers=b1.layers)
        if "substrate" in given or "coating" in given:
            mat = _material_flag(given["substrate"], "--substrate", "substrate") if "substrate" in given \
                else b2.material
            coat, layers = _coatings_flag(given["coating"]) if "coating" in given else (b2.coating, b2.layers)
            if coat is not None and b2.coating is not None:  # the file's interface stays
                coat = dataclasses.replace(coat, interface=b2.coating.interface)
            changes["body2"] = Body(mat, coat, b2.Rx, b2.Ry, b2.name, layers=layers)
        note = ", ".join(f"--{k} {v}" if k != "coating" else " ".join(f"--coating {c}" for c in v)
                         for k, v in given.items())
        return case.replace(label=f"{case.label or args.case} with {note}", **changes)
    missing = [f"--{k}" for k in ("W", "R", "substrate") if k not in given]
    if missing:
        raise CoatHertzError(f"give a case file (or example:NAME) or the flags {', '.join(missing)}")
    W = quantity(given["W"], "force", "--W: load W")
    R = _radius_flag(given["R"])
    indenter = _material_flag(given.get("indenter", "rigid"), "--indenter", "indenter")
    substrate = _material_flag(given["substrate"], "--substrate", "substrate")
    coating, layers = _coatings_flag(given["coating"]) if "coating" in given else (None, ())
    return ContactCase(Body(indenter, None, R, R), Body(substrate, coating, layers=layers), W)


def list_examples() -> int:
    from coathertz.casefile import examples, load_example

    for name in examples():
        print(f"example:{name:22s} {load_example(name).label}")
    return 0


def check_output_file(path: str | Path, flag: str) -> Path:
    """Fail now, before any computing, if ``path`` cannot be written: its folder must exist
    and be writable, and ``path`` must not be a folder."""
    p = Path(path)
    if p.is_dir():
        raise CoatHertzError(f"{flag} {str(path)!r} is a folder; give a file name")
    parent = p.parent
    if not parent.exists():
        raise CoatHertzError(f"{flag} {str(path)!r}: the folder {str(parent)!r} does not exist; "
                             f"create it first (mkdir -p {parent})")
    if not parent.is_dir():
        raise CoatHertzError(f"{flag} {str(path)!r}: {str(parent)!r} is not a folder")
    if not os.access(parent, os.W_OK):
        raise CoatHertzError(f"{flag} {str(path)!r}: the folder {str(parent)!r} is not writable")
    existed = p.exists()
    try:  # os.access says yes to root everywhere, /proc included: open it for real
        with open(p, "ab"):
            pass
    except OSError as exc:
        raise CoatHertzError(f"{flag} {str(path)!r}: cannot write there ({exc.strerror or exc}); "
                             "give a writable file name") from None
    if not existed:
        with contextlib.suppress(OSError):
            p.unlink()
    return p


@contextlib.contextmanager
def writing(path: str | Path, flag: str) -> Iterator[Path]:
    """Turn an error while writing ``path`` (disk full, quota, a device) into one line that
    names the flag and the file: ``with writing(out, "--vtu") as p: ...``."""
    try:
        yield Path(path)
    except OSError as exc:
        where = f" {str(exc.filename)!r}" if exc.filename and str(exc.filename) != str(path) else ""
        raise CoatHertzError(f"{flag} {str(path)!r}: writing{where} failed ({exc.strerror or exc}); "
                             "what was written is incomplete") from None


def output_dir(path: str | Path, flag: str = "--out") -> Path:
    """Create the output folder ``path`` (with parents) and check that it is writable."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise CoatHertzError(f"{flag} {str(path)!r} is a file, not a folder; give a folder for the output")
    try:
        p.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=p):
            pass
    except OSError as exc:
        raise CoatHertzError(f"{flag} {str(path)!r}: cannot write there "
                             f"({exc.strerror or exc}); give a writable folder") from None
    return p


def finish(case: ContactCase, res: ContactResult) -> ContactResult:
    """Every result a subcommand prints passes through here: model validity (a/R > 0.1 warns
    with :class:`~coathertz.errors.ModelValidityWarning` and sets ``meta["validity"]``)."""
    from coathertz.validity import check

    return check(case, res)


def to_json(obj: Any) -> str:
    """Strict JSON (inf/nan written as strings), indented."""
    return dumps(obj, indent=2)


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


def add_fields_argument(parser: argparse.ArgumentParser, what: str) -> None:
    """``--save-fields OUT.npz``: the method's arrays (``what`` says which) into one ``.npz``."""
    parser.add_argument("--save-fields", metavar="OUT.npz", help=f"write {what} to an .npz file")


def save_fields(path: str | Path | None, res: ContactResult) -> None:
    """Write ``res.fields`` to ``path`` (checked by :func:`check_output_file` before solving),
    under exactly that name (NumPy's ``.npz`` format whatever the suffix)."""
    if path:
        import numpy as np

        with writing(path, "--save-fields"), open(path, "wb") as f:
            np.savez_compressed(f, **{k: np.asarray(v) for k, v in res.fields.items()})
