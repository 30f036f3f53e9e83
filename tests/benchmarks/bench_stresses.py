"""Benchmark of the FFT stress field (a script, not part of the test run).

Reports, in one run, on one core (BLAS and scipy.fft pinned to one thread):

1. the full tensor (6 components) under pressure and sliding traction on 128^2 at 64 depths
   (goal: <= 1 s), with the peak traced Python memory;
2. 256^2 at 128 depths in batches of depths (goal: peak under 2 GB);
3. the ratio of the two wall times, the measure that survives a noisy shared machine.

Usage: ``python tests/benchmarks/bench_stresses.py [--quick]`` (``--quick``: part 1 only).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import platform
import time
import tracemalloc

import numpy as np

from coathertz.fft.frf import Layer
from coathertz.fft.grid import Grid
from coathertz.fft.stresses import CoatedStressFRF, stresses_surface
from coathertz.materials import Material


def run(n: int, n_depths: int, batch: int) -> tuple[float, float, float]:
    """Wall time [s], peak traced memory [MB] and result size [MB] of the full tensor."""
    g = Grid(n, n, 4.0e-4 / n, 4.0e-4 / n)  # a = 0.1 mm, domain 4a
    X, Y = np.meshgrid(g.x, g.y)
    p = 1e9 * np.sqrt(np.clip(1 - (X**2 + Y**2) / 1e-8, 0, None))
    frf = CoatedStressFRF(Layer(Material(E=300e9, nu=0.25), Material(E=200e9, nu=0.3)), 2e-5)
    depths = np.geomspace(1e-7, 3e-4, n_depths)
    out = np.empty((n_depths, 6, n, n))
    tracemalloc.start()
    t0 = time.perf_counter()
    for i in range(0, n_depths, batch):
        out[i:i + batch] = stresses_surface(g, depths[i:i + batch], frf, p=p, qx=0.3 * p)
    wall = time.perf_counter() - t0
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return wall, peak / 1e6, out.nbytes / 1e6


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, python {platform.python_version()}")
    w1, m1, r1 = run(128, 64, 64)
    print(f"128^2 x 64 depths, coated, pressure + sliding: {w1:.2f} s (goal <= 1 s), "
          f"peak traced {m1:.0f} MB (result {r1:.0f} MB)")
    if args.quick:
        return
    w2, m2, r2 = run(256, 128, 16)
    print(f"256^2 x 128 depths (batches of 16): {w2:.2f} s, peak traced {m2:.0f} MB "
          f"(result {r2:.0f} MB; goal < 2000 MB)")
    print(f"ratio 256^2x128 / 128^2x64: {w2 / w1:.1f} (8x the points)")


if __name__ == "__main__":
    main()
