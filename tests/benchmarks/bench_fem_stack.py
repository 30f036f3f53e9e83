"""Benchmark of the FE model on layer stacks (a script, not part of the test run).

For each stack of ``tests/multilayer/test_fe_stack.py`` (2-4 layers, bonded and frictionless
interfaces, elastic and rigid substrates, incompressible layers) and the built-in stack examples
it solves the case with ``FEMMethod`` at the mesh levels coarse (n_a = 20), default (40) and fine
(100) and prints, per level, the unknowns, the CPU time of the solve (``time.process_time``: this
process's CPU, so a loaded machine does not inflate it as it does the wall time) and the relative
differences of delta, a, p0 from the exact method (axisym, the arbiter), and per case the
observed order of each difference (least-squares slope of log |difference| against log n_a).

Usage: ``python tests/benchmarks/bench_fem_stack.py [--levels coarse,default,fine] [--json out.json]``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import importlib.util
import json
import platform
import time
from pathlib import Path

import numpy as np

from coathertz.axisym import AxisymMethod
from coathertz.casefile import load_example
from coathertz.errors import CoatHertzError
from coathertz.fem.method import FEMMethod

QS = ("delta", "a", "p0")
N_A = {"coarse": 20, "default": 40, "fine": 100}
EXAMPLES = ("tin_ti_on_steel", "dlc_crn_cr_on_steel", "graded_on_steel")


def _cases() -> dict:
    path = Path(__file__).resolve().parents[1] / "multilayer" / "test_fe_stack.py"
    spec = importlib.util.spec_from_file_location("test_fe_stack", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    out = {name: make() for name, make in mod.CASES.items()}
    out.update({name: load_example(name) for name in EXAMPLES})
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="coarse,default,fine")
    ap.add_argument("--json", metavar="FILE")
    args = ap.parse_args()
    levels = args.levels.split(",")
    load = os.getloadavg()[0]
    print(f"# {platform.machine()}, python {platform.python_version()}, load average {load:.1f}")
    print(f"{'case':28s} {'level':8s} {'dofs':>7s} {'cpu [s]':>8s}  " + "  ".join(f"{q:>9s}" for q in QS))
    rows = []
    for name, case in _cases().items():
        ref = AxisymMethod(keep_fields=False).solve(case)
        errs = {q: [] for q in QS}
        for lev in levels:
            t0 = time.process_time()
            try:
                r = FEMMethod(mesh=lev).solve(case)
            except CoatHertzError as exc:  # the memory guard
                print(f"{name:28s} {lev:8s} refused: {exc}", flush=True)
                continue
            cpu = time.process_time() - t0
            d = {q: getattr(r, q) / getattr(ref, q) - 1.0 for q in QS}
            for q in QS:
                errs[q].append(abs(d[q]))
            rows.append({"case": name, "level": lev, "dofs": r.meta["dofs"], "cpu_s": cpu, **d})
            diffs = "  ".join(f"{d[q]:+9.2e}" for q in QS)
            print(f"{name:28s} {lev:8s} {r.meta['dofs']:7d} {cpu:8.2f}  {diffs}", flush=True)
        if len(errs["delta"]) > 1:
            n = np.log([N_A[lev] for lev in levels][: len(errs["delta"])])
            orders = {q: float(-np.polyfit(n, np.log(np.maximum(errs[q], 1e-16)), 1)[0]) for q in QS}
            print(f"{name:28s} observed order " + ", ".join(f"{q} {o:.2f}" for q, o in orders.items()))
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
