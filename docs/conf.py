"""Sphinx configuration of the coathertz documentation.

Build (warnings are errors, every cross-reference must resolve)::

    .venv/bin/sphinx-build -W -n --keep-going -q -b html docs docs/_build/html

``tests/docs/test_sphinx_build.py`` runs the same build in the default test suite.
"""

from __future__ import annotations

import re
from pathlib import Path

# coathertz is imported as installed (``pip install -e ".[docs]"``): its ``fem`` and
# ``verification`` packages live outside ``src`` and are mapped in by the installation.

project = "coathertz"
author = "the coathertz developers"
copyright = "2026, the coathertz developers"

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",  # the docstrings are numpy style
    "sphinx.ext.mathjax",
    "myst_parser",  # the Markdown pages (README, paper notes, figure style)
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "examples/README.md"]
root_doc = "index"

myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]

autodoc_default_options = {"members": True, "undoc-members": True, "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_typehints_format = "short"
autodoc_member_order = "bysource"
autoclass_content = "class"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # an "Attributes" section as fields: the attributes are documented once

html_theme = "alabaster"
html_title = "coathertz"

nitpicky = True
#: Names that cannot be linked: no intersphinx inventories are fetched (the build runs offline),
#: so the types of numpy, scipy, matplotlib and the standard library have no target. Everything
#: of coathertz itself must resolve.
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|scipy|matplotlib|skfem|meshio|pyamg|dask|distributed|sqlite3)(\..*)?"),
    (r"py:.*", r"(collections\.abc|typing|pathlib|argparse|concurrent\.futures|dataclasses|enum|"
               r"multiprocessing|io|os|types|contextlib)\..*"),
    (r"py:class", r"(ArrayLike|NDArray|Path|Any|Callable|Iterable|Iterator|Sequence|Mapping|"
                  r"MutableMapping|ClassVar|Protocol|Enum|Future|Executor|TextIO|Self|Basis|CellBasis|Mesh)"),
    # a dataclass's generated __init__ keeps its annotations as strings that autodoc leaves quoted
    (r"py:class", r"'.*"),
    (r"py:class", r"(optional|array_like|array-like|callable|ndarray|default .*)"),
    (r"py:(class|obj)", r"(int|float|str|bool|bytes|dict|list|tuple|set|frozenset|complex|object|type|"
                        r"None|Exception|Warning|UserWarning|RuntimeWarning|ValueError|BaseException)"),
]


# -- pages filled from the code: every module, every registered study -----------------------------

def _all_modules() -> list[str]:
    """Every module of coathertz (its ``fem`` and ``verification`` packages included), except the
    command-line front end (documented by ``coathertz --help`` and the README)."""
    import importlib
    import pkgutil

    names = []
    for pkg in ("coathertz", "coathertz.fem", "coathertz.verification"):
        p = importlib.import_module(pkg)
        names.append(pkg)
        names += [m.name for m in pkgutil.walk_packages(p.__path__, pkg + ".")]
    return sorted({n for n in names if not n.startswith("coathertz.cli") and not _alias(n)})


def _alias(name: str) -> bool:
    """A deprecated module kept under an old name that only forwards to its new home."""
    import importlib.util

    spec = importlib.util.find_spec(name)
    return bool(spec and spec.origin and "DEPRECATED ALIAS" in Path(spec.origin).read_text())


def _documented(app) -> set[str]:
    import re

    out: set[str] = set()
    for page in ("api", "contract"):
        text = (Path(app.srcdir) / f"{page}.rst").read_text()
        out |= set(re.findall(r"automodule:: (\S+)", text))
    return out


def _fill(app, docname: str, source: list[str]) -> None:
    if docname == "internals":
        from coathertz.verification import studies

        skip = _documented(app) | {m.__name__ for m in studies().values()}
        for name in _all_modules():
            if name not in skip:
                source[0] += f"\n{name}\n{'-' * len(name)}\n\n.. automodule:: {name}\n"
    elif docname == "examples":
        import ast

        for script in sorted((Path(app.srcdir) / "examples").glob("*.py")):
            doc = ast.get_docstring(ast.parse(script.read_text())) or script.stem
            title, _, rest = doc.partition("\n")
            source[0] += (f"\n{title}\n{'-' * len(title)}\n\n{rest.strip()}\n\n"
                          f".. literalinclude:: examples/{script.name}\n   :language: python\n   :lines: "
                          f"{_after_docstring(script)}-\n")
    elif docname == "studies":
        from coathertz.verification import studies

        for key, mod in studies().items():
            title = f"``{key}``: {mod.TITLE}"
            source[0] += f"\n{title}\n{'-' * len(title)}\n\n.. automodule:: {mod.__name__}\n   :no-members:\n"


_BARS = re.compile(r"(?<![|`\\])\|([^|`\n]{1,40})\|(?![|`])")


def _plain_docstrings(app, what: str, name: str, obj, options, lines: list[str]) -> None:
    """Read the docstrings as written. Runs before napoleon (priority 400):

    * ``|x|`` is an absolute value in the docstrings, not a reStructuredText substitution;
    (an attribute's first line is a sentence, not napoleon's ``type: description``: see
    :func:`_attribute_as_written`).
    """
    for i, line in enumerate(lines):
        if "|" in line and not line.lstrip().startswith(("+-", "+=")):
            lines[i] = _BARS.sub(lambda m: "\\|" + m.group(1) + "\\|", line)


def _attribute_as_written(self) -> list[str]:
    """An attribute's docstring as written: ours are sentences, never ``type: description``."""
    return self._dedent(self._consume_to_end())


def _after_docstring(script: Path) -> int:
    """The first line of ``script`` after its module docstring."""
    import ast

    return ast.parse(script.read_text()).body[0].end_lineno + 2


#: Pages whose text comes from the code (:func:`_fill`): read again on every build, or an
#: incremental build would keep a stale list (a module added since the last build missing).
GENERATED_PAGES = ("internals", "studies", "examples")


def _generated_pages(app, env, added, changed, removed) -> list[str]:
    return [d for d in GENERATED_PAGES if d not in added | changed | removed]


def setup(app):
    from sphinx.ext.napoleon import docstring as napoleon_docstring

    napoleon_docstring.GoogleDocstring._parse_attribute_docstring = _attribute_as_written
    app.connect("source-read", _fill)
    app.connect("env-get-outdated", _generated_pages)
    app.connect("autodoc-process-docstring", _plain_docstrings, priority=400)
    return {"parallel_read_safe": True}
