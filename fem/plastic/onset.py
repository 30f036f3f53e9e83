r"""Elastic yield onset: the load at which the von Mises stress first reaches the yield stress.

No plasticity is computed: the elastic FE solution (:class:`coathertz.fem.method.FEMMethod`) at a
load ``W`` gives the largest ratio :math:`\rho(W) = \max \sigma_{vM} / Y` over the coating
(yield stress ``Yc``) and the substrate (``Ys``), and where it occurs. For a homogeneous body the
stress field scales with :math:`p_0 \propto W^{1/3}` (Hertz, Johnson 1985 eq 4.23), so
:math:`W_y = W / \rho^3` (the next solve's load; one solve where the first guess is right). A
coating with other elastic constants breaks the self-similarity: the next load is then the root
of :math:`\rho = 1` on the mesh of the last solve, found by secant steps in ``log W`` with the
contact solved again at trial loads on that solve's factorisation (``_predict``; cheap: no
new mesh or factorisation), and each full solve at its own mesh checks :math:`|\rho - 1| <`
``tol`` (at ``tol`` = 1e-3, 2-3 elastic solves per search in the quick study, against 4-5 with
secant steps between full solves, which stay the fallback).

The maximum is located in two stages: the largest quadrature-point value, then a 21 x 21 probe
grid (two element sizes wide) of the per-region :math:`L^2`-projected stress field
(:class:`coathertz.fem.post.StressField`) around it, with a parabolic refinement.

Reference (homogeneous half-space, rigid sphere, nu = 0.3): first yield on the axis at
``p0 = 1.60 Y``, depth ``z = 0.48 a`` (Johnson 1985, Section 6.2); :func:`hertz_axis_onset` gives
the closed-form numbers from the Hertz stresses on the axis (Johnson eq 3.45).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fem.method import FEMMethod, axisymmetric_equivalent, refuse_plastic_stack
from coathertz.fem.post import StressField, contact_radius, quad_stress, surface_pressure, von_mises


def hertz_axis_onset(nu: float) -> tuple[float, float]:
    """``(p0/Y, z/a)`` of first yield under a Hertz pressure (Johnson 1985, eq 3.45 on the axis)."""

    def vm_over_p0(zeta: float) -> float:
        s_z = -1.0 / (1.0 + zeta**2)
        s_r = -((1.0 + nu) * (1.0 - zeta * math.atan(1.0 / zeta)) - 0.5 / (1.0 + zeta**2))
        return abs(s_r - s_z)

    opt = minimize_scalar(lambda z: -vm_over_p0(z), bounds=(0.05, 2.0), method="bounded",
                          options={"xatol": 1e-12})
    return 1.0 / vm_over_p0(opt.x), float(opt.x)


@dataclass(frozen=True)
class YieldOnset:
    """First yield of an elastic solution (see module docstring)."""

    W_y: float  # load at first yield [N]
    p0_y: float  # maximum contact pressure at W_y [Pa]
    a_y: float  # contact radius at W_y [m]
    where: str  # "coating", "interface" or "substrate"
    region: str  # the region that yields: "coating" or "substrate"
    r: float  # location [m]
    z: float  # location [m] (z < 0 inside the body)
    Y: float  # yield stress of that region [Pa]
    solves: int
    rho: float  # max sigma_vM / Y at W_y (1 within tol)

    @property
    def p0_over_Y(self) -> float:
        return self.p0_y / self.Y


def _yield_stresses(case: ContactCase, Yc: float | None, Ys: float | None) -> tuple[float, float]:
    refuse_plastic_stack(case, "yield onset")
    eq = axisymmetric_equivalent(case)
    if eq is None:
        raise CoatHertzError("yield onset needs a case the FE model supports: " + case.describe())
    body = eq.body

    def pick(given, m, name):
        if given is not None:
            if not (0 < given < math.inf):
                raise CoatHertzError(f"{name} must satisfy 0 < {name} < inf [Pa], got {given!r}")
            return float(given)
        if m is not None and m.plasticity is not None:
            return m.plasticity.Y
        return math.inf

    Yc_ = pick(Yc, body.coating.material if body.is_coated else None, "Yc")
    Ys_ = pick(Ys, None if body.material.is_rigid else body.material, "Ys")
    if math.isinf(Yc_) and math.isinf(Ys_):
        raise CoatHertzError("yield onset needs a yield stress: give Yc/Ys or Material(..., plasticity=...)")
    return Yc_, Ys_


def _locate(model, k: int, r0: float, z0: float, s: float, sf: StressField) -> tuple[float, float, float]:
    """Refine the maximum of von Mises in region ``k`` near ``(r0, z0)`` on the projected field ``sf``."""
    els = model.regions[k].elements
    pz = model.lm.mesh.p[:, model.lm.mesh.t[:, els]]
    rmin, rmax, zmin, zmax = pz[0].min(), pz[0].max(), pz[1].min(), pz[1].max()
    rr = np.clip(np.linspace(r0 - 2 * s, r0 + 2 * s, 21), rmin + 1e-9 * s, rmax - 1e-9 * s)
    zz = np.clip(np.linspace(z0 - 2 * s, z0 + 2 * s, 21), zmin + 1e-9 * s, zmax - 1e-9 * s)
    R, Z = np.meshgrid(np.unique(rr), np.unique(zz), indexing="ij")
    vm = von_mises(sf.at(k, np.vstack([R.ravel(), Z.ravel()]))).reshape(R.shape)
    i, j = np.unravel_index(int(np.argmax(vm)), vm.shape)

    def parab(vals, coords, idx):
        if 0 < idx < len(coords) - 1:
            y0, y1, y2 = vals[idx - 1], vals[idx], vals[idx + 1]
            den = y0 - 2 * y1 + y2
            if den < 0:
                t = 0.5 * (y0 - y2) / den
                return coords[idx] + t * (coords[idx + 1] - coords[idx]), y1 - 0.25 * (y0 - y2) * t
        return coords[idx], vals[idx]

    r_m, v1 = parab(vm[:, j], R[:, 0], i)
    z_m, v2 = parab(vm[i, :], Z[0, :], j)
    return float(r_m), float(z_m), float(max(v1, v2, vm[i, j]))


def _self_similar(case: ContactCase) -> bool:
    """Whether the elastic stress field of ``case`` is self-similar in the load (Hertz: a
    homogeneous elastic body, or a coating with the substrate's elastic constants)."""
    body = axisymmetric_equivalent(case).body
    if not body.is_coated:
        return not body.material.is_rigid
    c, m = body.coating.material, body.material
    return not m.is_rigid and (c.E, c.nu) == (m.E, m.nu)


def _predict(sv: _Solved, names: list[str], Ys: tuple[float, float], W: float, rho: float,
             rho_q: float, slope: float, tol: float, trials: int = 6) -> tuple[float, float] | None:
    """The next load of the search where the field is not self-similar: the root of
    ``c rho_q(W') = 1`` on the mesh and factorisation of the solve at ``W`` (the contact solved
    again at trial loads, ``ContactSolution.resolve``: a few dense steps and one sparse solve
    each), with ``rho_q`` the largest quadrature-point ratio and ``c = rho / rho_q`` at ``W``
    (the located maximum's excess). Secant steps in ``log W`` from the search's ``slope``, until
    ``|c rho_q - 1| < tol / 4``. The next full solve (its own mesh, built around the contact
    radius of the last trial, :func:`~coathertz.fem.post.contact_radius`: no rebuild where the
    layered Hertz estimate of the radius is off) then checks the criterion. Returns that load
    and radius; ``None`` where the factorisation cannot be reused or a trial fails (then the
    search's own step)."""
    resolve = getattr(sv.path.solution, "resolve", None)
    if resolve is None:
        return None
    model = sv.model
    Y = [Ys[0] if n == "coating" else Ys[1] for n in names]
    c = rho / rho_q

    cand = model.candidates
    r_c, weights = model.r_dof[cand], model.weights_all[cand]
    radius = [math.nan]

    def f(x: float) -> float:
        sol = resolve(math.exp(x))
        sig = quad_stress(model, sol.u)
        try:  # (None where the contact reaches the end of this mesh's candidates)
            radius[0] = contact_radius(r_c, surface_pressure(sol.lam, weights), sol.gap, sol.active)["a"]
        except ConvergenceError:
            radius[0] = math.nan
        return math.log(c * max(float(von_mises(sig[k]).max()) / Y[k] for k in range(len(names))
                                if math.isfinite(Y[k])))

    x0, f0 = math.log(W), math.log(rho)
    x1 = x0 - f0 / slope
    try:
        for _ in range(trials):
            f1 = f(x1)
            if abs(f1) < tol / 4:
                break
            if abs(f1 - f0) < 1e-14:
                return None
            x0, f0, x1 = x1, f1, x1 - f1 * (x1 - x0) / (f1 - f0)
            if abs(x1 - x0) > math.log(100.0):  # no root nearby on this mesh
                return None
        else:
            f(x1)  # the radius at the last step
    except (ConvergenceError, np.linalg.LinAlgError, ValueError):
        return None
    a = radius[0]
    return math.exp(x1), (a if 0 < a < math.inf else None)  # (nan: no guess)


@dataclass
class _Solved:
    """An elastic solve of the search at one load, with its quadrature-point stresses and the
    recovered field (:class:`~coathertz.fem.post.StressField`, regions projected when read)."""

    res: object
    model: object
    path: object
    sig: dict
    field: StressField


def _solve(method: FEMMethod, case: ContactCase, solves: dict | None,
           a_guess: float | None = None) -> _Solved:
    if solves is not None and case.W in solves:
        return solves[case.W]
    res, model, path = method.solve_full(case, a_guess=a_guess)
    sig = quad_stress(model, path.x)
    out = _Solved(res, model, path, sig, StressField(model, path.x, sig))
    if solves is not None:
        solves[case.W] = out
    return out


def yield_onset(case: ContactCase, method: FEMMethod | None = None, Yc: float | None = None,
                Ys: float | None = None, tol: float = 1e-3, max_solves: int = 8,
                solves: dict | None = None, a_guess: float | None = None) -> YieldOnset:
    """Load ``W_y`` of first yield of ``case`` (its load is the first guess) and where it occurs.

    Parameters
    ----------
    case
        A case the FE model supports; its load ``W`` starts the iteration.
    method
        The elastic FE method (default ``FEMMethod()``, default mesh).
    Yc, Ys
        Yield stresses of coating and substrate [Pa]; default: from the materials' ``plasticity``
        (a region without either never yields).
    tol
        Stop when ``|max sigma_vM / Y - 1| < tol``.
    solves
        The elastic solves by load, shared by searches of the same case (its elastic problem:
        bodies, geometry) and ``method`` with other yield stresses: a load solved before is not
        solved again (the searches take the same steps until their yield stresses make them
        differ). ``None``: nothing shared.
    a_guess
        The contact radius at the case's load where known (a search started from another
        mesh's answer): the first mesh is built around it (``FEMMethod.solve_full``).
    """
    from dataclasses import replace

    Yc_, Ys_ = _yield_stresses(case, Yc, Ys)
    method = method or FEMMethod()
    similar = _self_similar(case)
    W = case.W
    # a_guess: the contact radius at W (given, then predicted on the previous solve's mesh)
    prev: tuple[float, float] | None = None  # (log W, log rho) of the previous solve
    for it in range(1, max_solves + 1):
        sv = _solve(method, replace(case, W=W), solves, a_guess)
        res, model, sig = sv.res, sv.model, sv.sig
        lm = model.lm
        names = (["coating"] if lm.h > 0 else []) + ([] if lm.rigid_base else ["substrate"])
        best = (-1.0, -1, 0.0, 0.0)
        coords = model.quad_points()
        for k, name in enumerate(names):
            Y = Yc_ if name == "coating" else Ys_
            if math.isinf(Y):
                continue
            ratio = von_mises(sig[k]) / Y
            i = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
            els = model.regions[k].elements
            if ratio[i] > best[0]:
                best = (float(ratio[i]), k, float(coords[0][els][i]), float(coords[1][els][i]))
        rho, k, r0, z0 = best
        s = lm.a_ref / lm.spec.n_a
        if lm.h > 0:
            s = min(s, lm.h / max(lm.spec.n_coat, 1))
        r_m, z_m, vm_m = _locate(model, k, r0, z0, s, sv.field)
        Y = Yc_ if names[k] == "coating" else Ys_
        rho = max(rho, vm_m / Y)
        if abs(rho - 1.0) < tol:
            where = names[k]
            if lm.h > 0 and abs(z_m + lm.h) <= 0.05 * max(lm.h, s) + 1e-12:
                where = "interface"
            return YieldOnset(W, res.p0, res.a, where, names[k], r_m, z_m, Y, it, rho)
        slope = 1.0 / 3.0
        if prev is not None and abs(math.log(W) - prev[0]) > 1e-12:
            s_ = (math.log(rho) - prev[1]) / (math.log(W) - prev[0])
            slope = s_ if 0.05 < s_ < 2.0 else slope
        prev = (math.log(W), math.log(rho))
        W_next, a_guess = W * math.exp(-math.log(rho) / slope), None
        if not similar:
            W_next, a_guess = _predict(sv, names, (Yc_, Ys_), W, rho, best[0], slope, tol) or (W_next, None)
        W = W_next
    raise ConvergenceError(f"yield onset: max sigma_vM / Y = {rho:.4f} after max_solves={max_solves} solves")
