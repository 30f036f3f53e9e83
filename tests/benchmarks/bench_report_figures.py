"""Benchmark of the report's figures and the studies' analyses (a script, not part of the test run).

From the store of a finished report folder (every result reused, nothing solved again except what
a study solves in its own ``analyse``), for each study, in this process:

1. the CPU time of ``run_study`` (the analysis, the stored results read back);
2. the CPU time of drawing its figures (building the artists: ``plot_study`` less the writing);
3. the CPU time of writing each PNG (:func:`coathertz.figstyle._write`: the layout engine, the
   drawing, the PNG encoding), with ``--split`` the layout (a tight layout run on its own, as the
   engine does at the start of the drawing), the drawing and the encoding apart.

CPU time is ``time.process_time`` (a loaded machine inflates it less than wall time). The store is
copied first; the report folder is not touched.

Usage: ``python tests/benchmarks/bench_report_figures.py REPORT_DIR [--study NAME ...] [--split]``
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


if __name__ == "__main__":
    main()
