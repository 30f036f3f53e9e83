"""Benchmark of the exact axisymmetric method (a script, not part of the test run).

Reports, in one run:

1. the median time per case (keep_fields off and on) over a sample of fig-3 cases, tables warm
   (goal: <= 20 ms per case);
2. the wall time of the full fig-3 grid, 25 modulus ratios x 101 H in [0.01, 3] (2525 cases,
   ``coathertz.verification``), on ``--workers`` processes (default 2; goal: <= 30 s);
3. the accuracy of the default settings against a reference with ~2x the modes and denser
   quadrature (n_modes = 2 x default + 16, 20 nodes per panel, decay 30) on 25 E x 7 H
   (goal: <= 1e-6 in delta, a, p0);
4. thin layers: the B4C example (example:b4c_on_steel) with h from H = 1e-5 (1 nm is
   H ~ 2.4e-5) to 10: warm time per case, traced peak memory of a cold solve (caches cleared) and
   the difference of delta, a, p0 to a solve with twice the modes (goal: <= 50 ms, <= 200 MB).

BLAS is pinned to one thread per process (the Galerkin systems are at most ~100 x 100).

Usage: ``python tests/benchmarks/bench_axisym.py [--workers 2] [--quick] [--thin]`` (``--quick``:
5 of the 25 modulus ratios, grid time scaled to 25; ``--thin``: item 4 only).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import platform
import time
import tracemalloc
import warnings
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from coathertz.axisym import AxisymMethod
from coathertz.axisym import solver as axisym_solver
from coathertz.casefile import load_case
from coathertz.verification import elastic_case, fig3_ratios, h_grid

QS = ("delta", "a", "p0")


def _solve_row(E: float) -> tuple[float, int, float]:
    """All 101 H of one modulus ratio (one worker task); returns (E, cases, seconds)."""
    m = AxisymMethod(keep_fields=False)
    t = time.perf_counter()
    cases = [elastic_case(E, float(H)) for H in h_grid(0.01, 3.0, 101)]
    m.solve_many(cases)
    return E, len(cases), time.perf_counter() - t


def per_case_times(keep_fields: bool, n: int = 60) -> np.ndarray:
    rng = np.random.default_rng(1)
    Es = rng.choice(fig3_ratios(), n)
    Hs = rng.choice(h_grid(0.01, 3.0, 101), n)
    cases = [elastic_case(float(E), float(H)) for E, H in zip(Es, Hs, strict=True)]
    m = AxisymMethod(keep_fields=keep_fields)
    m.solve_many(cases)  # warm the Bessel tables
    out = []
    for c in cases:
        t = time.perf_counter()
        m.solve(c)
        out.append(time.perf_counter() - t)
    return np.array(out)


def accuracy(ratios: list[float]) -> dict[str, float]:
    worst = dict.fromkeys(QS, 0.0)
    m = AxisymMethod(keep_fields=False)
    for E in ratios:
        for H in (0.01, 0.02, 0.05, 0.1, 0.3, 1.0, 3.0):
            c = elastic_case(E, H)
            r = m.solve(c)
            ref = AxisymMethod(n_modes=2 * r.meta["n_modes"] + 16, order=20, decay=30.0,
                               keep_fields=False).solve(c)
            for q in QS:
                worst[q] = max(worst[q], abs(getattr(r, q) / getattr(ref, q) - 1.0))
    return worst


def thin_layers() -> None:
    base = load_case("example:b4c_on_steel")
    a0 = base.a0s
    for H in (1e-5, 1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0):
        case = base.with_thickness(H * a0)
        m = AxisymMethod(keep_fields=False)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            axisym_solver._TABLES.clear()
            axisym_solver._TAIL.clear()
            tracemalloc.start()
            r = m.solve(case)
            peak = tracemalloc.get_traced_memory()[1] / 2**20
            tracemalloc.stop()
            t = []
            for _ in range(5):
                t0 = time.perf_counter()
                m.solve(case)
                t.append(time.perf_counter() - t0)
            ref = AxisymMethod(n_modes=2 * r.meta["n_modes"], keep_fields=False).solve(case)
        err = ", ".join(f"{q} {abs(getattr(r, q) / getattr(ref, q) - 1.0):.1e}" for q in QS)
        print(f"  H = {H:7.1e} (h = {H * a0:.3g} m): N = {r.meta['n_modes']:3d}, "
              f"{r.meta['n_xi']:6d} xi nodes, warm {np.median(t) * 1e3:6.1f} ms, "
              f"cold peak {peak:6.1f} MiB; vs 2N: {err}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--thin", action="store_true", help="only the thin-layer table (item 4)")
    args = ap.parse_args()
    if args.thin:
        print("thin layers (B4C example, h = H a0s):")
        thin_layers()
        return
    ratios = fig3_ratios()
    if args.quick:
        ratios = ratios[::6]
    print(f"machine: {platform.machine()} {platform.processor()}, {os.cpu_count()} CPUs visible "
          f"(shared with other jobs: timings are noisy), python {platform.python_version()}")

    for kf in (False, True):
        t = per_case_times(kf)
        print(f"per case (keep_fields={kf}): median {np.median(t) * 1e3:.1f} ms, "
              f"90th percentile {np.percentile(t, 90) * 1e3:.1f} ms, max {np.max(t) * 1e3:.1f} ms "
              f"over {t.size} random fig-3 cases")

    t0 = time.perf_counter()
    with ProcessPoolExecutor(max_workers=args.workers) as ex:
        rows = list(ex.map(_solve_row, ratios))
    wall = time.perf_counter() - t0
    n = sum(r[1] for r in rows)
    cpu = sum(r[2] for r in rows)
    scale = len(fig3_ratios()) / len(ratios)
    print(f"fig-3 grid: {n} cases in {wall:.1f} s wall on {args.workers} processes "
          f"({cpu / n * 1e3:.1f} ms per case of worker time)"
          + (f"; scaled to 2525 cases: {wall * scale:.1f} s" if args.quick else ""))
    slowest = max(rows, key=lambda r: r[2])
    print(f"  slowest modulus ratio: E = {slowest[0]:.4g}, {slowest[2]:.2f} s for {slowest[1]} cases")

    worst = accuracy(ratios if args.quick else ratios[::3])
    print("accuracy of the defaults (max relative difference to the refined reference): "
          + ", ".join(f"{q} {v:.1e}" for q, v in worst.items()))
    print("thin layers (B4C example, h = H a0s):")
    thin_layers()


if __name__ == "__main__":
    main()
