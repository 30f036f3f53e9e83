"""Benchmark of the axisymmetric FE model (a script, not part of the test run).

For each case at the default mesh it reports the wall time of ``FEMMethod.solve`` (median of
``--repeat`` solves), the factorisations and active-set iterations per solve, and ``delta``,
``a``, ``p0`` to full precision. Cases (issue 13, item 4):

* ``keer_a``: Section 6, Keer et al. case A (two identical coated balls; goal <= 0.4 s);
* ``thin``: rigid sphere on a thin stiff coating, E = Ec/Es = 4, H = h/a0s = 0.01 (goal <= 1.5 s);
* ``rigid_base``: rigid sphere on an incompressible layer (nu_c = 0.5, H = h/a0c = 0.2) bonded
  to a rigid base (mixed u-p system, the other factorisation path).

``--json FILE`` writes the numbers; ``--compare FILE`` checks delta, a, p0 against an earlier
output and prints the time ratios. With ``--legacy`` every case is also solved, in the same
process, by

* ``_before``: the path before issue 13 item 4 on the mesh before issue 9 (refactorising
  active set, skfem's generic assembly, no edge band, L = 40): the numbers of
  ``bench_fem_before.json`` (measured on the unmodified code);
* ``_newpath``: the condensed solve (one factorisation) on that same old mesh: the same numbers
  to round-off, so its time against ``_before`` is the solver's speed-up;

and the plain rows are the default (edge band s0/3, L = 160), so the ratios are measured in one
run on the shared machine.

Usage: ``python tests/benchmarks/bench_fem.py [--repeat 3] [--legacy] [--json out.json]``.
"""

from __future__ import annotations

import argparse
import inspect
import json
import os
import platform
import time
from dataclasses import replace
from importlib.resources import files

import numpy as np

from coathertz.case import ContactCase
from coathertz.casefile import load_case
from coathertz.fem.method import FEMMethod
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)


def cases() -> dict[str, ContactCase]:
    keer = load_case(files("coathertz") / "data" / "keer_case_a.toml")
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(800e9, 0.3), 1.0, STEEL)
    thin = c0.with_thickness(0.01 * c0.a0s)
    layer = Material(200e9, 0.5)
    rb0 = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 1e-6)), 1.0)
    rigid_base = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(layer, 0.2 * rb0.a0c)), 1.0)
    return {"keer_a": keer, "thin": thin, "rigid_base": rigid_base}


def _method(variant: str) -> FEMMethod:
    m = FEMMethod()
    if variant in ("before", "newpath"):
        m.spec = replace(m.spec, edge_refine=1.0, L=40.0)  # the mesh before issue 9
    if variant == "before":
        m._reuse_factorisation = False  # refactorising active set, generic assembly
    return m


def run(case: ContactCase, repeat: int, variant: str = "default") -> dict:
    times = []
    for _ in range(repeat):
        m = _method(variant)
        t = time.perf_counter()
        r = m.solve(case)
        times.append(time.perf_counter() - t)
    st = r.meta["solver_stats"]
    return {
        "wall_s": float(np.median(times)),
        "factorisations": st.get("factorisations", st.get("setups")),
        "contact_iterations": r.meta["contact_iterations"],
        "remeshes": r.meta["remeshes"],
        "dofs": r.meta["dofs"],
        "delta": r.delta,
        "a": r.a,
        "p0": r.p0,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--legacy", action="store_true", help="also time the refactorising path")
    ap.add_argument("--json", help="write the results to this file")
    ap.add_argument("--compare", help="earlier --json output: check delta, a, p0 to 1e-10")
    args = ap.parse_args()
    can_legacy = "_reuse_factorisation" in inspect.getsource(FEMMethod)
    print(f"# {platform.processor() or platform.machine()}, python {platform.python_version()},"
          f" load average {os.getloadavg()[0]:.1f}")
    out = {}
    for name, case in cases().items():
        if args.legacy and can_legacy:
            out[name + "_before"] = run(case, args.repeat, "before")
            out[name + "_newpath"] = run(case, args.repeat, "newpath")
        out[name] = run(case, args.repeat)
    old = json.loads(open(args.compare).read()) if args.compare else {}
    print(f"{'case':<18} {'wall [s]':>9} {'fact.':>6} {'iter':>5} {'dofs':>7}  delta, a, p0")
    for name, v in out.items():
        line = (f"{name:<18} {v['wall_s']:9.3f} {v['factorisations']:6d} {v['contact_iterations']:5d}"
                f" {v['dofs']:7d}  {v['delta']:.12e} {v['a']:.12e} {v['p0']:.12e}")
        base = old.get(name.removesuffix("_before").removesuffix("_newpath")) if name.endswith(
            ("_before", "_newpath")) else None
        if base:
            rel = max(abs(v[k] / base[k] - 1) for k in ("delta", "a", "p0"))
            line += f"  max rel diff {rel:.1e}, time ratio {v['wall_s'] / base['wall_s']:.2f}"
        print(line)
    for name in cases():
        if name + "_before" in out:
            b, n, d = out[name + "_before"], out[name + "_newpath"], out[name]
            rel = max(abs(n[k] / b[k] - 1) for k in ("delta", "a", "p0"))
            print(f"{name}: same mesh, condensed vs refactorising: {b['wall_s'] / n['wall_s']:.2f}x faster,"
                  f" max rel diff {rel:.1e}; default mesh vs before: {b['wall_s'] / d['wall_s']:.2f}x faster"
                  " (same run)")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
