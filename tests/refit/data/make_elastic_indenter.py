"""Build ``elastic_indenter.json``: held-out exact solutions for an ELASTIC indenter.

Not used to fit anything. Cases: a steel ball on coated steel (the grid E = Ec*/Es* in
{0.25, 0.5, 2, 4} x H in {0.01, 0.03, 0.1, 0.3, 1, 3} x nu_c in {0.2, 0.3}) and a seeded
random draw of other balls (tungsten carbide, aluminium) with E log-uniform in [0.25, 4],
H log-uniform in [0.01, 3], nu_c uniform in [0.2, 0.4]. H = h/a0s, a0s the Hertz radius with
the coating removed (ball against bare substrate, eq 7a). Each case is solved by the exact
axisymmetric method at its default settings and again at
:meth:`AxisymMethod.refined_settings`; the stored ``refine_rel`` is the largest relative
difference of delta, a, p0 between the two (the reference's numerical uncertainty).

Usage: ``python tests/refit/data/make_elastic_indenter.py`` (about 2 s of CPU).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from coathertz.axisym import AxisymMethod
from coathertz.case import ContactCase
from coathertz.closedform.hertz import hertz_circular
from coathertz.materials import Material

R_BALL, W = 10e-3, 10.0
SUBSTRATE = Material(210e9, 0.3, "steel")
BALLS = {"steel": Material(210e9, 0.3, "steel"), "WC": Material(600e9, 0.24, "WC"),
         "Al": Material(70e9, 0.33, "Al")}
OUT = Path(__file__).with_name("elastic_indenter.json")


def case_of(ball: str, E: float, H: float, nu_c: float) -> ContactCase:
    """Ball ``ball`` on steel coated with Ec* = E Es* of Poisson's ratio nu_c, h = H a0s."""
    b = BALLS[ball]
    E_star_s = 1.0 / (1.0 / b.E_star + 1.0 / SUBSTRATE.E_star)
    a0s = float(hertz_circular(W, R_BALL, E_star_s).a0)
    coat = Material(E * SUBSTRATE.E_star * (1.0 - nu_c**2), nu_c, "coating")
    return ContactCase.sphere_on_coated_half_space(R_BALL, W, coat, H * a0s, SUBSTRATE, indenter=b)


def main() -> int:
    specs = [("steel", E, H, nu_c) for nu_c in (0.3, 0.2) for E in (0.25, 0.5, 2.0, 4.0)
             for H in (0.01, 0.03, 0.1, 0.3, 1.0, 3.0)]
    rng = np.random.default_rng(20261125)
    for i in range(16):
        specs.append((("WC", "Al")[i % 2], float(10 ** rng.uniform(np.log10(0.25), np.log10(4.0))),
                      float(10 ** rng.uniform(-2, np.log10(3.0))), float(rng.uniform(0.2, 0.4))))
    base = AxisymMethod()
    fine = AxisymMethod(**AxisymMethod.refined_settings("full"))
    rows = []
    for ball, E, H, nu_c in specs:
        case = case_of(ball, E, H, nu_c)
        r, f = base.solve(case), fine.solve(case)
        diff = max(abs(getattr(r, q) / getattr(f, q) - 1.0) for q in ("delta", "a", "p0"))
        rows.append({"ball": ball, "E": E, "H": H, "nu_c": nu_c, "delta": r.delta, "a": r.a,
                     "p0": r.p0, "refine_rel": diff})
    OUT.write_text(json.dumps({"R": R_BALL, "W": W, "substrate": [SUBSTRATE.E, SUBSTRATE.nu],
                               "balls": {k: [m.E, m.nu] for k, m in BALLS.items()},
                               "cases": rows}, indent=1) + "\n")
    print(f"{len(rows)} cases, largest refine_rel {max(r['refine_rel'] for r in rows):.2e} -> {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
