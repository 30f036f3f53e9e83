"""Benchmark of the refitted closed form (a script, not part of the test run).

Reports the vectorised evaluation rate of the refit rule (goal: >= 1e6 cases/s, a case being
all three of a, delta, p0) for random inputs over the validated ranges, next to the paper's
rule (eq 19 + Appendix A through :func:`coathertz.closedform.extended.predict_bar`) on the same inputs,
for the elastic substrate, the rigid substrate, the elastic indenter and the elliptical
correction. Timings are the
best of ``--repeat`` runs; on a shared machine quote the ratios. ``RefitRule.bars`` and
``ellipse_bars`` evaluate large inputs in one block per core (threads, single-threaded BLAS), so
the rates use every core of the machine; the one-alpha rows and the paper's rule run on one.
Besides the wall-clock rate each row gives the CPU time per case (both threads together), which
a busy machine disturbs less.

``--reference`` times, in the same run, the evaluation as it was before issue 21's work (a copy
of the old shared surface evaluation below, which allocated its tables, ``W`` and the product
per chunk of 1024 points; no pieces inside a block; the elastic indenter through the rigid
form's bars and ``ln``) and prints the ratios. The values agree to 1.3e-15 relative (measured
on 1e5 points over and beyond the box, gamma = 1 and the box's edges included).

Measured 2026-11-27 on this project's 2-core AMD EPYC (2.45 GHz, AVX2; numpy 2.4 with OpenBLAS
0.3.31), while 4 other jobs ran on the same 2 cores (load 5-7): the wall-clock rates were then
2-6 times below the idle ones, so the CPU time per case and the ratios to the old evaluation in
the same run are the figures to quote. ``--n 1000000 --repeat 3 --reference``: CPU time per case
before / after: elastic indenter x 1.25 (3.06 us after), corrected rigid indenter on an elastic
substrate x 1.01 (1.78 us), on a rigid substrate x 1.16 (1.17 us), ellipse x 0.98 (2.42 us), one
alpha x 0.95 (elastic) and x 1.60 (rigid). One core, pieces of 16384 cases, best of 30 runs
interleaved with the old code (a copy of the old package in the same process): elastic indenter
3.86 -> 2.98 us (x 1.30), corrected elastic substrate 2.42 -> 1.77 us (x 1.37), corrected rigid
substrate 1.21 -> 1.07 us (x 1.13). The idle rates before (issue 21's note): elastic indenter
4.9e5/s, corrected elastic substrate 1.07e6/s, corrected rigid substrate 1.49e6/s, ellipse
8.2e5/s; the idle rates after were not measured (the machine was never idle).

Where the elastic indenter's time goes (one core, 16384 cases, busy machine, 3.9 us a case):
the two tensor surfaces' matrix products (the correction D_q, 64 x 196 coefficients, and the
base form's global surfaces, 76 x 143) 1.72 us at 27 GFLOP/s; building their ``W`` tensors
0.62 us; their last contraction 0.32 us; the stiff-coating patch and the ring of p0 (on 22 % and
5 % of the cases) 0.18 us; everything else (variables, eq 17, exp) about 1 us. The products are
the floor: 3 x (4116 + 3575) coefficients are 46,000 flops a case, 1.4 us a case and core at the
32-34 GFLOP/s one core reaches on these shapes (39 at its peak), so 2 cores cannot pass about
1.4e6 cases/s with everything else free; 1e6/s needs everything else below 0.6 us a case and
core, which element-wise numpy does not reach (a compiled kernel fusing tables, W and the
product, or a correction with fewer coefficients, would).

Usage: ``python tests/benchmarks/bench_refit.py [--n 1000000] [--repeat 5] [--reference]``
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import time
import warnings

import numpy as np

from coathertz.closedform.alpha import PAPER_RULE
from coathertz.closedform.extended import predict_bar
from coathertz.closedform.refit import corrected as CF
from coathertz.closedform.refit import indenter as IND
from coathertz.closedform.refit import load
from coathertz.closedform.refit import rule as R
from coathertz.closedform.refit import surface as SF
from coathertz.closedform.refit.surface import chebyshev_table


def best(f, repeat: int) -> tuple[float, float]:
    """Best wall-clock and best CPU time [s] of ``repeat`` calls."""
    t, c = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        f()
        t.append(time.perf_counter() - t0)
        c.append(time.process_time() - c0)
    return min(t), min(c)


def _reference_evaluate_shared(surfaces, X):
    """The shared surface evaluation before issue 21 (fresh tables, ``W`` and product per chunk)."""
    first = surfaces[0]
    X = np.asarray(X, dtype=float)
    if any((s.variables, s.lo, s.hi) != (first.variables, first.lo, first.hi) for s in surfaces[1:]):
        return [_reference_evaluate_shared([s], X)[0] for s in surfaces]
    d, n = X.shape
    rest = tuple(sorted({r for s in surfaces for r in s._layout[0]}))
    where = {r: k for k, r in enumerate(rest)}
    n0 = max(s.degrees[0] for s in surfaces) + 1
    big = np.zeros((len(surfaces) * n0, len(rest)))
    for m, s in enumerate(surfaces):
        rs, C = s._layout
        big[m * n0 : m * n0 + C.shape[0], [where[r] for r in rs]] = C
    degs = tuple(max(s.degrees[v] for s in surfaces) for v in range(d))
    pick = None
    if d > 1:
        flat = np.ravel_multi_index(np.array(rest).T, tuple(k + 1 for k in degs[1:]))
        if not np.array_equal(flat, np.arange(np.prod([k + 1 for k in degs[1:]]))):
            pick = flat
    outs = [np.empty(n) for _ in surfaces]
    for t0 in range(0, n, 32768):
        S_all = first.scaled(X[:, t0 : t0 + 32768])
        tabs_all = [chebyshev_table(S_all[v], degs[v]) for v in range(d)]
        for c0 in range(0, S_all.shape[1], 1024):
            tabs = [t[:, c0 : c0 + 1024] for t in tabs_all]
            T0, m = tabs[0], tabs[0].shape[1]
            W = tabs[1] if len(tabs) > 1 else np.ones((1, m))
            for T in tabs[2:]:
                W = (W[:, None, :] * T[None, :, :]).reshape(-1, m)
            if pick is not None:
                W = W[pick]
            B = (big @ W).reshape(len(outs), n0, m)
            for k, out in enumerate(outs):
                out[t0 + c0 : t0 + c0 + m] = np.einsum("in,in->n", B[k], T0)
    return outs


@contextlib.contextmanager
def reference_evaluation():
    """The evaluation before issue 21 (see the module docstring), for the ratios."""
    mods = [SF, CF, IND, R]
    saved = [m.evaluate_shared for m in mods], R.PIECE
    for m in mods:
        m.evaluate_shared = _reference_evaluate_shared
    R.PIECE = 10**12
    try:
        yield
    finally:
        for m, f in zip(mods, saved[0], strict=True):
            m.evaluate_shared = f
        R.PIECE = saved[1]


def reference_indenter_bars(rule, E, H, gamma, nu_c, nu_s):
    """The elastic indenter before issue 21: through the rigid form's bars and ``ln``."""
    form, rigid = rule._indenter, rule._bars_function("elastic")

    def bars(E, H, gamma, nu_c, nu_s):
        return {q: np.exp(v) for q, v in form.log_bars(rigid, E, H, nu_c, nu_s, gamma).items()}

    return R.in_blocks(bars, E, H, gamma, nu_c, nu_s)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--reference", action="store_true",
                    help="also time the evaluation before issue 21 and print the ratios")
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
    cases = [
        ("refit one alpha, elastic (a, delta, p)", lambda: el.bars(E, H, nu_c, nu_s), None),
        (f"refit {rule.best_form('elastic')}, elastic (a, delta, p)",
         lambda: rule.bars("elastic", E, H, nu_c, nu_s), None),
        ("refit one alpha, rigid (a, delta, p)", lambda: rg.bars(None, H, nu_c), None),
        (f"refit {rule.best_form('rigid')}, rigid (a, delta, p)",
         lambda: rule.bars("rigid", None, H, nu_c), None),
        ("refit, elastic indenter (a, delta, p)", lambda: rule.indenter_bars(E, H, gamma, nu_c, nu_s),
         lambda: reference_indenter_bars(rule, E, H, gamma, nu_c, nu_s)),
        ("refit, ellipse (r_a, r_b, delta, p)", lambda: rule.ellipse_bars(E, H, rho, nu_c, nu_s), None),
    ]
    indenter_row = 4
    rows, ref_rows = [], []
    for name, f, f_ref in cases:
        rows.append((name, *best(f, args.repeat)))
        if args.reference:
            with reference_evaluation():
                ref_rows.append(best(f_ref or f, args.repeat))

    def paper():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return [predict_bar(q, E, H, nu_c, nu_s, rule=PAPER_RULE, warn=False)
                    for q in ("a", "delta", "p")]

    rows.append(("paper's rule, elastic (a, delta, p)", *best(paper, args.repeat)))
    ref = rows[-1][1]
    for k, (name, t, c) in enumerate(rows):
        line = (f"{name:42s} {t:7.3f} s  {n / t:12.3e} cases/s  cpu {c / n * 1e6:6.3f} us/case  "
                f"({t / ref:.2f} x the paper's rule)")
        if k < len(ref_rows):
            line += f"  before: {n / ref_rows[k][0]:.3e} cases/s, cpu x {ref_rows[k][1] / c:.2f}"
        print(line)
    for label, k in (("rigid indenter, elastic substrate", 1), ("elastic indenter", indenter_row)):
        ok = n / rows[k][1] >= 1e6
        print(f"goal >= 1e6 cases/s ({label}, best form, all three quantities): {'met' if ok else 'NOT met'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
