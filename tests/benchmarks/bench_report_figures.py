"""Benchmark of the report's figures and the studies' analyses (a script, not part of the test run).

From the store of a finished report folder (every result reused, nothing solved again except what
a study solves in its own ``analyse``), for each study, in this process:

1. the CPU time of ``run_study`` (the analysis, the stored results read back);
2. the CPU time of drawing its figures (building the artists: ``plot_study`` less the writing);
3. the CPU time of writing each PNG (:func:`coathertz.figstyle._write`: the layout engine, the
   drawing, the PNG encoding), with ``--split`` the layout (a tight layout run on its own, as the
   engine does at the start of the drawing), the drawing and the encoding apart.

With ``--jobs N`` the figures are instead made as ``coathertz verify`` makes them, in a
:func:`~coathertz.figstyle.saving` block with ``N`` jobs (forked render processes), one block per
study: the CPU time of this process (``parent``: what the figures cost the main job's spine) and
of the render processes (``renders``, from ``getrusage(RUSAGE_CHILDREN)``) are printed.

CPU time is ``time.process_time`` (a loaded machine inflates it less than wall time). The store is
copied first; the report folder is not touched.

Usage: ``python tests/benchmarks/bench_report_figures.py REPORT_DIR [--study NAME ...] [--split]
[--jobs N]``
(``REPORT_DIR``: the ``--out`` of a ``coathertz verify --quick`` run; default every study but
``yield_onset``, whose analysis solves its onsets again).
"""

from __future__ import annotations

import argparse
import io
import shutil
import tempfile
import time
import warnings
from pathlib import Path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("report", type=Path, help="report folder with store.sqlite")
    ap.add_argument("--study", action="append", help="study (repeatable; default all but yield_onset)")
    ap.add_argument("--split", action="store_true", help="time layout, drawing and encoding apart")
    ap.add_argument("--jobs", type=int, default=1, help="render in forked processes, as verify does")
    args = ap.parse_args()

    import matplotlib.image

    from coathertz import figstyle
    from coathertz.report import plot_study
    from coathertz.store import open_run_store
    from coathertz.verification import build_methods, get_study, run_study, studies

    warnings.simplefilter("ignore")
    names = args.study or [n for n in studies() if n != "yield_onset"]
    tmp = Path(tempfile.mkdtemp(prefix="bench-figures-"))
    shutil.copy(args.report / "store.sqlite", tmp / "store.sqlite")
    store = open_run_store(tmp / "store.sqlite")
    methods, _ = build_methods("quick")
    written: list[tuple[str, float]] = []
    parts = {"layout": 0.0, "draw": 0.0, "encode": 0.0}
    original = figstyle._write

    def timed(fig, paths):
        t = time.process_time()
        if args.split:
            figstyle._prepare(fig)  # as _write does
            engine = fig.get_layout_engine()
            fig.set_dpi(figstyle.PNG_DPI)
            title = getattr(fig, "_suptitle", None)
            if engine is not None and title is not None:
                title.set_wrap(True)
            if engine is not None:
                engine.execute(fig)
                fig.set_layout_engine("none")
            t1 = time.process_time()
            fig.canvas.draw()
            t2 = time.process_time()
            matplotlib.image.imsave(io.BytesIO(), fig.canvas.buffer_rgba(), format="png",
                                    dpi=figstyle.PNG_DPI)
            t3 = time.process_time()
            parts["layout"] += t1 - t
            parts["draw"] += t2 - t1
            parts["encode"] += t3 - t2
        else:
            original(fig, paths)
        written.append((paths[0].name, time.process_time() - t))

    if args.jobs > 1:
        return _forked(args, names, tmp, store, methods)
    figstyle._write = timed
    total = {"analyse": 0.0, "build": 0.0, "write": 0.0}
    print(f"{'study':12s} {'analyse':>8s} {'build':>7s} {'write':>7s}  [CPU-s]  per figure")
    try:
        for name in names:
            mod = get_study(name)
            t = time.process_time()
            result = run_study(mod, "quick", methods, store, {"workers": 1, "progress": False})
            analyse = time.process_time() - t
            k = len(written)
            with figstyle.saving(("png",), 1):
                t = time.process_time()
                plot_study(result, mod, tmp / "figures")
                plot = time.process_time() - t
            write = sum(x for _, x in written[k:])
            total["analyse"] += analyse
            total["build"] += plot - write
            total["write"] += write
            print(f"{name:12s} {analyse:8.2f} {plot - write:7.2f} {write:7.2f}  "
                  + ", ".join(f"{f} {x:.2f}" for f, x in written[k:]), flush=True)
    finally:
        figstyle._write = original
        store.close()
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{'total':12s} {total['analyse']:8.2f} {total['build']:7.2f} {total['write']:7.2f}  "
          f"({len(written)} figures)")
    if args.split:
        print("writing: " + ", ".join(f"{k} {v:.2f}" for k, v in parts.items()))


def _forked(args, names, tmp, store, methods) -> None:
    """Per study: its analysis, then its figures in a saving block of ``args.jobs`` jobs (this
    process's CPU and its render processes')."""
    import resource

    from coathertz import figstyle
    from coathertz.report import plot_study
    from coathertz.verification import get_study, run_study

    def children() -> float:
        r = resource.getrusage(resource.RUSAGE_CHILDREN)
        return r.ru_utime + r.ru_stime

    total = {"parent": 0.0, "renders": 0.0}
    print(f"{'study':12s} {'parent':>7s} {'renders':>8s}  [CPU-s, {args.jobs} jobs]  figures")
    try:
        for name in names:
            mod = get_study(name)
            result = run_study(mod, "quick", methods, store, {"workers": 1, "progress": False})
            t, c = time.process_time(), children()
            with figstyle.saving(("png",), args.jobs):
                paths = plot_study(result, mod, tmp / "figures")
            parent, renders = time.process_time() - t, children() - c
            total["parent"] += parent
            total["renders"] += renders
            print(f"{name:12s} {parent:7.2f} {renders:8.2f}  {len(paths)}", flush=True)
    finally:
        store.close()
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{'total':12s} {total['parent']:7.2f} {total['renders']:8.2f}  "
          f"(sum {total['parent'] + total['renders']:.2f})")


if __name__ == "__main__":
    main()
