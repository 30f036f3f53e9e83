"""Benchmark of the elastic-plastic FE load path (a script, not part of the test run).

One load-unload path of a rigid sphere (R = 10 mm) on a yielding steel half-space (E = 200 GPa,
nu = 0.3, Y = 1 GPa, perfectly plastic) to 3x the first-yield load, ``--steps`` loading and as
many unloading increments (default 10 + 10 = 20) on the ``default`` plastic mesh (20 elements
across the reference contact radius). Goal: <= 60 s on 2 cores. Prints wall and CPU time, the
Newton iterations of every increment and the time per factorisation.

``--approach UM`` runs the README's approach-control path instead (``coathertz fem
example:yielding_steel --plastic --approach "20 um"``, ``--steps`` increments). The targets:
README path (>= 20 increments) <= 3 s, a path to delta/delta_c = 200 <= 30 s, failed-attempt
solves <= 10 % of all linear solves (printed as ``failed solves``).

``--approach 20 --unload`` adds unloading (under load control, to contact loss). Measured on the
shared 2-core machine (CPU time; wall time is inflated by the load), default mesh:

- README load path (``--steps 10``, 20 increments): 0 failed solves of 76 before the step-control
  changes (line search, onset-aware first step), 0 of 78 after; CPU 30-36 s.
- README approach path with unloading (``--approach 20 --unload``): before, 24 increments for 20
  targets, 68 failed solves of 173 (39 %), CPU 64 s; after, 21 increments (onset + 10 + 10), 0
  failed of 95, CPU 40 s.

Usage: ``python tests/benchmarks/bench_plastic.py [--steps 10] [--mesh default] [--approach 20] [--unload]``.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time

from coathertz.case import ContactCase
from coathertz.fem.plastic.method import solve_plastic
from coathertz.materials import Body, Material, Plasticity

Y, R = 1e9, 0.01


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--mesh", default="default", choices=["coarse", "default", "fine"])
    ap.add_argument("--approach", type=float, default=None, help="approach control to this many um")
    ap.add_argument("--unload", action="store_true", help="with --approach: unload after loading")
    args = ap.parse_args(argv)
    mat = Material(200e9, 0.3, plasticity=Plasticity(Y))
    W_y = (1.6128 * Y) ** 3 * math.pi**3 * R**2 / (6 * mat.E_star**2)
    case = ContactCase(Body.rigid_sphere(R), Body.half_space(mat), 3.0 * W_y)
    t0, c0 = time.perf_counter(), time.process_time()
    if args.approach is None:
        res = solve_plastic(case, mesh=args.mesh, n_steps=args.steps, unload=True)
    else:
        res = solve_plastic(case, mesh=args.mesh, n_steps=args.steps, delta_max=args.approach * 1e-6,
                            unload=args.unload)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    m, c = res.meta, res.curves
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cpus "
          f"(load average {os.getloadavg()[0]:.1f})")
    print(f"mesh {args.mesh}: {m['elements']} Q2 elements, {m['dofs']} dofs; {m['increments']} increments "
          f"({(1 if args.approach and not args.unload else 2) * args.steps} targets), "
          f"{m['newton_iterations_total']} Newton iterations, "
          f"{m['factorisations']} factorisations")
    failed = m["factorisations"] - m["newton_iterations_total"]  # solves of failed (halved) attempts
    print(f"failed solves {failed} of {m['factorisations']} ({100 * failed / m['factorisations']:.0f} %; "
          "goal <= 10 %)")
    print(f"wall {wall:.1f} s, CPU {cpu:.1f} s "
          "(target: <= 3 s for the README path of >= 20 increments)")
    print("Newton iterations per increment:", " ".join(str(k) for k in c["newton_iterations"]))
    depth = res.final["residual_depth"]
    print(f"final load {c['W'][-1]:.5g} N, residual depth "
          f"{'-' if depth is None else f'{depth * 1e9:.2f} nm'}, max ep {m['plastic_zone']['ep_max']:.4g}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
