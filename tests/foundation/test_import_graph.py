"""The import graph of coathertz, function-level imports counted: no cycle between its packages
(``coathertz.report`` sits above ``coathertz.verification``, both above ``coathertz.figstyle``),
and the numerical methods import none of each other."""

from __future__ import annotations

import ast
import collections
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCES = {ROOT / "src" / "coathertz": "coathertz", ROOT / "fem": "coathertz.fem",
           ROOT / "verification": "coathertz.verification"}
METHODS = ("coathertz.fft", "coathertz.axisym", "coathertz.fem")


def modules() -> dict[str, Path]:
    out = {}
    for root, pre in SOURCES.items():
        for f in root.rglob("*.py"):
            rel = f.relative_to(root).with_suffix("")
            parts = [p for p in rel.parts if p != "__init__"]
            out[".".join([pre, *parts])] = f
    return out


def imports(name: str, path: Path, known: dict) -> set[str]:
    """Every coathertz module ``name`` imports, at module level or inside a function."""
    pkg = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            cands = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = pkg.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1] + ([node.module] if node.module else []))
            cands = [base] + [f"{base}.{a.name}" for a in node.names]
        else:
            continue
        out |= {c for c in cands if c in known and c != name}
    return out


def package(m: str) -> str:
    return ".".join(m.split(".")[:2])


def package_graph() -> dict[str, set[str]]:
    mods = modules()
    G: dict[str, set[str]] = collections.defaultdict(set)
    for name, path in mods.items():
        for t in imports(name, path, mods):
            if package(t) != package(name):
                G[package(name)].add(package(t))
    return G


def test_no_cycle_between_packages():
    G = package_graph()
    state: dict[str, int] = {}

    def visit(v: str, path: list[str]) -> None:
        state[v] = 1
        for w in sorted(G.get(v, ())):
            assert state.get(w) != 1, "import cycle: " + " -> ".join([*path, v, w])
            if w not in state:
                visit(w, [*path, v])
        state[v] = 2

    for v in sorted(G):
        if v not in state:
            visit(v, [])
    assert {"coathertz.report", "coathertz.verification", "coathertz.figstyle"} <= set(G) | {
        w for ws in G.values() for w in ws}


def test_methods_import_none_of_each_other():
    G = package_graph()
    for m in METHODS:
        others = set(G.get(m, ())) & (set(METHODS) - {m})
        assert not others, f"{m} imports {sorted(others)}: the methods must stay independent"
