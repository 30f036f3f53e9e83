"""Benchmark of the exact axisymmetric stresses (a script, not part of the test run).

Reports, on one core (BLAS pinned to one thread), CPU time (``time.process_time``, which the
load of a shared machine inflates less than wall time) and peak traced Python memory of:

1. the summary field of ``coathertz stresses --method axisym`` (244 radii clustered at the edge,
   the default depths) for the examples ``homogeneous_steel``, ``b4c_on_steel``,
   ``fig3_soft_coating``, ``rigid_substrate`` and ``dlc_crn_cr_on_steel`` (a three-layer stack);
2. the same field revolved onto a 128 x 128 lattice (``--png``/``--vtu``; ~2100 distinct radii);
3. for comparison, the FFT field of the same case on 128^2 at the same depths and the FE's
   recovered field sampled on the same points (solve included).

Usage: ``python tests/benchmarks/bench_axisym_stresses.py [--quick]`` (``--quick``: items 1 and 3
on b4c_on_steel only).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import platform
import time
import tracemalloc

from coathertz.casefile import load_example
from coathertz.stress_methods import StressOptions, axisym_stresses, fem_stresses, fft_stresses

CASES = ("homogeneous_steel", "b4c_on_steel", "fig3_soft_coating", "rigid_substrate",
         "dlc_crn_cr_on_steel")


def measure(fn, *args) -> tuple[float, float, object]:
    """CPU seconds, peak traced memory [MB] and the result of ``fn(*args)``."""
    tracemalloc.start()
    t0 = time.process_time()
    out = fn(*args)
    cpu = time.process_time() - t0
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return cpu, peak / 1e6, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print(f"python {platform.python_version()}, {platform.machine()}, one core")
    cases = ("b4c_on_steel",) if args.quick else CASES
    print(f"{'case':22s} {'what':26s} {'CPU [s]':>8s} {'peak [MB]':>10s}  points")
    for name in cases:
        case = load_example(name)
        cpu, mem, res = measure(axisym_stresses, case, StressOptions())
        print(f"{name:22s} {'axisym summary field':26s} {cpu:8.2f} {mem:10.1f}  "
              f"{res.x.size} r x {res.z.size} z, {res.meta['n_xi']} xi nodes")
        if not args.quick:
            cpu, mem, res = measure(axisym_stresses, case, StressOptions(grid=128, lattice=True))
            print(f"{name:22s} {'axisym + 128^2 lattice':26s} {cpu:8.2f} {mem:10.1f}")
        if name in ("homogeneous_steel", "b4c_on_steel", "fig3_soft_coating", "rigid_substrate"):
            depths = tuple(res.z)
            cpu, mem, _ = measure(fft_stresses, case, StressOptions(grid=128, depths=depths))
            print(f"{name:22s} {'fft 128^2 (solve + field)':26s} {cpu:8.2f} {mem:10.1f}")
            cpu, mem, _ = measure(fem_stresses, case, StressOptions(depths=depths))
            print(f"{name:22s} {'fem default (solve + field)':26s} {cpu:8.2f} {mem:10.1f}")


if __name__ == "__main__":
    main()
