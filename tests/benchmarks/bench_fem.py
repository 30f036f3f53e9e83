"""Benchmark of the axisymmetric FE model (a script, not part of the test run).

For each case at the default mesh it reports the wall time of ``FEMMethod.solve`` (median of
``--repeat`` solves), the factorisations and active-set iterations per solve, and ``delta``,
``a``, ``p0`` to full precision. Cases:

* ``keer_a``: Section 6, Keer et al. case A (two identical coated balls; goal <= 0.4 s);
* ``thin``: rigid sphere on a thin stiff coating, E = Ec/Es = 4, H = h/a0s = 0.01 (goal <= 1.5 s);
* ``rigid_base``: rigid sphere on an incompressible layer (nu_c = 0.5, H = h/a0c = 0.2) bonded
  to a rigid base (mixed u-p system, the other factorisation path).

``--json FILE`` writes the numbers; ``--compare FILE`` checks delta, a, p0 against an earlier
output and prints the time ratios. With ``--legacy`` every case is also solved, in the same
process, by

* ``_before``: the path before the condensed contact solve, on the mesh before the edge band (refactorising
  active set, skfem's generic assembly, no edge band, L = 40): the numbers of
  ``bench_fem_before.json`` (measured on the unmodified code);
* ``_newpath``: the condensed solve (one factorisation) on that same old mesh: the same numbers
  to round-off, so its time against ``_before`` is the solver's speed-up;

and the plain rows are the default (edge band s0/3, L = 160), so the ratios are measured in one
run on the shared machine.

``--baseline REV`` (a git revision) times the ``fem/`` package of ``REV`` against the working
tree's in one run: each version runs in its own worker process (the same interpreter and
environment) and the solves alternate between the two, so that a shared, loaded machine slows
both alike; it prints the median wall and CPU time of both, their ratios, the factorisations per
solve and the largest relative difference in ``delta``, ``a``, ``p0`` (the "identical results"
check). On a machine shared with other jobs run it with ``OPENBLAS_NUM_THREADS=1``: the CPU times
then measure the work of each version, undisturbed by BLAS threads waiting for a busy core.
``bench_fem_baseline.json`` holds such a run.

Usage: ``python tests/benchmarks/bench_fem.py [--repeat 3] [--legacy] [--baseline REV] [--json out.json]``.
"""

from __future__ import annotations

import argparse
import importlib.abc
import importlib.machinery
import inspect
import json
import os
import platform
import subprocess
import sys
import tarfile
import tempfile
import time
from dataclasses import replace
from importlib.resources import files

import numpy as np

from coathertz.case import ContactCase
from coathertz.casefile import load_case
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)


def cases() -> dict[str, ContactCase]:
    keer = load_case(files("coathertz") / "data" / "keer_case_a.toml")
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(800e9, 0.3), 1.0, STEEL)
    thin = c0.with_thickness(0.01 * c0.a0s)
    layer = Material(200e9, 0.5)
    rb0 = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 1e-6)), 1.0)
    rigid_base = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 0.2 * rb0.a0c)), 1.0)
    return {"keer_a": keer, "thin": thin, "rigid_base": rigid_base}


def _method(variant: str):
    from coathertz.fem.method import FEMMethod

    m = FEMMethod()
    if variant in ("before", "newpath"):
        m.spec = replace(m.spec, edge_refine=1.0, L=40.0)  # the mesh before the edge band
    if variant == "before":
        m._reuse_factorisation = False  # refactorising active set, generic assembly
    return m


def run(case: ContactCase, repeat: int, variant: str = "default") -> dict:
    times, cpu = [], []
    for _ in range(repeat):
        m = _method(variant)
        t, c = time.perf_counter(), time.process_time()
        r = m.solve(case)
        times.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    st = r.meta["solver_stats"]
    return {
        "wall_s": float(np.median(times)),
        "cpu_s": float(np.median(cpu)),
        "factorisations": st.get("factorisations", st.get("setups")),
        "contact_iterations": r.meta["contact_iterations"],
        "remeshes": r.meta["remeshes"],
        "dofs": r.meta["dofs"],
        "delta": r.delta,
        "a": r.a,
        "p0": r.p0,
    }


class _Redirect(importlib.abc.MetaPathFinder):
    """Import ``coathertz.fem`` (and its modules) from another folder: the baseline's ``fem/``."""

    def __init__(self, fem_dir: str) -> None:
        self.fem_dir = fem_dir

    def find_spec(self, name, path, target=None):
        if name == "coathertz.fem":
            return importlib.machinery.PathFinder.find_spec(name, [os.path.dirname(self.fem_dir)])
        if name.startswith("coathertz.fem."):
            return importlib.machinery.PathFinder.find_spec(name, [self.fem_dir])
        return None


def _serve(fem_dir: str | None) -> None:
    """Worker: solve the cases named on stdin (one per line), one JSON line of results each."""
    if fem_dir:
        sys.meta_path.insert(0, _Redirect(fem_dir))
    all_cases = cases()
    for line in sys.stdin:
        out = run(all_cases[line.strip()], 1)
        print(json.dumps(out), flush=True)


