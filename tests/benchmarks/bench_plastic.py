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

Static condensation of the elastic far field (``fem/plastic/condense.py``, each iteration
factorises only a box around the contact and the plastic zone); ``--baseline`` solves the same path
factorising the whole tangent every iteration first and prints the CPU ratio (same run, 1 BLAS
thread, shared 2-core machine at load 5-6):

- README load path (``--baseline``): 26.1 -> 11.4 s CPU (ratio 2.30), 78 iterations, 0 failed
  solves, the same load (to 0) and residual depth 246.28 nm; 11 of the 78 box factorisations
  reused (elastic unloading);
- README approach path with unloading (``--approach 20 --unload --baseline``): 32.6 -> 15.0 s CPU
  (2.17), 95 iterations, 0 failed, largest load 1925.978 N (moved by 1e-14). Before today's
  changes the same path took 36.2 s CPU (a separate run);
- approach to delta/delta_c = 200 at E/Y = 1000 (``--delta-ratio 200 --EY 1000 --steps 20
  --baseline``): 78.3 -> 54.9 s CPU (1.43) with the box capped at 60 % of the elements (58 of
  197 solves factorised the whole tangent); 45.1 s CPU with the cap at 90 % (all 197 condensed;
  a separate run); 21 increments, 197 iterations, 0 failed solves, largest load 364.433 N.

Box matrix gathered into a structure built once per box, and ``t`` not solved again where
``b_e`` changed by round-off only (``T_REUSE`` in ``condense.py``); before (the previous
``condense.py``) and after in one process, 1 BLAS thread, the shared 2-core machine:

- README load path: 14.2 -> 14.0 s and 11.5 -> 9.9 s CPU (two pairs), 78 iterations, far-field
  solves for ``t`` 78 -> 62 (78 with ``T_REUSE = 0``), same load and residual depth 246.28 nm;
- README approach path with unloading: 16.0 -> 14.8 s and 16.1 -> 15.2 s CPU, 95 iterations,
  largest load 1925.978 N, residual depth 9158.09 nm both;
- delta/delta_c = 200 (E/Y = 1000, 20 steps): 43.1 -> 40.8 s CPU, 197 iterations, largest load
  364.433 N both.

Newton-loop assembly restricted to the elements that may yield (``BBarAssembler.evaluate(...,
stresses=False)``), the box's factors kept across the active-set changes of elastic unloading
(``ElasticCondensation._solve_free``), the far field solved once per iteration (for the combined
solution), no line search for a step already within the tolerance; the base commit's
``fem/plastic`` (c87b1d2) and the new one run alternately in one shell (``coathertz.fem.__path__``
pointed at a copy of each), 1 BLAS thread, the shared 2-core machine at load 5-10, CPU time:

- README load path: 13.3 / 10.7 s (base, two runs) -> 8.2 / 7.4 s (new), 78 iterations both
  (the same per increment), box factors reused 11 -> 39 times, far-field solves for ``t``
  62 -> 20, final load 0 and residual depth 246.28 nm both; the whole CLI command
  (``coathertz fem example:yielding_steel --plastic --unload --steps 10``, user CPU) 13.7 -> 8.0 s,
  the same table (residual depth 0.24762 um);
- delta/delta_c = 200 (E/Y = 1000, 20 steps): 39.9 -> 35.5 s, 197 iterations both, largest load
  364.433 N both.

Where the time goes now (CPU, instrumented run): README load path 8.3 s: box factorisations
2.6 s (45), the rest of the condensed solves 1.8 s, assembly 1.45 s (103 calls), contact-radius
fit 0.7 s, two condensations 0.6 s, the final stress report (``fem/post.py``) 0.6 s;
delta/delta_c = 200 35.0 s: box factorisations 17.6 s (203, boxes up to 90 % of the mesh),
assembly 8.7 s (275 calls, ~32 ms each: most of the fine zone yields, and every yielded element's
stiffness is integrated again), six condensations 1.5 s, the fit 1.05 s.

Element stiffness of the yielded elements as two batched matrix products on an element-major
strain operator (29 -> 6 ms for 1573 elements), the box matrix as one gather from the tangent's
data, ``K @ U0`` over the essential and active columns only (4.0 -> 1.0 ms); the base commit's
``fem/`` (ddc7b82, a copy, ``coathertz.fem.__path__`` pointed at it) and the new one alternately in
one shell, the whole ``solve_plastic`` call as this script makes it:

- delta/delta_c = 200 (E/Y = 1000, 20 steps), 1 BLAS thread, load 1.05: 33.2 / 34.8 -> 28.7 /
  30.2 s CPU; default threads, load 1.4-1.8: 33.0 / 34.4 -> 29.2 / 29.2 s wall (55.6 / 57.9 ->
  50.0 / 50.0 s CPU); 197 iterations (the same per increment), largest load 364.433014631 N in
  every run;
