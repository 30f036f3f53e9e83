"""Benchmark of the DC-FFT solver (a script, not part of the test run).

Reports, in one run and in the same allocator state (the FFT pair is timed in the same process,
right before each solve, on a machine that may be shared):

1. for n = 128, 256, 512 and three cases (homogeneous; E = 3, H = 0.3; E = 1/3, H = 1): the
   time of one forward + inverse real FFT of the padded grid (2n x 2n, ``scipy.fft.rfft2`` and
   ``irfft2``, the solver's thread count) and of one solve with cached coefficients, timed in
   alternating rounds; the median of the per-round ratios ("FFT-pair equivalents";
   target <= 40 at 128 and <= 60 at 512); the CG iterations and the transform pairs the solver
   counted (coarse-grid pairs of the nested start count a quarter);
2. the time of the fig-3 sweep: 25 modulus ratios x 101 H in [0.01, 3] at 128 x 128, solved
   with ``FFTMethod.solve_many`` (one grid per modulus ratio, warm start along H);
   ``--ratios k`` takes every k-th modulus ratio (same per-case mix of H) and scales to 2525.

3. ``--family``: the transform pairs counted per solve (with the solves on grids given up by
   the re-gridding, ``meta["pair_equivalents_total"]``; older versions without that key: the
   final solve's count) over 30 cases of the paper's circular families (the 24 of
   ``tests/fft/test_radius.py``, homogeneous, and five more) at the ``--ns`` grids, with
   min / median / max per grid. Counts, not
   timings: independent of the machine's load.

``--save FILE`` writes delta, a, a_num, p0 of the benchmark cases (JSON; with ``--family`` also
of the family cases); ``--compare FILE`` prints their relative differences against a saved run
(before/after a solver change).

Usage: ``python tests/benchmarks/bench_fft.py [--ns 128 256 512] [--ratios 5] [--workers W]
[--family]``.
"""

from __future__ import annotations

import argparse
import json
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
CASES = (("homogeneous", 1.0, 1.0), ("E=3, H=0.3", 3.0, 0.3), ("E=1/3, H=1", 1 / 3, 1.0))


