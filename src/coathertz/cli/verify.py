"""``coathertz verify``: run the paper's studies with every method that applies and write a report."""

from __future__ import annotations

import argparse
import contextlib
import gc
import signal
import sys
import time
from pathlib import Path

NAME = "verify"
HELP = "run the paper's studies (closed form, FFT, FE) and write the verification report"
#: What to lower when the command runs out of memory (named in the error).
MEMORY_HINT = "a lower resolution (--tiny, --quick)"

#: dask.distributed protocols a scheduler of another process can be reached by.
SCHEDULER_PROTOCOLS = ("tcp", "tls", "ws", "wss", "ucx")


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
    parser.add_argument("--workers", type=int, default=2,
                        help="local worker processes, for the cases and for rendering figures (default 2)")
    parser.add_argument("--svg", action="store_true",
                        help="also write every figure as SVG (vector copies; the report embeds the PNGs)")
    parser.add_argument("--store", type=Path, help="result store (default OUT/store.sqlite)")
    parser.add_argument("--retry-errors", action="store_true", help="rerun cases stored as failed")
    parser.add_argument("--recover-store", action="store_true",
                        help="if the store is damaged, move it aside to STORE.damaged-<time> (kept) "
                             "and recompute")
    parser.add_argument("--no-progress", action="store_true",
                        help="no progress on stderr (default: a line redrawn on a terminal, else a line "
                             "every few seconds: cases done, rate, elapsed, time left by measured cost)")
    parser.add_argument("--list", action="store_true", help="list the studies and methods and exit")


def _sigterm(signum, frame):  # pragma: no cover - exercised through a subprocess
    raise KeyboardInterrupt


def study_line(name: str, cases: int, solved: int, reused: int, seconds: float) -> str:
    """The console line of one finished study (README quotes it): its cases, and its results
    (one per case and method) solved in this run or reused from the store."""
    results = solved + reused
    return (f"{name:9s} {cases:5d} case{'s' if cases != 1 else ''}, {results} result"
            f"{'s' if results != 1 else ''} ({solved} solved now, {reused} reused from the store) "
            f"{seconds:7.1f} s")


def check_scheduler(address: str) -> str:
    """Fail now, with one line, on a ``--scheduler`` that is not ``[PROTOCOL://]HOST:PORT``."""
    from coathertz.errors import CoatHertzError

    try:
        from distributed.comm import parse_address
        from distributed.comm.addressing import parse_host_port
    except ImportError:
        raise CoatHertzError("--scheduler needs dask.distributed: pip install 'coathertz[dask]'") from None
    try:
        scheme, loc = parse_address(address)
        if scheme not in SCHEDULER_PROTOCOLS:
            raise ValueError(f"protocol {scheme!r} is not one of {', '.join(SCHEDULER_PROTOCOLS)}")
        host, _ = parse_host_port(loc)
        if not host or any(c.isspace() for c in host):
            raise ValueError(f"no host name in {loc!r}")
    except (ValueError, TypeError) as exc:
        raise CoatHertzError(f"--scheduler {address!r} is not a scheduler address ({exc}); give "
                             "PROTOCOL://HOST:PORT, e.g. tcp://127.0.0.1:8786") from None
    return address


def _once(fn):
    """``fn`` for its first call, then an empty list (a study calls the runner twice: its cases,
    then its reference refinements; the next study's cases go ahead once)."""
    calls = []

    def call():
        if calls:
            return []
        calls.append(1)
        return fn()
    return call