- README load path, 1 BLAS thread: 5.9 / 6.6 / 7.6 -> 6.3 / 6.5 / 6.7 s CPU (no change beyond the
  noise: its time is the box factorisations and the far field's solves); 78 iterations, final
  load 0, residual depth 246.27593 nm in every run.

Where the time of the delta/delta_c = 200 path goes now (cProfile, 1 thread, 34.6 s under the
profiler, with the new element stiffness, before the gather and ``K @ U0`` changes): SuperLU's
factorisation 18.9 s (203 calls; the box grows to 17.8k of the 28.7k unknowns, 2184 of 3528
elements, 75 % of them yielded, so neither a smaller box nor another box shape helps: a box shaped
to the plastic zone measured 495 against 458 Mflop), SuperLU's solves 3.2 s, the assembly 6.6 s (274
calls). The box's factorisation does 458 Mflop for 17.8k unknowns at 3-4 Gflop/s; measured and not
kept: a leaf size of 8 or 16 in the nested dissection (440 / 450 Mflop, the same time within the
noise), splitting the box into two halves factorised apart with a dense root (more CPU: 236 against
168 ms, and on two threads no shorter: 207-247 ms wall), a single-precision factorisation with
iterative refinement (two refinement steps reach round-off, but 132 against 150 ms before them).

The default two OpenBLAS threads do not shorten the path: SuperLU's factorisation here uses none
(CPU = wall), and the second core's 20 CPU-s are spent spinning: OpenBLAS threads ``ddot`` beyond
10k entries, and each ``np.linalg.norm`` of a long vector leaves its worker spinning about 0.11 s.
The condensation's norms and the residual's norm in ``contact.py`` (``IncrementalContact._residual``)
no longer use BLAS (``coathertz.blas.norm2``). Measured before the residual's was changed, with it
run under one BLAS thread to simulate that: 32.1 s wall, 32.1 s CPU, against 29.1 s wall, 48.6 s
CPU with the residual's norm threaded (load 1.1-1.4, the same iterations and loads); the whole
increment under one thread, two pairs: 29.9 / 28.9 s wall and 30.0 / 29.0 s CPU against 29.4 /
29.1 s wall and 51.3 / 50.1 s CPU.

With the residual's norm off BLAS (idle, 15:49-16:09 UTC): delta/delta_c = 200 in 27.7, 25.3 and
26.8 s wall (CPU = wall; the base ddc7b82 alternating with the first two: 33.1 and 28.9 s wall,
54.8 and 50.7 s CPU), under the 30 s target; the README load path 6.0, 6.8 and 7.7 s wall (7.6-9.3 s
CPU; base 6.9-7.7 s wall, 12.9-14.2 s CPU), not the 3 s target: per Newton iteration the box's
factorisation (up to 17.8k unknowns), one or two solves with the far field's factor and the
assembly (~25-30 ms late in the deep path) remain, at 4-15 iterations per increment.

Contact-following meshes (``--follow``) and the mean-pressure check (printed for
``--delta-ratio``), delta/delta_c = 200 at E/Y = 1000 in 20 steps, idle, one run each (16:09 UTC):

- default, fixed: 26.8 s wall, 197 iterations; p_mean/Y 2.6147 at 50 (Kogut & Etsion +3.2 %,
  Jackson & Green -4.5 %), 2.7801 at 100 (+1.2, -2.3 %); scatter 0.68 %;
- default, following: 65.4 s, 305; 2.5453 (+0.4, -7.0 %), 2.7448 (-0.1, -3.6 %); 1.24 %;
- coarse, following: 21.4 s, 279; 2.5561 (+0.9, -6.6 %), 2.7684 (+0.7, -2.7 %); 0.62 %;
- coarse, fixed: 8.6 s, 185; 2.6638 (+5.1, -2.7 %), 2.7627 (+0.5, -2.9 %); 2.83 %.

Largest loads 364.433, 364.366, 364.457, 364.442 N. The two fits differ by 8.0 % at 50 and 3.5 %
at 100: no value is within 3 % of both at 50. A following mesh costs what the fixed mesh's last
increments cost at every increment (the box holds most of the fine zone), plus a rebalance per
remesh; on the coarse mesh it resolves the early increments (first yield on Hertz's load to 1e-5,
against 7.7 % off on the fixed coarse mesh) for about the fixed default mesh's time.

Usage: ``python tests/benchmarks/bench_plastic.py [--steps 10] [--mesh default] [--approach 20]
[--unload] [--baseline] [--follow] [--delta-ratio 200 --EY 1000]``.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time

import numpy as np

from coathertz.case import ContactCase
from coathertz.fem.plastic.contact import NewtonSettings
from coathertz.fem.plastic.method import solve_plastic
from coathertz.materials import Body, Material, Plasticity

