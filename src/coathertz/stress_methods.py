"""The methods that give stress fields, behind one signature (the registry of ``coathertz
stresses --method``).

Each entry solves the case with its own contact method and returns a :class:`StressResult`: the
field on an ``(x, y, z)`` lattice in the Voigt order of :mod:`coathertz.stress_summary` (for the
PNG and VTU files), the field the designer's maxima are read from, and the interface stresses.

* ``fft``: DC-FFT solution and per-depth FFT of the layered responses
  (:mod:`coathertz.fft.stresses`), any layer stack; friction (``mu``, ``Q``) allowed.
* ``axisym``: the exact axisymmetric solution and its Hankel integrals
  (:mod:`coathertz.axisym.stresses`), frictionless only, any layer stack. The maxima are read
  on the ``r-z`` half-plane (radii clustered at the contact edge, where the surface tension
  peaks; depths through every layer and both sides of each interface); the files hold the
  exact field revolved onto an ``n x n`` lattice of the same extent as the FFT's.
* ``fem``: the axisymmetric FE solution (default mesh) and its recovered stresses
  (:mod:`coathertz.fem.stress_points`) on the same ``r-z`` points; frictionless, one coating.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.stress_depths import default_depths


@dataclass(frozen=True)
class StressOptions:
    """What ``coathertz stresses`` asks of a method: lattice cells per side ``grid``, friction
    ``mu``, partial-slip load ``Q`` [N] (``None``: full sliding), ``depths`` [m] (``None``: the
    method's default) and whether the 3-D lattice for the files is wanted (``lattice``)."""

    grid: int = 128
    mu: float = 0.0
    Q: float | None = None
    depths: tuple[float, ...] | None = None
    lattice: bool = False


@dataclass(frozen=True)
class StressResult:
    """A stress field in body2 and what the summary needs.

    ``x, y, z, sigma``: the field the maxima are read from (``sigma[z, 6, y, x]``, Voigt order,
    Pa); ``interfaces``: ``(depth, sigma[6, y, x])`` on the upper side of each interface;
    ``lattice``: ``(x, y, z, sigma)`` on a regular ``x-y`` lattice for the files (``None`` if not
    asked); ``a, r_a, r_b, p0`` from the contact solution; ``label``: the method in words.
    """

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    sigma: np.ndarray
    interfaces: tuple[tuple[float, np.ndarray], ...]
    a: float
    r_a: float
    r_b: float
    p0: float
    label: str
    lattice: tuple | None = None
    meta: dict = field(default_factory=dict)


def fft_stresses(case: ContactCase, opt: StressOptions) -> StressResult:
    """DC-FFT solution and its stress field (:func:`coathertz.fft.stresses.contact_stresses`)."""
    from coathertz.fft.method import FFTMethod
    from coathertz.fft.stresses import contact_stresses

    res = FFTMethod(n=opt.grid).solve(case)
    kw = {"mu": opt.mu, "Q": opt.Q}
    f = contact_stresses(case, res, depths=opt.depths, **kw)
    bottoms = np.cumsum([L.h for L in case.body2.stack if L.h > 0])  # every interface (stack)
    inter: tuple = ()
    if bottoms.size:
        fi = contact_stresses(case, res, depths=bottoms, **kw)
        inter = tuple((float(zb), fi.sigma[i]) for i, zb in enumerate(bottoms))
    lattice = (f.x, f.y, f.z, f.sigma) if opt.lattice else None
    return StressResult(f.x, f.y, f.z, f.sigma, inter, res.a, res.r_a, res.r_b, res.p0,
                        f"FFT {opt.grid}^2", lattice, dict(f.meta))


def summary_radii(a: float, r_max: float) -> np.ndarray:
    """Radii [m] for the maxima: 0 to ``r_max``, clustered at and beyond the contact edge
    (steps ``a/200`` within ``0.8a .. 1.6a``, ``r = a`` itself included: the surface tension peaks
    at the edge on a homogeneous body and up to ~0.1a beyond it under a stiff coating)."""
    rho_max = r_max / a
    rho = np.concatenate([np.linspace(0, 0.8, 33), np.linspace(0.8, 1.6, 161),
                          np.linspace(1.6, max(rho_max, 1.7), 50)])
    return np.unique(rho) * a


def axisym_stresses(case: ContactCase, opt: StressOptions) -> StressResult:
    """Exact axisymmetric solution and its stress field (:mod:`coathertz.axisym.stresses`)."""
    from coathertz.axisym.method import AxisymMethod
    from coathertz.axisym.stresses import AxisymStresses

    if opt.mu != 0 or opt.Q is not None:
        raise CoatHertzError("--method axisym: the exact method gives the frictionless normal "
                             f"solution only (got --mu {opt.mu:g}); use --method fft for friction")
    res = AxisymMethod().solve(case)
    S = AxisymStresses(case, res, body=2)
    body = case.body2
    a = res.a
    H = S.response.depth
    r = summary_radii(a, max(3 * a, 2 * H))
    z_min = S.min_depth(float(r[-1]))
    bottoms = [p.z0 + p.h for p in S.response.parts]  # on a rigid base the last is the base itself
    if bottoms and bottoms[0] < z_min:
        raise CoatHertzError(
            f"--method axisym: body2's top layer (h = {bottoms[0] * 1e6:.3g} um = {bottoms[0] / a:.2g} a) "
            f"is thinner than the smallest depth the Hankel quadrature takes ({z_min * 1e6:.3g} um): "
            "its interface stresses are out of reach; use --method fft")
    dropped = 0
    if opt.depths is None:
        z = default_depths(body, a)
        keep = (z == 0) | (z >= z_min)  # thin layers: the quadrature's floor
        dropped = int(np.sum(~keep))
        z = z[keep]
    else:
        z = np.asarray(opt.depths, float)
    F = S.field(r, z)
    inter = tuple((zb, S.field(r, [zb], side="above").voigt()[0]) for zb in bottoms)
    lattice = None
    if opt.lattice:
        lattice = _revolve(lambda rr: S.field(rr, z).sigma, z, a, opt.grid)
    meta = {**F.meta, "radii": int(r.size), "r_max": float(r[-1]), "depths_dropped": dropped}
    return StressResult(r, np.zeros(1), z, F.voigt(), inter, a, a, a, res.p0,
                        "exact axisymmetric", lattice, meta)


def fem_stresses(case: ContactCase, opt: StressOptions) -> StressResult:
    """Axisymmetric FE solution (default mesh) and its recovered stresses sampled on the ``r-z``
    half-plane (:mod:`coathertz.fem.stress_points`): radii to ``min(3a, L)`` clustered at the
    edge, the depths of :func:`~coathertz.stress_depths.default_depths`."""
    from coathertz.fem.method import FEMMethod
    from coathertz.fem.post import StressField
    from coathertz.fem.stress_points import sample

    if opt.mu != 0 or opt.Q is not None:
        raise CoatHertzError("--method fem: the FE model is frictionless (no tangential traction; got "
                             f"--mu {opt.mu:g}); use --method fft for friction")
    fm = FEMMethod()
    res, model, path = fm.solve_full(case)
    a = res.a
    body = case.body2
    z = default_depths(body, a) if opt.depths is None else np.asarray(opt.depths, float)
    sf = StressField(model, path.x)
    r = summary_radii(a, min(3 * a, model.lm.L))
    sig = sample(model, path.x, r, z, field=sf)
    H = model.lm.h

    def voigt(f: np.ndarray) -> np.ndarray:  # (nz, 4, nr) -> (nz, 6, 1, nr)
        rr, tt, zz, rz = (f[:, j] for j in range(4))
        zero = np.zeros_like(rr)
        return np.stack([rr, tt, zz, zero, rz, zero], axis=1)[:, :, None, :]

    inter: tuple = ()
    if H > 0:
        inter = ((H, voigt(sample(model, path.x, r, [H], field=sf))[0]),)
    lattice = None
    if opt.lattice:
        lattice = _revolve(lambda rr: sample(model, path.x, rr, z, field=sf), z, a, opt.grid)
    meta = {"method": "fem", "elements": res.meta["elements"], "mesh": fm.mesh, "radii": int(r.size)}
    return StressResult(r, np.zeros(1), z, voigt(sig), inter, a, a, a, res.p0,
                        f"FE ({res.meta['elements']} elements)", lattice, meta)


def _revolve(field_at: Callable[[np.ndarray], np.ndarray], z: np.ndarray, a: float, n: int) -> tuple:
    """An axisymmetric field on the ``n x n`` cell centres of a square of side ``2.5 a`` (the FFT's
    default domain) at the depths ``z``: ``field_at(radii)`` (``(nz, 4, nr)``: ``rr, tt, zz, rz``)
    at every distinct radius, rotated to ``(xx, yy, zz, yz, xz, xy)``."""
    dx = 2.5 * a / n
    x = (np.arange(n) - n // 2) * dx
    X, Y = np.meshgrid(x, x)
    R = np.hypot(X, Y)
    radii, inv = np.unique(np.round(R / dx, 9), return_inverse=True)
    f = field_at(radii * dx)
    rr, tt, zz, rz = (f[:, j][:, inv.reshape(R.shape)] for j in range(4))
    th = np.arctan2(Y, X)
    c, s = np.cos(th), np.sin(th)
    sig = np.stack([c * c * rr + s * s * tt, s * s * rr + c * c * tt, zz, s * rz, c * rz,
                    c * s * (rr - tt)], axis=1)
    return x, x, z, sig


#: ``coathertz stresses --method NAME``: the default first.
STRESS_METHODS: dict[str, Callable[[ContactCase, StressOptions], StressResult]] = {
    "fft": fft_stresses,
    "axisym": axisym_stresses,
    "fem": fem_stresses,
}


def stress_method(name: str) -> Callable[[ContactCase, StressOptions], StressResult]:
    """The registered stress method ``name`` (one clear line otherwise)."""
    try:
        return STRESS_METHODS[name]
    except KeyError:
        raise CoatHertzError(f"unknown stress method {name!r}; choose one of {list(STRESS_METHODS)}") \
            from None


def check_depths(case: ContactCase, depths) -> None:
    """Depths must lie in body2 (down to its layers' bottom on a rigid base)."""
    body = case.body2
    H = sum(L.h for L in body.stack)
    bottom = H if body.material.is_rigid else math.inf
    bad = [z for z in depths if not (0 <= z <= bottom)]
    if bad:
        raise CoatHertzError(f"--depths: body2 depth {bad[0] * 1e6:g} um outside the body "
                             f"(valid: 0 to {bottom * 1e6:g} um)")
