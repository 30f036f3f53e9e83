"""Post-processing: contact radius, peak pressure, pressure profile and subsurface stresses.

Pressure profile
    ``p_i = lambda_i / w_i`` at the surface nodes, ``w_i = int phi_i 2 pi r ds`` the nodal
    area (row-sum lumping of the consistent surface mass). Exact for uniform pressure, O(s^2)
    for smooth pressure. The node on the axis has ``w_0 = 0`` for Q2 and is skipped.
Peak pressure ``p0``
    Least-squares fit ``p = c0 + c1 r^2 + c2 r^4`` to the nodal pressures at ``0 < r <= 0.3 a``
    (the pressure is smooth and even in ``r`` near the axis); ``p0 = c0``.
Contact radius ``a`` (sub-element estimate)
    Outside the edge of a contact between smooth bodies the gap grows like ``(r - a)^{3/2}``
    (Hertz; generally for a square-root pressure edge), so ``g^{2/3}`` is linear in ``r`` near
    ``a``. ``a`` is the root of a linear fit of ``g^{2/3}`` on the 2nd to 5th inactive surface
    nodes (the first one is skipped: its gap is dominated by the discretisation of the edge).
    Alternatives kept in ``meta``: ``a_pfit`` (root of ``p^2`` fitted linearly in ``r^2`` on the
    active nodes in ``[0.7 a_n, r_{n-2}]``, exact in form for Hertz but biased for coated
    bodies whose ``p^2`` is curved), ``a_node`` (last active node) and ``a_num = sqrt(S/pi)``.
    Measured on Hertz with the edge placed anywhere between nodes: the gap fit errs
    <= 0.1 % at 20 elements across ``a`` and <= 0.05 % at 40 (node spacing is half the element
    size for Q2); ``a_node`` errs up to one node spacing (1.2 % / 0.6 %).
Stresses
    Quadrature-point stresses are L2-projected (weight ``2 pi r``) on continuous Q2 fields, one
    projection per region, so jumps of ``sigma_rr`` and ``sigma_tt`` across the
    coating/substrate interface are kept; values along the axis and both sides of the interface
    are probed from them.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, ElementQuad1, ElementQuad2, LinearForm, asm

from coathertz.errors import ConvergenceError
from coathertz.fem import forms
from coathertz.fem.model import INTORDER, FEModel

STRESS_NAMES = ("sigma_rr", "sigma_zz", "sigma_tt", "sigma_rz")
#: Surface nodes at ``r <= AXIS_TOL * a`` are on the axis.
AXIS_TOL = 1e-9


def surface_pressure(lam: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Nodal pressures ``lambda_i / w_i`` (0 where ``w_i = 0``, i.e. on the axis)."""
    p = np.zeros_like(lam)
    ok = weights > 1e-9 * weights.max()  # the Q2 node on the axis has w = 0 (up to round-off)
    p[ok] = lam[ok] / weights[ok]
    return p


def peak_pressure(r: np.ndarray, p: np.ndarray, a: float) -> float:
    """``p(0)`` from the fit ``c0 + c1 r^2 + c2 r^4`` on ``0 < r <= 0.3 a`` (the axis node, whose
    pressure is undefined, is the one at ``r <= 1e-9 a``: its coordinate carries round-off of the
    mesh's scale, so ``r > 0`` alone is not scale-invariant)."""
    off_axis = r > AXIS_TOL * a
    sel = off_axis & (r <= 0.3 * a)
    if sel.sum() < 4:
        sel = off_axis & (r <= 0.6 * a)
    if sel.sum() < 4:
        raise ConvergenceError("too few surface nodes inside the contact to estimate p0: refine the mesh")
    return float(np.polyfit(r[sel] ** 2, p[sel], 2)[-1])


def contact_radius(r: np.ndarray, p: np.ndarray, gap: np.ndarray, active: np.ndarray) -> dict:
    """Sub-element estimates of the contact radius (see module docstring); ``a`` is the gap fit."""
    ia = np.nonzero(active)[0]
    last = int(ia.max())
    a_node = float(r[last])
    out = {"a_node": a_node}
    gi = np.arange(last + 2, min(last + 6, len(r)))
    if len(gi) < 3:
        raise ConvergenceError("contact reaches the end of the candidate zone: enlarge r_fine")
    d1, d0 = np.polyfit(r[gi], np.cbrt(np.clip(gap[gi], 0.0, None)) ** 2, 1)
    a_gap = float(-d0 / d1) if d1 > 0 else math.nan
    if not (r[max(last - 1, 0)] <= a_gap <= r[last + 2]):
        a_gap = math.nan  # implausible: fall back below
    sel = active & (r >= 0.7 * a_node) & (r <= r[max(last - 2, 0)])
    a_p = math.nan
    if sel.sum() >= 3:
        c1, c0 = np.polyfit(r[sel] ** 2, p[sel] ** 2, 1)
        a_p = float(np.sqrt(-c0 / c1)) if c1 < 0 < c0 else math.nan
    out["a_gap"] = a_gap
    out["a_pfit"] = a_p
    out["a"] = a_gap if math.isfinite(a_gap) else (a_p if math.isfinite(a_p) else a_node)
    edges = np.concatenate([[0.0], 0.5 * (r[1:] + r[:-1]), [r[-1]]])
    out["a_num"] = float(edges[last + 1])  # sqrt(S/pi), S the active nodes' tributary disc
    return out


