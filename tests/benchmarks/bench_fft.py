"""Benchmark of the DC-FFT solver (a script, not part of the test run).

Reports, in one run:

1. the time of one forward + inverse real FFT of the padded grid (2n x 2n, scipy.fft);
2. the solve time at the paper's n = 128 (rigid sphere on a coated half-space, coefficients
   cached, and including their construction) and its ratio to (1) (goal: at most 40);
3. the time of the fig-3 sweep: 25 modulus ratios x 101 H in [0.01, 3] at 128 x 128, solved
   with ``FFTMethod.solve_many`` (one grid per modulus ratio, warm start along H)
   (goal: under 2 minutes on 2 cores).

Usage: ``python tests/benchmarks/bench_fft.py [--n 128] [--quick]`` (``--quick``: 5 of the 25
modulus ratios, time scaled to 25).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np
from scipy import fft

from coathertz.case import ContactCase
from coathertz.fft import method as fm
from coathertz.fft.method import FFTMethod
from coathertz.materials import Material

NU = 0.3
ES = Material(200e9, NU)


def fig3_ratios() -> list[float]:
    """NOTES.md: 1/E = 4 - (i-1)/4, i = 1..12 and E = 1 + i/4, i = 0..12."""
    return [1 / (4 - (i - 1) / 4) for i in range(1, 13)] + [1 + i / 4 for i in range(13)]


def case_for(E: float, H: float) -> ContactCase:
    co = Material(E * ES.E, NU)  # same nu: Ec*/Es* = Ec/Es
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, co, 1.0, ES)
    return c0.with_thickness(H * c0.a0s)


def time_pair(n: int, workers: int, repeat: int = 100) -> float:
    """Median over 5 rounds of the mean time of rfft2 + irfft2 on the 2n x 2n padded grid."""
    a = np.random.default_rng(0).random((n, n))
    s = (2 * n, 2 * n)
    fft.irfft2(fft.rfft2(a, s=s, workers=workers), s=s, workers=workers)
    rounds = []
    for _ in range(5):
        t = time.perf_counter()
        for _ in range(repeat):
            fft.irfft2(fft.rfft2(a, s=s, workers=workers), s=s, workers=workers)
        rounds.append((time.perf_counter() - t) / repeat)
    return float(np.median(rounds))


def time_solve(case: ContactCase, m: FFTMethod, repeat: int = 7) -> tuple[float, float, int]:
    """(first solve incl. coefficients, median of cached solves, iterations)."""
    fm._CACHE.clear()
    t = time.perf_counter()
    r = m.solve(case)
    cold = time.perf_counter() - t
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        r = m.solve(case)
        times.append(time.perf_counter() - t)
    return cold, float(np.median(times)), r.meta["iterations"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=128)
    ap.add_argument("--workers", type=int, default=-1)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    n = args.n
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; n = {n}")
    m = FFTMethod(n=n, workers=args.workers, keep_fields=False)
    for label, case in (("homogeneous", case_for(1.0, 1.0)), ("E=3, H=0.3", case_for(3.0, 0.3)),
                        ("E=1/3, H=1", case_for(1 / 3, 1.0))):
        pair = time_pair(n, args.workers)  # re-measured next to each solve (shared machine)
        print(f"forward + inverse rfft2 of {2 * n} x {2 * n}: {pair * 1e3:.3f} ms")
        cold, warm, its = time_solve(case, m)
        print(f"solve {label:12s}: {warm * 1e3:7.1f} ms ({warm / pair:5.1f} FFT pairs, goal 40), "
              f"{its} iterations; with coefficient construction {cold * 1e3:.1f} ms "
              f"({cold / pair:.1f} pairs)")
    ratios = fig3_ratios()
    if args.quick:
        ratios = ratios[::6]
    Hs = np.linspace(0.01, 3.0, 101)
    cases = [case_for(E, H) for E in ratios for H in Hs]
    fm._CACHE.clear()
    t = time.perf_counter()
    res = m.solve_many(cases)
    dt = time.perf_counter() - t
    scale = 25 / len(ratios)
    its = np.array([r.meta["iterations"] for r in res])
    print(f"fig-3 sweep: {len(cases)} cases in {dt:.1f} s ({dt / len(cases) * 1e3:.1f} ms/case, "
          f"mean {its.mean():.1f} iterations); 2525 cases: {dt * scale:.0f} s (goal < 120 s)")


if __name__ == "__main__":
    main()