def run(args: argparse.Namespace) -> int:
    from coathertz.cli._common import output_dir, writing
    from coathertz.errors import CoatHertzError
    from coathertz.figstyle import saving
    from coathertz.methods import method_info, method_names
    from coathertz.report import plot_study, write_report
    from coathertz.report.baseline import load_baseline
    from coathertz.report.document import verdict_counts
    from coathertz.report.provenance import collect
    from coathertz.runner import worker_pool
    from coathertz.store import open_run_store
    from coathertz.verification import build_methods, get_study, run_study, studies
    from coathertz.verification.running import study_tasks

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
    if args.scheduler is not None:
        check_scheduler(args.scheduler)
    mods = [get_study(n) for n in args.study] if args.study else list(studies().values())
    baseline = load_baseline(args.baseline) if args.baseline else None
    methods, notes = build_methods(args.resolution, args.method)
    out_path = args.out or Path("reports") / args.resolution

    def note(m: str) -> None:
        print(f"coathertz verify: note: {m}", file=sys.stderr)

    if args.store:  # a store that is busy or damaged fails before the --out folder is created
        store = open_run_store(args.store, recover=args.recover_store, note=note)
        try:
            out = output_dir(out_path, "--out")
        except BaseException:
            store.close()
            raise
    else:
        out = output_dir(out_path, "--out")
        store = open_run_store(out / "store.sqlite", recover=args.recover_store, note=note)
    for n in notes:
        note(n)
    opts = {"workers": args.workers, "scheduler": args.scheduler,
            "progress": not args.no_progress, "retry_errors": args.retry_errors}
    old = signal.signal(signal.SIGTERM, _sigterm)
    # the objects that exist now (modules, methods, the store) live as long as the run: kept out
    # of the garbage collector's scans, in this process and in the worker and render processes
    # forked from it (a scan writes to every object it visits, so each child would copy them)
    gc.freeze()
    t0 = time.perf_counter()
    results = []
    figures: dict[str, list[Path]] = {}
    figdir = out / "figures"
    try:
        # each study's figures are drawn as soon as it is done and rendered in the background
        # while the next study runs (the block ends when every render has finished)
        # one pool of worker processes for all the studies (started once, caches kept)
        pool = worker_pool(args.workers, store) if args.scheduler is None else contextlib.nullcontext()
        with pool, saving(("png", "svg") if args.svg else ("png",), 1 if args.scheduler else args.workers):
            # studies whose analysis solves in processes of its own (``RUN_EARLY``) first, so that
            # the next studies' cases fill the workers it leaves idle; the report keeps the order
            order = sorted(mods, key=lambda m: not getattr(m, "RUN_EARLY", False))
            planned = 1  # the studies of ``order`` whose cases were handed to the runner ahead

            def ahead(i: int):
                # the cases of every later study not handed over yet, study by study (the first
                # call hands over all of them): the workers solve them while this process
                # analyses and draws, however long that takes
                nonlocal planned
                todo, planned = order[max(planned, i + 1):], len(order)
                return (study_tasks(m, args.resolution, methods) for m in todo)

            for i, mod in enumerate(order):
                nxt = None if args.scheduler is not None else _once(lambda i=i: ahead(i))
                r = run_study(mod, args.resolution, methods, store, {**opts, "ahead": nxt})
                results.append(r)
                n = len({x['case'] for x in r.rows})
                print(study_line(r.name, n, r.computed, r.reused, r.wall_time) + "  claims: "
                      + verdict_counts([c.verdict for c in r.claims]), flush=True)
                with writing(figdir, "--out"):
                    figures[r.name] = plot_study(r, mod, figdir)
            t_studies = time.perf_counter()
            results.sort(key=lambda r: [m.NAME for m in mods].index(r.name))
            # every result is stored now: the store is exported while the last figures render
            try:
                with writing(out / "store.csv", "--out"):
                    store.export_csv(out / "store.csv")
                with writing(out / "store.json", "--out"):
                    store.export_json(out / "store.json")
            except BaseException:
                store.close()
                raise
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
    store.close()
    with writing(out, "--out"):  # a full disk: the folder named, not a traceback
        files = write_report(results, out, prov, {m.NAME: m for m in mods}, baseline, notes,
                             figures=figures)
    print(f"all studies: {verdict_counts([c.verdict for r in results for c in r.claims])}")
    pages = time.perf_counter() - t0 - total
    print(f"report: {files.html} (studies {t_studies - t0:.1f} s; their figures and the store's "
          f"export done {t0 + total - t_studies:.1f} s later; pages {pages:.1f} s)")
    if files.drift is not None:
        if files.drifted:
            print(f"regression: {len(files.drifted)} claim(s) moved beyond tolerance:")
            for d in files.drifted:
                print(f"  {d.describe()}")
            return 1
        print("regression: no drift beyond tolerances")
    return 0
