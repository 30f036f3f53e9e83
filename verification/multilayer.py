r"""Layer stacks: an interlayer's modulus and thickness against delta, a and p0.

Not a figure of the paper: an extension. Configuration: a rigid sphere (R = 5 mm, W = 2 N) on a
3 um TiN top layer (450 GPa, nu = 0.25) over an interlayer (modulus ratio
:math:`E_i/E_s`, nu = 0.3, thickness :math:`h_i`) on steel (210 GPa, 0.3), all interfaces bonded;
plus the TiN layer alone (``coating-only``, a one-layer stack: equal to the coating to 1e-15,
``tests/multilayer``), the baseline of every ratio. The closed form refuses stacks; the exact
method (axisym, where registered), the FFT and the FE model solve them (the FE, about 1 s of CPU
per case at its default mesh, on every case at ``full``, on the baseline and two interlayers at
``quick``).

Claims: an interlayer of the substrate's own material (:math:`E_i = E_s`) adds nothing (each
quantity within 1e-6 % of the coating-only case, at every :math:`h_i`: an identity of the
N-layer kernel, judged on an exact method, reference rank >= 30; measured 4e-8 %); the FFT and
the FE agree with the exact method within 0.02 % in delta and p0 and 0.1 % in a (measured at
``quick``: 0.0023 % and 0.05 %); the effect of the interlayer on delta, a, p0 is mapped
(figure).

Resolutions: ``full`` 5 ratios x 4 thicknesses; ``quick`` 3 x 3; ``tiny`` 2 x 1 (+ the baseline).
"""

from __future__ import annotations

import math

from coathertz import verification as C
from coathertz.case import ContactCase
from coathertz.materials import Body, Layer, Material

NAME = "multilayer"
TITLE = "Layer stacks: TiN over an interlayer (modulus ratio, thickness) on steel, rigid sphere"
CLAIM = ("Extension: an interlayer of the substrate's material adds nothing; the "
         "interlayer's modulus and thickness against delta, a, p0 (exact method, FFT and FE).")
STEEL = Material(210e9, 0.3)
TIN = Material(450e9, 0.25)
H_TOP = 3e-6
R, W = 5e-3, 2.0
IDENTITY_BOUND = 1e-6  # percent
#: Agreement asked of every stack-capable method with the exact one [%]: delta and p0 2e-4, a 1e-3.
AGREE_BOUND = {"delta": 0.02, "p0": 0.02, "a": 0.1}
QS = ("delta", "a", "p0")
#: Methods ranked this high are exact (the axisymmetric integral-equation method): they judge the identity.
EXACT_RANK = 30


