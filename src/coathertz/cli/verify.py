"""``coathertz verify``: run the paper's studies with every method that applies and write a report."""

from __future__ import annotations

import argparse
import signal
import sys
import time
from pathlib import Path

NAME = "verify"
HELP = "run the paper's studies (closed form, FFT, FE) and write the verification report"
#: What to lower when the command runs out of memory (named in the error).
MEMORY_HINT = "a lower resolution (--tiny, --quick)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    res = parser.add_mutually_exclusive_group()
    res.add_argument("--quick", dest="resolution", action="store_const", const="quick",
                     help="quick resolution (default): a few E and H per figure, a handful of FE cases")
    res.add_argument("--full", dest="resolution", action="store_const", const="full",
                     help="the paper's grids (fig 3: 25 E x 101 H, ...)")
    res.add_argument("--tiny", dest="resolution", action="store_const", const="tiny",
                     help="smallest resolution (tests)")
    parser.set_defaults(resolution="quick")
    parser.add_argument("--study", action="append", metavar="NAME",
                        help="study to run (repeatable; default all; see --list)")
    parser.add_argument("--method", action="append", metavar="NAME",
                        help="method to run (repeatable; default all registered; see --list)")
    parser.add_argument("--out", type=Path, help="report folder (default reports/<resolution>)")
    parser.add_argument("--baseline", type=Path, metavar="FILE",
                        help="baseline.json of an earlier run: exit 1 if a claim moved beyond its tolerance")
    parser.add_argument("--scheduler", metavar="ADDR",
                        help="dask.distributed scheduler, e.g. tcp://host:8786 (needs coathertz[dask])")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    parser.add_argument("--store", type=Path, help="result store (default OUT/store.sqlite)")
    parser.add_argument("--retry-errors", action="store_true", help="rerun cases stored as failed")
    parser.add_argument("--recover-store", action="store_true",
                        help="if the store is damaged, move it aside to STORE.damaged-<time> (kept) "
                             "and recompute")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.add_argument("--list", action="store_true", help="list the studies and methods and exit")


def _sigterm(signum, frame):  # pragma: no cover - exercised through a subprocess
    raise KeyboardInterrupt


def run(args: argparse.Namespace) -> int:
    from coathertz.cli._common import output_dir
    from coathertz.errors import CoatHertzError
    from coathertz.methods import method_info, method_names
    from coathertz.report import write_report
    from coathertz.report.baseline import load_baseline
    from coathertz.report.document import verdict_counts
    from coathertz.report.provenance import collect
    from coathertz.store import open_run_store
    from coathertz.verification import build_methods, get_study, run_study, studies

    if args.list:
        for name, mod in studies().items():
            print(f"study  {name:10s} {mod.TITLE}")
            for v, (base, extra) in getattr(mod, "VARIANTS", {}).items():
                print(f"         variant {v}: {base} with {extra} (runs with {base}, on this study's cases)")
        for name in method_names():
            i = method_info(name)
            print(f"method {name:12s} {i.label}; cost {i.cost}, reference rank {i.reference_rank}")
        return 0
    if args.workers < 1:
        raise CoatHertzError(f"--workers must be >= 1, got {args.workers}")
    mods = [get_study(n) for n in args.study] if args.study else list(studies().values())
    baseline = load_baseline(args.baseline) if args.baseline else None
    methods, notes = build_methods(args.resolution, args.method)
    out = output_dir(args.out or Path("reports") / args.resolution, "--out")
    for n in notes:
        print(f"coathertz verify: note: {n}", file=sys.stderr)
    store = open_run_store(args.store or out / "store.sqlite", recover=args.recover_store,
                           note=lambda m: print(f"coathertz verify: note: {m}", file=sys.stderr))
    opts = {"workers": args.workers, "scheduler": args.scheduler,
            "progress": not args.no_progress and sys.stderr.isatty(), "retry_errors": args.retry_errors}
    old = signal.signal(signal.SIGTERM, _sigterm)
    t0 = time.perf_counter()
    results = []
    try:
        for mod in mods:
            r = run_study(mod, args.resolution, methods, store, opts)
            results.append(r)
            n = len({x['case'] for x in r.rows})
            print(f"{r.name:9s} {n:5d} case{'s' if n != 1 else ' '} ({r.computed} solved now, "
                  f"{r.reused} reused from the store) {r.wall_time:7.1f} s  claims: "
                  f"{verdict_counts([c.verdict for c in r.claims])}", flush=True)
    except KeyboardInterrupt:
        print(f"coathertz verify: interrupted; {store.count()} results are in {store.path}; "
              "run the same command again to resume", file=sys.stderr)
        return 130
    finally:
        signal.signal(signal.SIGTERM, old)
    total = time.perf_counter() - t0
    prov = collect(args.resolution, {"studies": ", ".join(r.name for r in results),
                                     "methods": ", ".join(sorted(methods)),
                                     "workers": args.scheduler or args.workers,
                                     "total_run_time": f"{total:.1f} s",
                                     "store": str(store.path)})
    store.export_csv(out / "store.csv")
    store.export_json(out / "store.json")
    store.close()
    files = write_report(results, out, prov, {m.NAME: m for m in mods}, baseline, notes)
    print(f"all studies: {verdict_counts([c.verdict for r in results for c in r.claims])}")
    print(f"report: {files.html} ({total:.1f} s)")
    if files.drift is not None:
        if files.drifted:
            print(f"regression: {len(files.drifted)} claim(s) moved beyond tolerance:")
            for d in files.drifted:
                print(f"  {d.describe()}")
            return 1
        print("regression: no drift beyond tolerances")
    return 0
