"""Read and write contact cases as TOML, with explicit units.

Format (every dimensional value carries its unit; ``"inf"`` is a flat surface)::

    label = "B4C coating on 52100 steel, steel ball"
    W = "1 N"
    theta = "0 deg"            # optional, eq (3b)

    [body1]                    # the indenter
    material = { E = "200 GPa", nu = 0.3 }   # or material = "rigid"
    R = "10 mm"                # or Rx = "...", Ry = "..."; default flat

    [body2]                    # the (coated) half-space
    material = { E = "200 GPa", nu = 0.3 }
    coating = { E = "380 GPa", nu = 0.17, h = "40 um" }   # interface = "frictionless" optional

``interface = "bonded"`` (default, the paper's model) or ``"frictionless"`` at the top level sets
every coating's interface; a coating table's own ``interface`` key overrides it.

Optional J2 plasticity (FE ``--plastic`` only) on any elastic material or coating table:
``Y = "1.2 GPa"`` (yield stress) with ``hardening = "perfect"`` (default), ``"linear"``
(``H = "5 GPa"``), ``"power"`` (``n = 0.1``, ``eps0 = 0.002``) or ``"table"``
(``table = [[0, "1.2 GPa"], [0.05, "1.5 GPa"]]``, pairs of plastic strain and flow stress).
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.materials import INTERFACES, RIGID, Body, Coating, Layer, Material, Plasticity
from coathertz.units import parse_quantity

_BODY_KEYS = {"material", "coating", "layers", "R", "Rx", "Ry", "name"}
_TOP_KEYS = {"label", "W", "theta", "interface", "body1", "body2"}
#: Largest |theta| a case file accepts [rad]: one full turn either way (eq 3b is pi-periodic).
THETA_MAX = 2.0 * math.pi


def quantity(text: Any, dimension: str, name: str, *, minimum: str = ">0", allow_inf: bool = False) -> float:
    """Parse ``text`` (:func:`~coathertz.units.parse_quantity`) and check its range, quoting
    the value as the user wrote it in the message.

    ``minimum`` is ``">0"`` (strictly positive) or ``">=0"``; ``allow_inf`` admits ``"inf"``.
    """
    v = parse_quantity(text, dimension, name=name)
    bad = math.isnan(v) or (v <= 0 if minimum == ">0" else v < 0) or (math.isinf(v) and not allow_inf)
    if bad:
        lo = "0 < " if minimum == ">0" else "0 <= "
        hint = {"length": " ('inf': flat)", "pressure": " ('inf': rigid)"}.get(dimension, "")
        hi = f" <= inf{hint}" if allow_inf else " < inf"
        raise CoatHertzError(f"{name} must satisfy {lo}{name.split()[-1]}{hi}, got {text!r}")
    return v


def _where(where: str) -> str:
    """``body2.coating`` -> ``[body2] coating``; ``body1.material`` -> ``[body1] material``."""
    table, _, rest = where.partition(".")
    return f"[{table}] {rest.replace('.', ' ')}".strip()


def _material(spec: Any, where: str) -> Material:
    w = _where(where)
    if spec == "rigid":
        return RIGID
    if not isinstance(spec, dict):
        raise CoatHertzError(f"{w}: expected 'rigid' or a table {{ E = \"...\", nu = ... }}, got {spec!r}")
    unknown = set(spec) - {"E", "nu", "name", "h", *_PLASTIC_KEYS}
    if unknown:
        allowed = sorted({"E", "name", "nu", *_PLASTIC_KEYS})
        raise CoatHertzError(f"{w}: unknown keys {sorted(unknown)}; allowed {allowed}")
    for key in ("E", "nu"):
        if key not in spec:
            raise CoatHertzError(f"{w}: missing {key}")
    E = quantity(spec["E"], "pressure", f"{w} E", allow_inf=True)
    nu = spec["nu"]
    if not isinstance(nu, int | float) or isinstance(nu, bool):
        raise CoatHertzError(f"{w} nu must be a plain number in (-1, 0.5], got {nu!r}")
    plasticity = _plasticity(spec, w)
    try:
        return Material(E, nu, name=str(spec.get("name", "")), plasticity=plasticity)
    except CoatHertzError as exc:
        raise CoatHertzError(f"{w}: {exc}") from None


_PLASTIC_KEYS = ("Y", "hardening", "H", "n", "eps0", "table")


def _plasticity(spec: dict, where: str) -> Plasticity | None:
    """The optional yield data of a material table (keys :data:`_PLASTIC_KEYS`)."""
    given = [k for k in _PLASTIC_KEYS if k in spec]
    if not given:
        return None
    if "Y" not in spec:
        raise CoatHertzError(f"{where}: plasticity keys {given} need the yield stress Y "
                             '(e.g. Y = "1.2 GPa")')
    kw: dict[str, Any] = {"Y": parse_quantity(spec["Y"], "pressure", name=f"{where}.Y"),
                          "hardening": str(spec.get("hardening", "perfect"))}
    if kw["hardening"] == "linear" and "H" not in spec:
        raise CoatHertzError(f'{where}: hardening = "linear" needs the hardening modulus H '
                             '(H >= 0, e.g. H = "10 GPa")')
    if "H" in spec:
        kw["H"] = parse_quantity(spec["H"], "pressure", name=f"{where}.H")
    for k in ("n", "eps0"):
        if k in spec:
            if not isinstance(spec[k], int | float) or isinstance(spec[k], bool):
                raise CoatHertzError(f"{where}.{k} must be a plain number, got {spec[k]!r}")
            kw[k] = float(spec[k])
    if "table" in spec:
        tab = spec["table"]
        if not isinstance(tab, list) or not all(isinstance(t, list) and len(t) == 2 for t in tab):
            raise CoatHertzError(f"{where}.table must be a list of [ep, \"Y\"] pairs, got {tab!r}")
        kw["table"] = tuple((float(e), parse_quantity(y, "pressure", name=f"{where}.table"))
                            for e, y in tab)
    return Plasticity(**kw)


def _interface(value: Any, where: str) -> str:
    if value not in INTERFACES:
        raise CoatHertzError(f"{where} must be one of {list(INTERFACES)}, got {value!r}")
    return value


def _body(spec: Any, where: str, interface: str = "bonded") -> Body:
    if not isinstance(spec, dict):
        raise CoatHertzError(f"[{where}] must be a table")
    unknown = set(spec) - _BODY_KEYS
    if unknown:
        raise CoatHertzError(f"[{where}]: unknown keys {sorted(unknown)}; allowed {sorted(_BODY_KEYS)}")
    if "material" not in spec:
        raise CoatHertzError(f"[{where}]: missing 'material' (the substrate: 'rigid' or {{ E, nu }})")
    material = _material(spec["material"], f"{where}.substrate material")
    coating = None
    if "coating" in spec:
        c = spec["coating"]
        if not isinstance(c, dict) or "h" not in c:
            raise CoatHertzError(f"[{where}] coating must be a table with E, nu and h, got {c!r}")
        cmat = _material({k: v for k, v in c.items() if k not in ("h", "interface")}, f"{where}.coating")
        h = quantity(c["h"], "length", f"[{where}] coating thickness h", minimum=">=0")
        interface = _interface(c.get("interface", interface), f"[{where}] coating interface")
        try:
            coating = Coating(cmat, h, interface)
        except CoatHertzError as exc:
            raise CoatHertzError(f"[{where}] coating: {exc}") from None
    layers = _layers(spec["layers"], where) if "layers" in spec else ()
    if layers and coating is not None:
        raise CoatHertzError(f"[{where}]: give either a coating or [[{where}.layers]], not both")
    if "R" in spec and ("Rx" in spec or "Ry" in spec):
        raise CoatHertzError(f"[{where}]: give either R or Rx/Ry, not both")
    if "R" in spec:
        Rx = Ry = quantity(spec["R"], "length", f"[{where}] sphere radius R", allow_inf=True)
    else:
        Rx = quantity(spec.get("Rx", math.inf), "length", f"[{where}] radius Rx", allow_inf=True)
        Ry = quantity(spec.get("Ry", math.inf), "length", f"[{where}] radius Ry", allow_inf=True)
    try:
        return Body(material, coating, Rx, Ry, name=str(spec.get("name", "")), layers=layers)
    except CoatHertzError as exc:
        raise CoatHertzError(f"[{where}]: {exc}") from None


_LAYER_KEYS = {"E", "nu", "h", "interface", "name", *_PLASTIC_KEYS}


def _layers(spec: Any, where: str) -> tuple[Layer, ...]:
    """``[[bodyN.layers]]`` tables (top first), each ``E, nu, h`` and optionally ``interface``
    (``bonded``, the default, or ``frictionless``: how the layer's lower face is joined)."""
    if not isinstance(spec, list) or not all(isinstance(t, dict) for t in spec):
        raise CoatHertzError(f"[{where}] layers must be [[{where}.layers]] tables, got {spec!r}")
    if not spec:
        raise CoatHertzError(f"[{where}] layers: the stack is empty (give at least one "
                             f"[[{where}.layers]] table with E, nu and h)")
    out = []
    for i, t in enumerate(spec, 1):
        w = f"[{where}] layer {i}"
        unknown = set(t) - _LAYER_KEYS
        if unknown:
            raise CoatHertzError(f"{w}: unknown keys {sorted(unknown)}; allowed "
                                 f"{sorted({'E', 'nu', 'h', 'interface', 'name'})}")
        if "h" not in t:
            raise CoatHertzError(f"{w}: missing h (the layer thickness)")
        mat = _material({k: v for k, v in t.items() if k not in ("h", "interface")}, f"{where}.layer {i}")
        h = quantity(t["h"], "length", f"{w} thickness h")
        layer = Layer(mat, h, str(t.get("interface", "bonded")))
        layer.check(w)
        out.append(layer)
    return tuple(out)


def case_from_dict(data: dict) -> ContactCase:
    """Build a :class:`~coathertz.case.ContactCase` from a parsed TOML document."""
    unknown = set(data) - _TOP_KEYS
    if unknown:
        raise CoatHertzError(f"case file: unknown keys {sorted(unknown)}; allowed {sorted(_TOP_KEYS)}")
    for key in ("W", "body1", "body2"):
        if key not in data:
            raise CoatHertzError(f"case file: missing '{key}'")
    W = quantity(data["W"], "force", "load W")
    theta = parse_quantity(data.get("theta", 0.0), "angle", name="theta")
    if not abs(theta) <= THETA_MAX:  # also NaN; cos(2 theta) of eq (3b) loses every digit past ~1e16
        raise CoatHertzError(f"theta (angle between the bodies' principal planes, eq 3b) must be in "
                             f"[-360 deg, 360 deg], got {data['theta']!r}")
    interface = _interface(data.get("interface", "bonded"), "interface")
    return ContactCase(_body(data["body1"], "body1", interface), _body(data["body2"], "body2", interface),
                       W, theta,
                       label=str(data.get("label", "")))


def load_case(path: str | Path) -> ContactCase:
    """Load a case from a TOML file, or a built-in example given as ``example:NAME``."""
    text = str(path)
    if text.startswith("example:"):
        return load_example(text.split(":", 1)[1])
    p = Path(path)
    if p.is_dir():
        raise CoatHertzError(f"case file {text!r} is a directory; give a TOML case file or example:NAME")
    if not p.exists():
        raise CoatHertzError(f"case file {text!r} does not exist (built-ins: "
                             f"{', '.join('example:' + e for e in examples())})")
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise CoatHertzError(f"cannot read case file {text!r}: {exc.strerror or exc}") from exc
    try:
        data = tomllib.loads(raw.decode("utf-8-sig"))  # a byte-order mark (Windows editors) is dropped
    except UnicodeDecodeError as exc:
        raise CoatHertzError(f"case file {text!r} is not a text (UTF-8 TOML) file: "
                             f"byte {exc.start} cannot be decoded") from None
    except tomllib.TOMLDecodeError as exc:
        raise CoatHertzError(f"case file {text!r} is not valid TOML: {exc}") from exc
    return case_from_dict(data)


def examples() -> list[str]:
    """Names of the built-in example cases (``example:NAME``)."""
    files = resources.files("coathertz") / "data"
    return sorted(f.name[:-5] for f in files.iterdir() if f.name.endswith(".toml"))


def load_example(name: str) -> ContactCase:
    f = resources.files("coathertz") / "data" / f"{name}.toml"
    if not f.is_file():
        raise CoatHertzError(f"unknown example {name!r}; choose one of {examples()}")
    return case_from_dict(tomllib.loads(f.read_text()))


def _q(value: float, unit: str, factor: float) -> str:
    return "inf" if math.isinf(value) else f"{value / factor:.12g} {unit}"


def _plastic_toml(m: Material) -> str:
    pl = m.plasticity
    if pl is None:
        return ""
    out = f', Y = "{_q(pl.Y, "MPa", 1e6)}", hardening = "{pl.hardening}"'
    if pl.hardening == "linear":
        out += f', H = "{_q(pl.H, "MPa", 1e6)}"'
    elif pl.hardening == "power":
        out += f", n = {pl.n!r}, eps0 = {pl.eps0!r}"
    elif pl.hardening == "table":
        out += ", table = [" + ", ".join(f'[{e!r}, "{_q(y, "MPa", 1e6)}"]' for e, y in pl.table) + "]"
    return out


def _mat(m: Material) -> str:
    if m.is_rigid:
        return '"rigid"'
    return f'{{ E = "{_q(m.E, "GPa", 1e9)}", nu = {m.nu!r}{_plastic_toml(m)} }}'


def case_to_toml(case: ContactCase) -> str:
    """Write ``case`` in the TOML format read by :func:`load_case`."""
    lines = []
    if case.label:
        lines.append(f"label = {case.label!r}".replace("'", '"'))
    lines.append(f'W = "{_q(case.W, "N", 1.0)}"')
    if case.theta:
        lines.append(f'theta = "{case.theta!r} rad"')
    for i, b in enumerate((case.body1, case.body2), start=1):
        lines += ["", f"[body{i}]", f"material = {_mat(b.material)}"]
        if b.coating is not None:
            c = b.coating
            iface = "" if c.interface == "bonded" else f', interface = "{c.interface}"'
            lines.append(f'coating = {{ E = "{_q(c.material.E, "GPa", 1e9)}", nu = {c.material.nu!r}, '
                         f'h = "{_q(c.h, "um", 1e-6)}"{iface}{_plastic_toml(c.material)} }}')
        lines.append(f'Rx = "{_q(b.Rx, "mm", 1e-3)}"')
        lines.append(f'Ry = "{_q(b.Ry, "mm", 1e-3)}"')
        for L in b.layers:  # arrays of tables after the body's keys
            lines += [f"[[body{i}.layers]]", f'E = "{_q(L.material.E, "GPa", 1e9)}"',
                      f"nu = {L.material.nu!r}", f'h = "{_q(L.h, "um", 1e-6)}"']
            if L.interface != "bonded":
                lines.append(f'interface = "{L.interface}"')
    return "\n".join(lines) + "\n"
