"""The import graph of coathertz, function-level imports counted: no cycle between its modules
(a package's ``__init__`` counts as a module: ``coathertz.report`` sits above
``coathertz.verification``, both above ``coathertz.figstyle``; the shipped closed form below the
offline fit), and the numerical methods import none of each other."""

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
            # ``from pkg import sub`` imports the submodule (and the package, which is always
            # entered first); ``from mod import name`` imports the module
            subs = [f"{base}.{a.name}" for a in node.names if f"{base}.{a.name}" in known]
            cands = subs or [base]
        else:
            continue
        for c in cands:
            if c not in known or c == name:
                continue
            out.add(c)
            # importing pkg.sub runs pkg/__init__ first, unless the importer is inside pkg already
            parts = c.split(".")
            for k in range(2, len(parts)):
                parent = ".".join(parts[:k])
                if parent in known and parent != name and not name.startswith(parent + "."):
                    out.add(parent)
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


def module_graph() -> dict[str, set[str]]:
    mods = modules()
    return {name: imports(name, path, mods) for name, path in mods.items()}


def test_no_cycle_between_modules():
    G = module_graph()
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
    assert "coathertz.figstyle" in G["coathertz.report"] | G["coathertz.verification"]


def test_methods_import_none_of_each_other():
    G = package_graph()
    for m in METHODS:
        others = set(G.get(m, ())) & (set(METHODS) - {m})
        assert not others, f"{m} imports {sorted(others)}: the methods must stay independent"