def quad_stress(model: FEModel, x: np.ndarray) -> dict[int, np.ndarray]:
    """Stress ``[4, nel_region, nqp]`` per region index at the quadrature points."""
    eps = model.quad_strain(x)
    out = {}
    p_off = model.n_u
    blocks = iter(model._p_blocks)
    for k, reg in enumerate(model.regions):
        e = eps[:, reg.elements]
        lam, mu = reg.law.lame
        if reg.mixed:
            pd, _, _, scale = next(blocks)
            pb = Basis(model.lm.mesh, ElementQuad1(), intorder=INTORDER, elements=reg.elements)
            pfull = np.zeros(pb.N)
            pfull[pd] = scale * x[p_off : p_off + len(pd)]
            p_off += len(pd)
            pq = np.asarray(pb.interpolate(pfull))
            sig = np.array(forms.linear_stress(0.0, mu)(tuple(e)))
            sig[:3] -= pq
        else:
            sig = np.array(forms.linear_stress(lam, mu)(tuple(e)))
        out[k] = sig
    return out


def von_mises(s: np.ndarray) -> np.ndarray:
    srr, szz, stt, srz = s
    return np.sqrt(0.5 * ((srr - szz) ** 2 + (szz - stt) ** 2 + (stt - srr) ** 2) + 3.0 * srz**2)


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses, sorted descending (``sigma_tt`` is one of them)."""
    srr, szz, stt, srz = s
    c = 0.5 * (srr + szz)
    d = np.sqrt((0.5 * (srr - szz)) ** 2 + srz**2)
    return -np.sort(-np.array([c + d, c - d, stt]), axis=0)


class StressField:
    """Continuous (per region) Q2 projections of the four stress components; ``at(points)``.

    ``sig`` (optional): quadrature-point stresses per region index, e.g. from a non-linear law's
    committed state (:mod:`coathertz.fem.plastic.method`); default: the linear-elastic stresses
    of ``x`` (:func:`quad_stress`).

    A region is projected when it is first read (:meth:`at`). On the tensor-product mesh of
    :mod:`coathertz.fem.mesh` (every element an axis-aligned rectangle) the mass matrix and the
    right-hand sides come from the reference tables of :class:`coathertz.fem.affine.RectQ2` (the
    same quadrature as skfem's ``asm(forms.mass, ...)``, equal to round-off, measured <= 1e-15
    relative in ``tests/fem/test_stress_points.py``) and the mass matrix, symmetric positive
    definite, is factorised in SuperLU's symmetric mode; other meshes use skfem's assembly.
    """

    def __init__(self, model: FEModel, x: np.ndarray, sig: dict[int, np.ndarray] | None = None):
        self.model = model
        self._x = x
        self._sig = sig
        self.nodal: dict[int, np.ndarray] = {}
        self._full: Basis | None = None
        self._rect = model.rect

    @property
    def full(self) -> Basis:
        """Scalar Q2 basis of the whole mesh (its probes; built on first use, one quadrature
        point per element: the probes do not depend on the quadrature)."""
        if self._full is None:
            self._full = Basis(self.model.lm.mesh, ElementQuad2(), intorder=1)
        return self._full

    def _stresses(self) -> dict[int, np.ndarray]:
        if self._sig is None:
            self._sig = quad_stress(self.model, self._x)
        return self._sig

    def _project(self, k: int) -> np.ndarray:
        """Nodal values ``[4, N]`` of the projection of region ``k`` (zero off the region)."""
        mesh = self.model.lm.mesh
        els = self.model.regions[k].elements
        sig = self._stresses()[k]
        if self._rect is None:
            sb = Basis(mesh, ElementQuad2(), intorder=INTORDER, elements=els)
            dofs = np.unique(sb.element_dofs)
            M = asm(forms.mass, sb).tocsc()[dofs][:, dofs]
            lu = spla.splu(M)
            vals = np.zeros((4, sb.N))
            for i in range(4):
                b = asm(LinearForm(lambda v, w: w["s"] * v * 2 * np.pi * w.x[0]), sb, s=sig[i])
                vals[i, dofs] = lu.solve(b[dofs])
            return vals
        q = self._rect
        edofs = self.full.element_dofs[:, els]  # [9, nel_k]
        n = self.full.N
        dx = 2 * np.pi * q.r[els] * np.abs(q.h_r[els] * q.h_z[els])[:, None] * q.W  # [nel_k, nq]
        Me = dx @ np.einsum("kq,lq->qkl", q.N, q.N).reshape(len(q.W), 81)  # [nel_k, 81]
        rows = np.repeat(edofs.T, 9, axis=1).ravel()
        cols = np.tile(edofs.T, (1, 9)).ravel()
        M = sp.csc_matrix((Me.ravel(), (rows, cols)), shape=(n, n))
        dofs = np.unique(edofs)
        lu = spla.splu(M[dofs][:, dofs], permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
        # b_i[dof(j, e)] = sum_q N_j(q) sigma_i(e, q) dx(e, q)
        be = np.einsum("jq,ieq->iej", q.N, sig * dx[None])  # [4, nel_k, 9]
        vals = np.zeros((4, n))
        for i in range(4):
            b = np.bincount(edofs.T.ravel(), weights=be[i].ravel(), minlength=n)
            vals[i, dofs] = lu.solve(b[dofs])
        return vals

    def at(self, region: int, pts: np.ndarray) -> np.ndarray:
        """Stresses ``[4, npts]`` of ``region`` at ``pts[2, npts]`` (points inside the region)."""
        if region not in self.nodal:
            self.nodal[region] = self._project(region)
        P = self.full.probes(pts).tocsr()
        return np.array([P @ self.nodal[region][i] for i in range(4)])


def stress_report(model: FEModel, x: np.ndarray, a: float,
                  sig: dict[int, np.ndarray] | None = None) -> tuple[dict, dict]:
    """Axis and interface stress profiles (fields) and their extrema (meta); ``sig`` as in
    :class:`StressField`. The coating/substrate interface has the keys ``interface_coating`` and
    ``interface_substrate``; a stack's interface ``i`` (under layer ``i``, over an elastic layer or
    substrate) ``interface{i}_above`` and ``interface{i}_below``."""
    sf = StressField(model, x, sig)
    lm = model.lm
    fields: dict[str, np.ndarray] = {}
    meta: dict = {}
    eps = 1e-7 * lm.a_ref
    depth_max = min(lm.D, 3.0 * max(a, lm.h)) - eps
    z = -np.linspace(eps, depth_max, 301)
    ax = np.zeros((4, len(z)))
    for k, reg in enumerate(model.regions):
        zc = lm.mesh.p[1, lm.mesh.t[:, reg.elements]]
        inside = (z <= zc.max() + 1e-12) & (z >= zc.min() - 1e-12)
        if inside.any():
            ax[:, inside] = sf.at(k, np.vstack([np.full(inside.sum(), eps), z[inside]]))
    fields["axis_z"] = z
    for name, v in zip(STRESS_NAMES, ax, strict=True):
        fields[f"axis_{name}"] = v
    vm = von_mises(ax)
    fields["axis_von_mises"] = vm
    i = int(np.argmax(vm))
    meta["axis_max_von_mises"] = {"value": float(vm[i]), "z": float(z[i])}
    # (region above, region below, depth, key prefix of each side): the coating/substrate
    # interface, or each interface of a stack over what lies below it (none on a rigid base)
    sides: list[tuple[int, int, float, str, str]] = []
    if len(lm.depths) <= 1:
        if lm.h > 0 and len(model.regions) > 1:
            sides.append((0, 1, lm.h, "interface_coating", "interface_substrate"))
    else:
        for i, d in enumerate(lm.depths):
            if i + 1 < len(model.regions):
                sides.append((i, i + 1, d, f"interface{i + 1}_above", f"interface{i + 1}_below"))
    rr = np.linspace(eps, 3.0 * a, 301)
    for k_up, k_down, depth, key_up, key_down in sides:
        for k, key, dz in ((k_up, key_up, +1), (k_down, key_down, -1)):
            pts = np.vstack([rr, np.full(len(rr), -depth + dz * 1e-6 * depth)])
            s = sf.at(k, pts)
            fields["interface_r"] = rr
            for name, v in zip(STRESS_NAMES, s, strict=True):
                fields[f"{key}_{name}"] = v
            vmi = von_mises(s)
            fields[f"{key}_von_mises"] = vmi
            pr = principal(s)
            fields[f"{key}_sigma_1"] = pr[0]
            j, jt, jr = int(np.argmax(vmi)), int(np.argmax(pr[0])), int(np.argmax(np.abs(s[3])))
            meta[key] = {
                "max_von_mises": float(vmi[j]),
                "r_max_von_mises": float(rr[j]),
                "max_sigma_1": float(pr[0][jt]),
                "r_max_sigma_1": float(rr[jt]),
                "max_abs_sigma_rz": float(abs(s[3][jr])),
                "r_max_abs_sigma_rz": float(rr[jr]),
            }
    return fields, meta
