"""Benchmark of the refitted closed form (a script, not part of the test run).

Reports the vectorised evaluation rate of the refit rule (goal: >= 1e6 cases/s, a case being
all three of a, delta, p0) for random inputs over the validated ranges, next to the paper's
rule (eq 19 + Appendix A through :func:`coathertz.closedform.extended.predict_bar`) on the same inputs,
for the elastic substrate, the rigid substrate, the elastic indenter and the elliptical
correction. Timings are the
best of ``--repeat`` runs; on a shared machine quote the ratios. ``RefitRule.bars`` and
``ellipse_bars`` evaluate large inputs in one block per core (threads, single-threaded BLAS), so
the rates use every core of the machine; the one-alpha rows and the paper's rule run on one.

Usage: ``python tests/benchmarks/bench_refit.py [--n 1000000] [--repeat 5]``
"""

from __future__ import annotations

import argparse
import os
import platform
import time
import warnings

import numpy as np

from coathertz.closedform.alpha import PAPER_RULE
from coathertz.closedform.extended import predict_bar
from coathertz.closedform.refit import load


def best(f, repeat: int) -> float:
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    n = args.n
    rng = np.random.default_rng(0)
    E = 10 ** rng.uniform(-1, 1, n)
    H = 10 ** rng.uniform(-3, 1, n)
    nu_c = rng.uniform(0, 0.5, n)
    nu_s = rng.uniform(0, 0.5, n)
    rho = 10 ** rng.uniform(0, 1, n)
    gamma = rng.uniform(0.02, 1.0, n)
    rule = load()
    el, rg = rule.model("elastic"), rule.model("rigid")
    rule.bars("elastic", E[:10], H[:10], nu_c[:10], nu_s[:10])  # build the cached evaluation tables
    rule.ellipse_bars(E[:10], H[:10], rho[:10])  # and the ellipse correction
    rule.indenter_bars(E[:10], H[:10], gamma[:10])  # and the elastic indenter
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores (shared, load "
          f"{os.getloadavg()[0]:.2f}), numpy {np.__version__}; n = {n}, best of {args.repeat}")
    rows = []
    t = best(lambda: el.bars(E, H, nu_c, nu_s), args.repeat)
    rows.append(("refit one alpha, elastic (a, delta, p)", t))
    t = best(lambda: rule.bars("elastic", E, H, nu_c, nu_s), args.repeat)
    rows.append((f"refit {rule.best_form('elastic')}, elastic (a, delta, p)", t))
    t = best(lambda: rg.bars(None, H, nu_c), args.repeat)
    rows.append(("refit one alpha, rigid (a, delta, p)", t))
    t = best(lambda: rule.bars("rigid", None, H, nu_c), args.repeat)
    rows.append((f"refit {rule.best_form('rigid')}, rigid (a, delta, p)", t))

    t = best(lambda: rule.indenter_bars(E, H, gamma, nu_c, nu_s), args.repeat)
    rows.append(("refit, elastic indenter (a, delta, p)", t))
    indenter_row = len(rows) - 1

    t = best(lambda: rule.ellipse_bars(E, H, rho, nu_c, nu_s), args.repeat)
    rows.append(("refit, ellipse (r_a, r_b, delta, p)", t))

    def paper():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return [predict_bar(q, E, H, nu_c, nu_s, rule=PAPER_RULE, warn=False)
                    for q in ("a", "delta", "p")]

    t = best(paper, args.repeat)
    rows.append(("paper's rule, elastic (a, delta, p)", t))
    ref = rows[-1][1]
    for name, t in rows:
        print(f"{name:42s} {t:7.3f} s  {n / t:12.3e} cases/s  ({t / ref:.2f} x the paper's rule)")
    for label, k in (("rigid indenter, elastic substrate", 1), ("elastic indenter", indenter_row)):
        ok = n / rows[k][1] >= 1e6
        print(f"goal >= 1e6 cases/s ({label}, best form, all three quantities): {'met' if ok else 'NOT met'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
