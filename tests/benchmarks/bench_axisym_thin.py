"""Benchmark of the exact axisymmetric method at any thickness (a script, not part of the test run).

Reports, in one run, on one core (BLAS pinned to one thread), CPU time (``time.process_time``,
less sensitive than wall time to other jobs on a shared machine):

1. thin to thick single coatings (example:b4c_on_steel, h = H a0s, H from 1e-5 to 10, and its
   1 nm coating): median CPU time per case (warm caches; goal <= 50 ms), traced peak memory of a
   cold solve (caches cleared; goal <= 200 MB), the regime (Legendre modes, edge functions), and
   the difference of delta, a, p0 to a refined solve (edge functions: the next level of the
   nested sequence, ratio 1.25^(1/2) with the same scale range, 12 nodes per panel;
   Legendre-only: twice the modes, 12 nodes per panel; goal <= 1e-8);
2. stacks of 1 to 4 layers at H >= 0.01 (thinnest layer; random moduli 1/10..10 of steel, random
   thicknesses): median CPU time per case (goal <= 20 ms), and 3-layer stacks with every layer
   at H = 1e-5 .. 1e-3 (goal <= 50 ms); for both the cold traced peak of three cases and the
   largest difference to the refined solves (goal <= 1e-8).

Usage: ``python tests/benchmarks/bench_axisym_thin.py [--quick]`` (``--quick``: fewer stack cases).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import math
import platform
import time
import tracemalloc
import warnings

import numpy as np

from coathertz.axisym import AxisymMethod
from coathertz.axisym import solver as axisym_solver
from coathertz.case import ContactCase
from coathertz.casefile import load_case
from coathertz.materials import Body, Layer, Material

QS = ("delta", "a", "p0")
STEEL = Material(200e9, 0.3)


def cpu_times(m: AxisymMethod, case: ContactCase, n: int = 7) -> np.ndarray:
    m.solve(case)  # warm
    out = []
    for _ in range(n):
        t = time.process_time()
        m.solve(case)
        out.append(time.process_time() - t)
    return np.array(out)


def cold_peak_mib(m: AxisymMethod, case: ContactCase) -> float:
    axisym_solver._TABLES.clear()
    axisym_solver._TAIL.clear()
    axisym_solver._CONST.clear()
    axisym_solver._ENV.clear()
    axisym_solver._BASIS.clear()
    tracemalloc.start()
    m.solve(case)
    peak = tracemalloc.get_traced_memory()[1] / 2**20
    tracemalloc.stop()
    return peak


def refined(case: ContactCase, r) -> object:
    if r.meta["n_edge"]:
        # the next level of the nested sequence (tests/axisym/test_thin_self_convergence.py): the
        # same finest and top scales at ratio 1.25^(1/2), so its basis contains the default's
        return AxisymMethod(edge_ratio=1.25**0.5, order=12, keep_fields=False).solve(case)
    return AxisymMethod(n_modes=min(2 * r.meta["n_modes"], 400), order=12, keep_fields=False).solve(case)


def single_coatings() -> None:
    base = load_case("example:b4c_on_steel")
    a0 = base.a0s
    rows = [(f"H = {H:7.1e}", base.with_thickness(H * a0)) for H in
            (1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 0.1, 1.0, 10.0)]
    rows.insert(1, ("1 nm B4C ", base.with_thickness(1e-9)))
    worst = dict.fromkeys(QS, 0.0)
    for label, case in rows:
        for kf in (False, True):
            m = AxisymMethod(keep_fields=kf)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                t = cpu_times(m, case)
                peak = cold_peak_mib(m, case)
                r = m.solve(case)
            if kf:
                print(f"      with profiles (keep_fields): median {np.median(t) * 1e3:5.1f} ms CPU, "
                      f"cold peak {peak:5.1f} MiB")
                continue
            ref = refined(case, r)
            err = {q: abs(getattr(r, q) / getattr(ref, q) - 1.0) for q in QS}
            for q in QS:
                worst[q] = max(worst[q], err[q])
            print(f"  {label} (h/a = {r.meta['h_over_a']:.2g}): N = {r.meta['n_modes']:3d}, "
                  f"{r.meta['n_edge']:2d} edge functions, {r.meta['iterations']} radii; "
                  f"median {np.median(t) * 1e3:5.1f} ms CPU (max {np.max(t) * 1e3:5.1f}), "
                  f"cold peak {peak:5.1f} MiB; vs refined: "
                  + ", ".join(f"{q} {e:.1e}" for q, e in err.items()))
    print("  largest difference to the refined solves: "
          + ", ".join(f"{q} {v:.1e}" for q, v in worst.items()))


def _random_stack(rng, n_layers: int, a0: float, H_lo: float, H_hi: float) -> ContactCase:
    Es = 200e9 * 10.0 ** rng.uniform(-1.0, 1.0, n_layers)
    Hs = 10.0 ** rng.uniform(math.log10(H_lo), math.log10(H_hi), n_layers)
    layers = tuple(Layer(Material(float(E), 0.3), float(H) * a0) for E, H in zip(Es, Hs, strict=True))
    return ContactCase(Body.rigid_sphere(10e-3), Body(STEEL, layers=layers), 1.0)


def stacks(n_cases: int) -> None:
    rng = np.random.default_rng(3)
    m = AxisymMethod(keep_fields=False)
    probe = ContactCase(Body.rigid_sphere(10e-3), Body.half_space(STEEL), 1.0)
    a0 = (3.0 * probe.W * probe.R / (4.0 * probe.E_star_s)) ** (1.0 / 3.0)
    rows = [(f"{n} layer(s)", n, 1e-2, 10.0**0.5, "H_min >= 0.01") for n in (1, 2, 3, 4)]
    rows.append(("3 layers, thin", 3, 1e-5, 1e-3, "H from 1e-5 to 1e-3"))
    for label, n_layers, H_lo, H_hi, what in rows:
        cases = [_random_stack(rng, n_layers, a0, H_lo, H_hi) for _ in range(n_cases)]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = m.solve_many(cases)  # warm
            t = []
            for c in cases:
                t0 = time.process_time()
                m.solve(c)
                t.append(time.process_time() - t0)
            worst = dict.fromkeys(QS, 0.0)
            for c, r in zip(cases, res, strict=True):
                ref = refined(c, r)
                for q in QS:
                    worst[q] = max(worst[q], abs(getattr(r, q) / getattr(ref, q) - 1.0))
            peak = max(cold_peak_mib(m, c) for c in cases[:3])
        t = np.array(t)
        print(f"  {label}: median {np.median(t) * 1e3:5.1f} ms CPU, 90th percentile "
              f"{np.percentile(t, 90) * 1e3:5.1f} ms over {n_cases} cases ({what}); cold peak "
              f"<= {peak:4.1f} MiB (3 cases); vs refined: "
              + ", ".join(f"{q} {v:.1e}" for q, v in worst.items()))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print(f"machine: {platform.machine()} {platform.processor()}, {os.cpu_count()} CPUs visible "
          f"(shared with other jobs: timings are noisy), python {platform.python_version()}")
    print("single coatings (B4C example, h = H a0s):")
    single_coatings()
    print("layer stacks on steel (rigid 10 mm sphere, 1 N):")
    stacks(8 if args.quick else 25)


if __name__ == "__main__":
    main()
