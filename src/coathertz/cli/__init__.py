"""``coathertz`` command line: one module per subcommand in this package.

Each subcommand module defines ``NAME``, ``HELP``, ``add_arguments(parser)`` and
``run(args) -> int``; :func:`main` discovers them with ``pkgutil``, so adding a
module adds a subcommand. Modules import their heavy dependencies inside ``run``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import sys
import warnings
from collections.abc import Sequence

from coathertz import __version__
from coathertz.errors import CoatHertzError, ConvergenceError


def _subcommands() -> list:
    mods = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(mod, "NAME") and hasattr(mod, "run"):
            mods.append(mod)
    return sorted(mods, key=lambda m: m.NAME)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="coathertz",
        description="Verify the extended Hertz theory of coated bodies (closed form, DC-FFT, FE).",
    )
    parser.add_argument("--version", action="version", version=f"coathertz {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for mod in _subcommands():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run, _memory_hint=getattr(mod, "MEMORY_HINT", "a smaller problem"))
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``coathertz`` console script; returns the exit status.

    Exit status: 0 success, 1 regression drift (``verify --baseline``), 2 bad input, a solver
    that did not converge, or a file that cannot be read or written (one-line message on
    stderr, no traceback), 130 interrupted, 141 (128 + SIGPIPE) when the reader of the output
    went away (``| head``: quietly, as Unix tools do). Warnings go to stderr as
    ``coathertz CMD: warning:``.
    """
    from coathertz.allocator import keep_freed_memory

    parser = build_parser()
    args = parser.parse_args(argv)
    prefix = f"coathertz {args.command}"
    keep_freed_memory()  # fewer page faults in the solvers (see coathertz.allocator)

    def show(message, category, filename, lineno, file=None, line=None):
        print(f"{prefix}: warning: {message}", file=sys.stderr)

    with warnings.catch_warnings():
        warnings.showwarning = show
        try:
            status = int(args._run(args) or 0)
            sys.stdout.flush()  # a closed pipe shows here, not in the interpreter's exit
            return status
        except (CoatHertzError, ConvergenceError) as exc:
            print(f"{prefix}: error: {exc}", file=sys.stderr)
            return 2
        except BrokenPipeError:  # stdout closed by its reader: stop quietly
            _silence_stdout()
            return 141
        except OSError as exc:  # a file the command had to read or write
            where = f" {exc.filename!r}" if exc.filename else ""
            print(f"{prefix}: error: cannot access{where}: {exc.strerror or exc}", file=sys.stderr)
            return 2
        except MemoryError:
            print(f"{prefix}: error: out of memory; use {args._memory_hint}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print(f"{prefix}: interrupted", file=sys.stderr)
            return 130


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush raises nothing."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # pragma: no cover - stdout without a descriptor
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
