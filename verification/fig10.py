r"""Figure 10 (Section 5): elliptical contact on a coated elastic half-space, eq (21).

Configuration: principal relative radii Rx = 17.4 mm and Ry = 3 mm (Johnson's example, page 97;
1/zeta ~ 3.18), W = 400 N, :math:`\nu_c = \nu_s = 0.3`, modulus ratios E in {1/4, 0.8, 1.25, 4};
a rigid indenter (as in the alpha fits) on the coated half-space. Bars are ratios to the
uncoated elliptical Hertz values of eqs (5b-d) (``r_a/r_a0s``, ``r_b/r_b0s``,
``delta/delta0s``, ``p/p0s``), :math:`H = h/a_{0s}` with :math:`a_{0s} = \sqrt{r_{a0} r_{b0}}`.
The paper used a 128 x 128 grid with dy = dx/3; our FFT method's default cell aspect follows
the Hertz ellipse (dy/dx = r_b/r_a ~ 0.31).

Paper's claim: eqs (5), (17), (18), (21) predict the semi-axes, approach and maximum pressure
*within 4 %*. FE does not apply (not axisymmetric).

Resolutions: ``full`` 4 E x 50 H; ``quick`` 4 E x 6 H; ``tiny`` 2 E x 2 H.
"""

from __future__ import annotations

import numpy as np

from coathertz.case import ContactCase
from coathertz.extended import predict
from coathertz.materials import RIGID, Body, Coating, Material

from . import _common as C

NAME = "fig10"
TITLE = "Figure 10: elliptical contact (Rx = 17.4 mm, Ry = 3 mm, W = 400 N), eq (21)"
CLAIM = "Eqs (5), (17), (18), (21) predict the elliptical cases within 4 % (Section 5)."
BOUND = 4.0
QUANTITIES = ("r_a", "r_b", "delta", "p")
RX, RY, W = 17.4e-3, 3.0e-3, 400.0
RATIOS = (0.25, 0.8, 1.25, 4.0)


def elliptical_case(E: float, H: float, label: str = "") -> ContactCase:
    sub = Material(C.E_SUBSTRATE, C.NU)
    coat = Material(E * sub.E_star * (1 - C.NU**2), C.NU)
    indenter = Body(RIGID, None, RX, RY, name="rigid ellipsoid")
    base = ContactCase(indenter, Body.half_space(sub, Coating(coat, 0.0)), W)
    return ContactCase(indenter, Body.half_space(sub, Coating(coat, H * base.a0s)), W, label=label)


def grid(resolution: str):
    C.check_resolution(resolution)
    if resolution == "full":
        return RATIOS, C.h_grid(0.01, 3.0, 50)
    if resolution == "quick":
        return RATIOS, C.h_grid(0.03, 3.0, 6)
    return (0.25, 4.0), np.array([0.1, 1.0])


def cases(resolution: str) -> list[C.StudyCase]:
    Es, Hs = grid(resolution)
    return [C.StudyCase(f"E={E:g},H={H:.4g}", elliptical_case(E, float(H), f"E={E:g},H={H:.4g}"),
                        {"E": float(E), "H": float(H), "nu_c": C.NU, "nu_s": C.NU}, C.CF_FFT)
            for E in Es for H in Hs]


def analyse(result: C.StudyResult) -> None:
    n = len({r["case"] for r in result.rows})
    for ref in C.NUMERICAL:
        if not result.rows_of(ref):
            continue
        result.claims.append(C.bound_claim(
            "fig10-max-err", f"max |err| of eqs (5), (17), (18), (21) over {n} elliptical cases",
            result.errors, ref, BOUND, QUANTITIES))
        for q in QUANTITIES:
            v, k, _ = C.max_abs(result.errors, ref, (q,))
            result.claims.append(C.Claim(f"fig10-max-err-{q}-{ref}",
                                         f"max |err| of {q} against {ref.upper()}", v,
                                         f"< {BOUND:g} %", bool(v < BOUND), "%", 0.05, f"{k} cases"))


def plot(result: C.StudyResult, outdir) -> list:
    fig, axes = C.figure(4, width=3.7, height=3.4)
    Es = sorted({r["E"] for r in result.rows})
    H_line = np.geomspace(0.01, 3.0, 60)
    labels = {"r_a": r"$r_a/r_{a0s}$", "r_b": r"$r_b/r_{b0s}$", "delta": r"$\delta/\delta_{0s}$",
              "p": r"$p_0/p_{0s}$"}
    field = {"r_a": "r_a_bar", "r_b": "r_b_bar", "delta": "delta_bar", "p": "p_bar"}
    for i, E in enumerate(Es):
        col = C.colour(i, len(Es))
        preds = [predict(elliptical_case(E, float(H)), warn=False) for H in H_line]
        ref_case = elliptical_case(E, 1.0)
        n = ref_case.normalisers
        curves = {"r_a": [p.r_a / n.r_a0 for p in preds], "r_b": [p.r_b / n.r_b0 for p in preds],
                  "delta": [p.delta / n.delta0 for p in preds], "p": [p.p0 / n.p0 for p in preds]}
        for j, q in enumerate(QUANTITIES):
            ax = axes[0, j]
            ax.plot(H_line, curves[q], color=col, lw=1.2, label=f"E = {E:g}")
            x, y = C.series(result.rows, "fft", "E", E, "H", field[q])
            if len(x):
                ax.plot(x, y, "o", color=col, ms=4)
    for j, q in enumerate(QUANTITIES):
        ax = axes[0, j]
        ax.set_xscale("log")
        ax.set_xlabel(r"$H = h/a_{0s}$")
        ax.set_ylabel(labels[q])
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].legend(fontsize=7, title="lines: eq (21); o: FFT", title_fontsize=7)
    fig.suptitle("Fig. 10: elliptical contact, Rx = 17.4 mm, Ry = 3 mm, W = 400 N", fontsize=10)
    fig.tight_layout()
    return C.save(fig, outdir, "fig10")