R = 0.01


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--mesh", default="default", choices=["coarse", "default", "fine"])
    ap.add_argument("--approach", type=float, default=None, help="approach control to this many um")
    ap.add_argument("--unload", action="store_true", help="with --approach: unload after loading")
    ap.add_argument("--baseline", action="store_true",
                    help="also solve the path factorising the whole tangent every iteration "
                         "(no condensation) "
                         "and print the CPU ratio")
    ap.add_argument("--delta-ratio", type=float, default=None,
                    help="approach control to this delta/delta_c (overrides --approach)")
    ap.add_argument("--follow", action="store_true",
                    help="contact-following meshes (solve_plastic(follow_contact=True)); prints the remeshes")
    ap.add_argument("--EY", type=float, default=200.0, help="E / Y (E = 200 GPa; default Y = 1 GPa)")
    args = ap.parse_args(argv)
    Y = 200e9 / args.EY
    mat = Material(200e9, 0.3, plasticity=Plasticity(Y))
    W_y = (1.6128 * Y) ** 3 * math.pi**3 * R**2 / (6 * mat.E_star**2)
    case = ContactCase(Body.rigid_sphere(R), Body.half_space(mat), 3.0 * W_y)
    if args.delta_ratio is not None:  # delta_c = a_y^2 / R, a_y = pi R p0_y / (2 E*)
        a_y = math.pi * R * 1.6128 * Y / (2 * mat.E_star)
        args.approach = args.delta_ratio * a_y**2 / R * 1e6

    def run(condense: bool):
        t0, c0 = time.perf_counter(), time.process_time()
        newton = NewtonSettings(condense=condense)
        if args.approach is None:
            res = solve_plastic(case, mesh=args.mesh, n_steps=args.steps, unload=True, newton=newton,
                                follow_contact=args.follow)
        else:
            res = solve_plastic(case, mesh=args.mesh, n_steps=args.steps, delta_max=args.approach * 1e-6,
                                unload=args.unload, newton=newton, follow_contact=args.follow)
        return res, time.perf_counter() - t0, time.process_time() - c0

    if args.baseline:
        base, _, cpu0 = run(False)
        print(f"baseline (whole tangent factorised every iteration): CPU {cpu0:.1f} s, "
              f"final/largest load {max(base.curves['W']):.7g} N, "
              f"{base.meta['newton_iterations_total']} Newton iterations")
    res, wall, cpu = run(True)
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
    print(f"linear solves: {m['linear_solves']}; largest load {max(c['W']):.7g} N")
    if args.baseline:
        print(f"CPU ratio baseline / now: {cpu0 / cpu:.2f}; largest load moved by "
              f"{max(c['W']) / max(base.curves['W']) - 1:.2e} (relative)")
    print("elements across a per increment:", " ".join(f"{x:.1f}" for x in c["elements_across_a"]))
    for r_ in m.get("remeshes", []):
        print(f"remesh ({r_['reason']}) a_ref {r_['a_ref_old'] * 1e6:.4g} -> {r_['a_ref_new'] * 1e6:.4g} um: "
              f"{'load' if m['control'] == 'approach' else 'approach'} {r_['change'] * 100:+.3f} % "
              "in the rebalance "
              f"({r_['newton_iterations']} Newton iterations)")
    if args.delta_ratio is not None:
        _mean_pressure_report(res, mat, a_y)
    depth = res.final["residual_depth"]
    print(f"final load {c['W'][-1]:.5g} N, residual depth "
          f"{'-' if depth is None else f'{depth * 1e9:.2f} nm'}, max ep {m['plastic_zone']['ep_max']:.4g}")
    return 0


def _mean_pressure_report(res, mat: Material, a_y: float) -> None:
    """Issue 20's mean-pressure check on an approach path: p_mean / Y at delta/delta_c = 50 and 100
    (the path's own increments there; delta_c = a_y^2 / R with Hertz's first yield) against Kogut &
    Etsion (2002) and Jackson & Green (2005) at the same approach, and the largest departure of an
    increment's p_mean from the log-log interpolation between its neighbours for
    delta/delta_c >= 20 (the scatter)."""
    from coathertz.fem.plastic.published import jackson_green, kogut_etsion

    c = res.curves
    Y = mat.plasticity.Y
    dc = a_y**2 / R
    rows = [(d / dc, pm / Y) for d, pm, ph in zip(c["delta"], c["p_mean"], c["phase"], strict=True)
            if ph == "loading" and pm > 0]
    for target in (50.0, 100.0):
        hit = [(x, pm) for x, pm in rows if abs(x / target - 1) < 1e-6]
        if not hit:
            continue
        x, pm = hit[0]
        ke = kogut_etsion(x * dc, mat.E_star, Y, mat.nu, R).p_mean / Y
        jg = jackson_green(x * dc, mat.E_star, Y, mat.nu, R).p_mean / Y
        print(f"p_mean/Y at delta/delta_c = {x:g}: {pm:.4f}; Kogut & Etsion {ke:.4f} "
              f"({100 * (pm / ke - 1):+.1f} %), Jackson & Green {jg:.4f} ({100 * (pm / jg - 1):+.1f} %)")
    xs = np.log([x for x, _ in rows if x >= 20.0])
    ps = np.log([pm for x, pm in rows if x >= 20.0])
    if len(xs) >= 3:
        dev = [abs(math.exp(ps[k] - np.interp(xs[k], xs[[k - 1, k + 1]], ps[[k - 1, k + 1]])) - 1)
               for k in range(1, len(xs) - 1)]
        print(f"p_mean scatter for delta/delta_c >= 20: largest {100 * max(dev):.2f} % (goal <= 2 %)")


if __name__ == "__main__":
    raise SystemExit(main())