def _baseline_fem(rev: str, tmp: str) -> str:
    """Extract ``fem/`` of the git revision ``rev`` into ``tmp``; returns the folder."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True, text=True,
                          check=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    tar = os.path.join(tmp, "fem.tar")
    subprocess.run(["git", "archive", "-o", tar, rev, "fem"], check=True, cwd=root)
    with tarfile.open(tar) as tf:
        tf.extractall(tmp, filter="data")
    return os.path.join(tmp, "fem")


def compare_with(rev: str, repeat: int) -> dict:
    """Time ``rev``'s ``fem/`` against the working tree's, solves alternating (module docstring)."""
    with tempfile.TemporaryDirectory() as tmp:
        fem_dir = _baseline_fem(rev, tmp)
        cmd = [sys.executable, os.path.abspath(__file__), "--serve"]
        workers = {
            who: subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            for who, args in (("baseline", [*cmd, fem_dir]), ("current", cmd))
        }

        def ask(who: str, name: str) -> dict:
            w = workers[who]
            w.stdin.write(name + "\n")
            w.stdin.flush()
            return json.loads(w.stdout.readline())

        out = {}
        try:
            for name in cases():
                res = {"baseline": [], "current": []}
                for who in workers:
                    ask(who, name)  # warm-up (imports, caches)
                for k in range(repeat):
                    for who in (("baseline", "current") if k % 2 == 0 else ("current", "baseline")):
                        res[who].append(ask(who, name))
                for who, rs in res.items():
                    v = dict(rs[-1])
                    for k in ("wall_s", "cpu_s"):
                        v[k] = float(np.median([r[k] for r in rs]))
                    out[f"{name}:{who}"] = v
        finally:
            for w in workers.values():
                w.stdin.close()
                w.wait()
    return out


def print_comparison(out: dict, rev: str) -> None:
    print(f"baseline = fem/ at {rev}, current = working tree; median wall of alternating solves")
    print(f"{'case':<11} {'wall: base':>10} {'now':>6} {'ratio':>6} {'cpu: base':>10} {'now':>6} {'ratio':>6}"
          f" {'fact.':>6} {'iter':>4} {'dofs':>6}  max rel diff (delta, a, p0)")
    for name in cases():
        b, c = out[f"{name}:baseline"], out[f"{name}:current"]
        rel = max(abs(c[k] / b[k] - 1) for k in ("delta", "a", "p0"))
        print(f"{name:<11} {b['wall_s']:10.3f} {c['wall_s']:6.3f} {b['wall_s'] / c['wall_s']:5.2f}x"
              f" {b['cpu_s']:10.3f} {c['cpu_s']:6.3f} {b['cpu_s'] / c['cpu_s']:5.2f}x"
              f" {b['factorisations']:>2}->{c['factorisations']:<2} {c['contact_iterations']:4d}"
              f" {c['dofs']:6d}  {rel:.1e}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--legacy", action="store_true", help="also time the refactorising path")
    ap.add_argument("--json", help="write the results to this file")
    ap.add_argument("--compare", help="earlier --json output: check delta, a, p0 to 1e-10")
    ap.add_argument("--baseline", metavar="REV", help="git revision whose fem/ to time against (alternating)")
    ap.add_argument("--serve", nargs="?", const="", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.serve is not None:
        _serve(args.serve or None)
        return
    print(f"# {platform.processor() or platform.machine()}, python {platform.python_version()},"
          f" load average {os.getloadavg()[0]:.1f}")
    if args.baseline:
        out = compare_with(args.baseline, args.repeat)
        print_comparison(out, args.baseline)
        print(f"# load average at the end {os.getloadavg()[0]:.1f}")
        if args.json:
            with open(args.json, "w") as fh:
                json.dump(out, fh, indent=1)
        return
    from coathertz.fem.method import FEMMethod

    can_legacy = "_reuse_factorisation" in inspect.getsource(FEMMethod)
    out = {}
    for name, case in cases().items():
        if args.legacy and can_legacy:
            out[name + "_before"] = run(case, args.repeat, "before")
            out[name + "_newpath"] = run(case, args.repeat, "newpath")
        out[name] = run(case, args.repeat)
    old = json.loads(open(args.compare).read()) if args.compare else {}
    print(f"{'case':<18} {'wall [s]':>9} {'fact.':>6} {'iter':>5} {'dofs':>7}  delta, a, p0")
    for name, v in out.items():
        line = (f"{name:<18} {v['wall_s']:9.3f} {v['factorisations']:6d} {v['contact_iterations']:5d}"
                f" {v['dofs']:7d}  {v['delta']:.12e} {v['a']:.12e} {v['p0']:.12e}")
        base = old.get(name.removesuffix("_before").removesuffix("_newpath")) if name.endswith(
            ("_before", "_newpath")) else None
        if base:
            rel = max(abs(v[k] / base[k] - 1) for k in ("delta", "a", "p0"))
            line += f"  max rel diff {rel:.1e}, time ratio {v['wall_s'] / base['wall_s']:.2f}"
        print(line)
    for name in cases():
        if name + "_before" in out:
            b, n, d = out[name + "_before"], out[name + "_newpath"], out[name]
            rel = max(abs(n[k] / b[k] - 1) for k in ("delta", "a", "p0"))
            print(f"{name}: same mesh, condensed vs refactorising: {b['wall_s'] / n['wall_s']:.2f}x faster,"
                  f" max rel diff {rel:.1e}; default mesh vs before: {b['wall_s'] / d['wall_s']:.2f}x faster"
                  " (same run)")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