def grid(resolution: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Interlayer modulus ratios E_i/E_s and thicknesses h_i [m]."""
    C.check_resolution(resolution)
    if resolution == "full":
        return (0.25, 0.5, 1.0, 2.0, 4.0), (0.1e-6, 0.3e-6, 1e-6, 3e-6)
    if resolution == "quick":
        return (0.25, 1.0, 4.0), (0.1e-6, 1e-6, 3e-6)
    return (0.25, 1.0), (1e-6,)


def _case(layers: tuple[Layer, ...], label: str) -> ContactCase:
    return ContactCase(Body.rigid_sphere(R), Body(STEEL, layers=layers), W, label=label)


def fe_cases(resolution: str) -> set[tuple[float, float]]:
    """The (E_i/E_s, h_i) the FE solves besides the baseline: every one at ``full`` and ``tiny``;
    at ``quick`` the soft and the stiff interlayer at the middle thickness (the FE costs about a
    second per case, the main job's budget)."""
    ratios, hs = grid(resolution)
    if resolution == "quick":
        return {(ratios[0], hs[1]), (ratios[-1], hs[1])}
    return {(Ei, hi) for Ei in ratios for hi in hs}


def cases(resolution: str) -> list[C.StudyCase]:
    ratios, hs = grid(resolution)
    fe = fe_cases(resolution)
    base = _case((Layer(TIN, H_TOP),), "TiN on steel")
    out = [C.StudyCase("coating-only", base, {"E_i": math.nan, "h_i": 0.0}, "expensive")]
    for Ei in ratios:
        for hi in hs:
            cid = f"Ei={Ei:g},hi={hi * 1e6:g}um"
            layers = (Layer(TIN, H_TOP), Layer(Material(Ei * STEEL.E, STEEL.nu), hi))
            tier = "expensive" if (Ei, hi) in fe else "moderate"
            out.append(C.StudyCase(cid, _case(layers, cid), {"E_i": Ei, "h_i": hi}, tier))
    return out


def _reference_rows(result: C.StudyResult) -> dict[str, dict]:
    return {r["case"]: r for r in result.rows if result.reference.get(r["case"]) == r["method"]}


def analyse(result: C.StudyResult) -> None:
    # the identity is a property of the kernel: judged on an exact (arbiter-rank) method only, as
    # a discretising method's grid and estimators differ between the two cases
    ref = {cid: r for cid, r in _reference_rows(result).items()
           if C.method_info(r["method"]).reference_rank >= EXACT_RANK}
    base = ref.get("coating-only")
    same = [r for cid, r in ref.items() if cid != "coating-only" and r.get("E_i") == 1.0]
    if base is None or not same:
        result.claims.append(C.Claim(
            "multilayer-substrate-interlayer-adds-nothing", "an interlayer of the substrate's material "
            "adds nothing (needs an exact method, reference rank >= 30: none ran)", math.nan,
            f"< {IDENTITY_BOUND:g} %", None, "%", 1e-6))
    else:
        worst = max(abs(r[q] / base[q] - 1.0) * 100.0 for r in same for q in QS)
        result.claims.append(C.Claim(
            "multilayer-substrate-interlayer-adds-nothing",
            "max over h_i and delta, a, p0 of |stack / coating-only - 1| for an interlayer of the "
            "substrate's material (an identity)", worst, f"< {IDENTITY_BOUND:g} %",
            worst < IDENTITY_BOUND, "%", 1e-6,
            judged_against=f"{', '.join(sorted({r['method'] for r in same}))} on {len(same)} cases"))
    checks = [d for d in result.crosscheck if not d["method"].endswith("-refined")]
    for suffix, qs, bound, what in (("delta-p0", ("delta", "p"), AGREE_BOUND["delta"], "delta and p0"),
                                    ("a", ("a",), AGREE_BOUND["a"], "a")):  # qs: the cross-checks' names
        mine = [d for d in checks if d["quantity"] in qs]
        if not mine:
            continue
        d = max(mine, key=lambda d: abs(d["diff"]))
        worst = abs(d["diff"])
        result.claims.append(C.Claim(
            f"multilayer-methods-agree-{suffix}",
            f"max |difference| of the other methods (FFT, FE) from the exact method over the stacks, "
            f"{what} (the stack issue's bound)", worst, f"< {bound:g} %", worst < bound, "%", 0.05 * bound,
            f"largest: {d['pair']}, case {d['case']}",
            judged_against=f"{len({x['case'] for x in mine})} cases, "
                           f"{', '.join(sorted({x['pair'] for x in mine}))}"))


def plot(result: C.StudyResult, outdir) -> list:
    ref = _reference_rows(result)
    base = ref.get("coating-only")
    fig, axes = C.figure(3, width=3.6, height=3.2)
    ratios = sorted({r["E_i"] for r in result.rows if r["case"] != "coating-only"})
    labels = {"delta": r"$\delta$", "a": "a", "p0": r"$p_0$"}
    for j, q in enumerate(QS):
        ax = axes[0, j]
        for i, Ei in enumerate(ratios):
            col = C.colour(i, len(ratios))
            for m in sorted({r["method"] for r in result.rows}):
                pts = sorted((r["h_i"] * 1e6, 100.0 * (r[q] / base[q] - 1.0)) for r in result.rows
                             if r["method"] == m and r.get("E_i") == Ei and base is not None)
                if not pts:
                    continue
                is_ref = all(result.reference.get(r["case"]) == m for r in result.rows
                             if r["method"] == m and r.get("E_i") == Ei)
                ax.plot([p[0] for p in pts], [p[1] for p in pts],
                        **{**C.method_style(m, col), "ls": "-" if is_ref else "none"},
                        label=f"$E_i/E_s$ = {Ei:g} ({m})")
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xscale("log")
        ax.set_xlabel(r"interlayer thickness $h_i$ [$\mu$m]")
        ax.set_ylabel(f"{labels[q]} / coating-only - 1 [%]")
        ax.set_title(f"{labels[q]}", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0, -1].legend(fontsize=6, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.suptitle("Layer stacks: 3 um TiN over an interlayer on steel, rigid sphere R = 5 mm, W = 2 N; "
                 "change against TiN alone (lines: reference, markers: other methods)", fontsize=9)
    fig.set_layout_engine("tight")  # laid out when drawn, in the render process
    return C.save(fig, outdir, "multilayer")