def family_cases() -> dict[str, tuple[ContactCase, str]]:
    """30 circular cases of the paper's families: name -> (case, interface)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from fft.conftest import STEEL, coated
    from fft.test_radius import A_EXACT, _case

    from coathertz.materials import RIGID, Body

    cases = {name: _case(name) for name in A_EXACT}
    cases["homogeneous"] = (ContactCase(Body.rigid_sphere(10e-3), Body.half_space(STEEL), 1.0),
                            "bonded")
    cases["el_E3_H0.3"] = (coated(3.0, 0.3), "bonded")
    cases["el_E1/3_H1"] = (coated(1 / 3, 1.0), "bonded")
    cases["el_E2_H0.05"] = (coated(2.0, 0.05), "bonded")
    cases["rg_nu0.5_H0.01"] = (coated(0.0, 0.01, nu_c=0.5, substrate=RIGID), "bonded")
    cases["fl_el_E4_H0.3"] = (coated(4.0, 0.3), "frictionless")
    return cases


def family_pairs(ns: list[int], kw: dict, saved: dict) -> None:
    """Print the transform pairs per solve over :func:`family_cases` (see module docstring)."""
    counts: dict[int, list[float]] = {n: [] for n in ns}
    for name, (case, interface) in family_cases().items():
        row = []
        for n in ns:
            r = FFTMethod(n=n, interface=interface, keep_fields=False, **kw).solve(case)
            m = r.meta
            pairs = m.get("pair_equivalents_total",
                          m["convolutions_batch"] + m.get("coarse_pair_equivalents_batch", 0))
            counts[n].append(pairs)
            row.append(f"n = {n}: {pairs:5.1f} ({m['iterations']:2d} it)")
            saved[f"family {n} {name}"] = {"delta": r.delta, "a": r.a, "a_num": m["a_num"],
                                            "p0": r.p0}
        print(f"{name:18s} " + "  ".join(row), flush=True)
    for n in ns:
        v = np.array(counts[n])
        print(f"family, n = {n}: transform pairs per solve min {v.min():.1f}, "
              f"median {np.median(v):.1f}, max {v.max():.1f} over {v.size} cases")


def fig3_ratios() -> list[float]:
    """NOTES.md: 1/E = 4 - (i-1)/4, i = 1..12 and E = 1 + i/4, i = 0..12."""
    return [1 / (4 - (i - 1) / 4) for i in range(1, 13)] + [1 + i / 4 for i in range(13)]


def case_for(E: float, H: float) -> ContactCase:
    co = Material(E * ES.E, NU)  # same nu: Ec*/Es* = Ec/Es
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, co, 1.0, ES)
    return c0.with_thickness(H * c0.a0s)


def time_pair(n: int, workers: int, repeat: int, rounds: int = 5) -> float:
    """Median over rounds of the mean time of rfft2 + irfft2 on the 2n x 2n padded grid."""
    a = np.random.default_rng(0).random((n, n))
    s = (2 * n, 2 * n)
    fft.irfft2(fft.rfft2(a, s=s, workers=workers), s=s, workers=workers)
    times = []
    for _ in range(rounds):
        t = time.perf_counter()
        for _ in range(repeat):
            fft.irfft2(fft.rfft2(a, s=s, workers=workers), s=s, workers=workers)
        times.append((time.perf_counter() - t) / repeat)
    return float(np.median(times))


def time_solve(case: ContactCase, m: FFTMethod, n: int, workers: int, repeat: int):
    """Interleaved rounds of (FFT pairs, one solve) with cached coefficients.

    Returns (median pair time, median solve time, median of the per-round ratios, result):
    on a shared machine the per-round ratio is steadier than either time.
    """
    r = m.solve(case)  # builds and caches the coefficients
    pairs, solves, ratios = [], [], []
    for _ in range(repeat):
        pair = time_pair(n, workers, repeat=max(5, 2000 // n), rounds=1)
        t = time.perf_counter()
        r = m.solve(case)
        dt = time.perf_counter() - t
        pairs.append(pair)
        solves.append(dt)
        ratios.append(dt / pair)
    return float(np.median(pairs)), float(np.median(solves)), float(np.median(ratios)), r


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ns", type=int, nargs="*", default=[128, 256, 512])
    ap.add_argument("--workers", type=int, default=None,
                    help="FFT threads (default: the method's default)")
    ap.add_argument("--ratios", type=int, default=5,
                    help="fig-3 sweep: every k-th modulus ratio (1: all 2525 cases; 0: skip)")
    ap.add_argument("--family", action="store_true",
                    help="transform pairs per solve over 30 family cases at the --ns grids")
    ap.add_argument("--save", default=None)
    ap.add_argument("--compare", default=None)
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.1f} (timings as ratios: the machine may be shared)")
    kw = {} if args.workers is None else {"workers": args.workers}
    saved = {}
    for n in args.ns:
        m = FFTMethod(n=n, keep_fields=False, **kw)
        workers = m.workers if m.workers is not None else -1
        if hasattr(m, "fft_workers"):
            workers = m.fft_workers()
        repeat = {128: 9, 256: 5}.get(n, 3)
        for label, E, H in CASES:
            case = case_for(E, H)
            pair, t, ratio, r = time_solve(case, m, n, workers, repeat)
            conv = r.meta.get("pair_equivalents_total", r.meta["convolutions_batch"]
                              + r.meta.get("coarse_pair_equivalents_batch", 0))
            print(f"n = {n:4d} {label:12s}: pair {pair * 1e3:7.3f} ms, solve {t * 1e3:8.1f} ms, "
                  f"ratio {ratio:6.1f} pairs; {r.meta['iterations']:3d} iterations, "
                  f"{conv:5.1f} transform pairs counted (workers {workers})")
            saved[f"{n} {label}"] = {"delta": r.delta, "a": r.a, "a_num": r.meta["a_num"],
                                     "p0": r.p0}
    if args.family:
        family_pairs(args.ns, kw, saved)
    if args.save:
        with open(args.save, "w") as f:
            json.dump(saved, f, indent=1)
    if args.compare:
        with open(args.compare) as f:
            old = json.load(f)
        for k, v in saved.items():
            if k in old:
                d = {q: v[q] / old[k][q] - 1 for q in v}
                print(f"vs saved {k:20s}: " + ", ".join(f"{q} {x:+.2e}" for q, x in d.items()))
    if args.ratios > 0:
        ratios = fig3_ratios()[:: args.ratios]
        Hs = np.linspace(0.01, 3.0, 101)
        cases = [case_for(E, H) for E in ratios for H in Hs]
        m = FFTMethod(n=128, keep_fields=False, **kw)
        fm._CACHE.clear()
        pair = time_pair(128, 1, repeat=30)
        t, c = time.perf_counter(), time.process_time()
        res = m.solve_many(cases)
        dt, dc = time.perf_counter() - t, time.process_time() - c
        its = np.array([r.meta["iterations"] for r in res])
        print(f"fig-3 sweep: {len(cases)} cases ({len(ratios)} of 25 modulus ratios) in {dt:.1f} s "
              f"({dt / len(cases) * 1e3:.1f} ms/case = {dt / len(cases) / pair:.0f} pairs of "
              f"{pair * 1e3:.3f} ms, mean {its.mean():.1f} iterations); "
              f"scaled to 2525 cases: {dt * 2525 / len(cases):.0f} s; CPU time of this process "
              f"{dc:.1f} s (scaled {dc * 2525 / len(cases):.0f} s: less sensitive to other load)")


if __name__ == "__main__":
    main()
