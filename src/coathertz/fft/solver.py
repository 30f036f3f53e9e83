"""Normal contact by the conjugate-gradient method of Polonsky & Keer (Wear 231 (1999) 206).

Load control: the load ``W`` is prescribed; the rigid-body approach ``delta`` (relative to
points far away in the bodies, which the half-space coefficients measure from) comes out as the
mean of ``u + g0`` over the contact. Surface displacements are computed by the zero-padded
DC-FFT (Liu, Wang & Liu, Wear 243 (2000) 101): the pressure on the ``ny x nx`` grid is padded
to ``2ny x 2nx`` and convolved cyclically with the wrap-around coefficients of
:func:`coathertz.fft.influence.circulant`, which is the exact linear convolution.

Efficiency
----------
* the iteration is written on whole arrays (no Python loop over cells) and works on a *batch*
  of ``B`` problems sharing one grid: arrays are ``(B, ny, nx)``, reductions are per problem;
* ``scipy.fft`` caches its plans; ``workers`` sets its threads; the kernel transform is
  computed once per (grid, bodies) and reused;
* the displacement is updated from the search direction's response
  (``u <- s (u - tau K t)``), so an iteration costs one convolution, except when the active set
  changed (clipped or re-activated points) or every ``REFRESH`` iterations (fresh ``K p``);
* the array namespace is chosen at run time (``backend="numpy"`` or ``"cupy"``), so the same
  code runs on a GPU with CuPy.

Nomenclature: ``p`` pressure [Pa] per cell, ``u`` total surface displacement of both bodies
(positive into the bodies), ``g0`` initial separation, ``gap = u + g0 - delta``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from coathertz.errors import CoatHertzError, ConvergenceError

REFRESH = 16


@dataclass(frozen=True)
class Backend:
    """Array namespace and FFT module (numpy + scipy.fft, or cupy + cupyx.scipy.fft)."""

    name: str
    xp: Any
    fft: Any
    workers: int | None

    def rfft2(self, a, s):
        if self.name == "numpy":
            return self.fft.rfft2(a, s=s, workers=self.workers)
        return self.fft.rfft2(a, s=s)

    def irfft2(self, a, s):
        if self.name == "numpy":
            return self.fft.irfft2(a, s=s, workers=self.workers)
        return self.fft.irfft2(a, s=s)

    def asarray(self, a):
        return self.xp.asarray(a)

    def to_numpy(self, a):
        return a if self.name == "numpy" else self.xp.asnumpy(a)


def get_backend(name: str = "numpy", workers: int | None = -1) -> Backend:
    """``numpy`` (scipy.fft with ``workers`` threads; -1: all cores) or ``cupy`` (GPU)."""
    if name == "numpy":
        from scipy import fft

        return Backend("numpy", np, fft, workers)
    if name == "cupy":
        try:
            import cupy
            import cupyx.scipy.fft as cfft
        except ImportError as exc:  # pragma: no cover - depends on the machine
            raise CoatHertzError("backend 'cupy' needs CuPy and a CUDA device") from exc
        return Backend("cupy", cupy, cfft, None)
    raise CoatHertzError(f"backend must be 'numpy' or 'cupy', got {name!r}")


class Convolver:
    """``u = K * p`` on a grid by zero-padded DC-FFT; ``khat`` may carry a batch axis.

    ``spacing = (dy, dx)`` enables :meth:`precondition`, the multiplication by ``|k|`` (the
    inverse of the half-space FRF ``2/(E* |k|)`` up to a constant factor, which CG does not see).
    """

    def __init__(self, kernel_circ, backend: Backend, spacing: tuple[float, float] | None = None):
        self.backend = backend
        kc = backend.asarray(kernel_circ)
        self.shape2 = tuple(kc.shape[-2:])
        self.ny, self.nx = self.shape2[0] // 2, self.shape2[1] // 2
        self.khat = backend.rfft2(kc, s=self.shape2)
        self.mhat = None
        if spacing is not None:
            dy, dx = spacing
            ky = 2 * np.pi * np.fft.fftfreq(self.shape2[0], dy)
            kx = 2 * np.pi * np.fft.rfftfreq(self.shape2[1], dx)
            self.mhat = backend.asarray(np.hypot(ky[:, None], kx[None, :]) * dx)

    def __call__(self, p):
        b = self.backend
        ph = b.rfft2(p, s=self.shape2)
        ph *= self.khat
        return b.irfft2(ph, s=self.shape2)[..., : self.ny, : self.nx]

    def precondition(self, r):
        """``|k| r`` on the padded grid (an approximate inverse of the half-space operator)."""
        b = self.backend
        rh = b.rfft2(r, s=self.shape2)
        rh *= self.mhat
        return b.irfft2(rh, s=self.shape2)[..., : self.ny, : self.nx]


@dataclass
class PKSolution:
    """Result of :func:`polonsky_keer` (batched arrays, numpy)."""

    p: np.ndarray
    u: np.ndarray
    delta: np.ndarray
    iterations: np.ndarray
    eps: np.ndarray
    residual: np.ndarray
    penetration: np.ndarray
    convolutions: int
    wall_time: float


def polonsky_keer(
    conv: Convolver,
    g0,
    W,
    cell_area: float,
    *,
    tol: float = 1e-10,
    max_iter: int = 2000,
    p_init=None,
    precondition: bool = False,
) -> PKSolution:
    """Solve ``B`` frictionless normal contact problems on one grid (Polonsky & Keer 1999).

    Parameters
    ----------
    conv
        The DC-FFT convolution (kernel of one problem, or a batch ``(B, 2ny, nx+1)``).
    g0
        Initial separation ``(ny, nx)`` or ``(B, ny, nx)`` [m].
    W
        Load(s) [N], scalar or ``(B,)``.
    cell_area
        ``dx dy`` [m^2].
    tol
        Stop when ``sum |p - p_old| dA / W < tol`` (P&K's error measure).
    max_iter
        Iteration cap; not converging within it raises :class:`ConvergenceError`.
    p_init
        Initial pressure (any non-negative field; rescaled to the load), default uniform.
    precondition
        Precondition the CG direction with ``|k|`` (needs ``conv`` built with ``spacing``): the
        iteration count roughly halves and stops growing with ``n`` (31-36 -> 17-27 at n = 128,
        57-105 -> 24-35 at n = 512), each iteration costs one more FFT pair, and at equal ``tol``
        the solution is 10-100x closer to the converged one.
    """
    if precondition and conv.mhat is None:
        raise CoatHertzError("precondition=True needs a Convolver built with spacing=(dy, dx)")
    if not (0 < tol < 1):
        raise CoatHertzError(f"tol must satisfy 0 < tol < 1, got {tol!r}")
    if not (isinstance(max_iter, int) and max_iter >= 1):
        raise CoatHertzError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    t0 = time.perf_counter()
    b = conv.backend
    xp = b.xp
    g0 = b.asarray(g0)
    ny, nx = conv.ny, conv.nx
    W = xp.atleast_1d(xp.asarray(W, dtype=float))
    B = max(W.shape[0], conv.khat.shape[0] if conv.khat.ndim == 3 else 1)
    if g0.ndim == 3:
        B = max(B, g0.shape[0])
    W = xp.broadcast_to(W, (B,)).copy()
    ax = (-2, -1)

    def bsum(a):
        return a.sum(axis=ax)

    def col(v):
        return v[:, None, None]

    def bdot(a, c):
        return xp.einsum("bij,bij->b", a, c)

    p = xp.ones((B, ny, nx)) if p_init is None else xp.broadcast_to(b.asarray(p_init), (B, ny, nx))
    p = xp.maximum(p, 0.0)
    p = p * col(W / (bsum(p) * cell_area))
    u = conv(p)
    nconv = 1
    t = xp.zeros_like(p)
    G_old = xp.ones(B)
    restart = xp.ones(B, dtype=bool)
    done = xp.zeros(B, dtype=bool)
    iters = xp.zeros(B, dtype=int)
    eps = xp.full(B, np.inf)
    for it in range(1, max_iter + 1):
        gap = u + g0
        m = (p > 0).astype(gap.dtype)
        n_in = bsum(m)
        gap -= col(bdot(gap, m) / n_in)
        gm = gap * m
        if precondition:
            z = conv.precondition(gm)
            nconv += 1
            z *= m
            z -= col(bdot(z, m) / n_in)
            z *= m
            G = bdot(gm, z)
        else:
            z = gm
            G = bdot(gm, gap)
        beta = xp.where(restart, 0.0, G / xp.where(G_old == 0, 1.0, G_old))
        t *= col(beta)
        t *= m
        t += z
        G_old = G
        r_raw = conv(t)
        nconv += 1
        rt = bdot(r_raw, t) - bdot(r_raw, m) / n_in * bsum(t)
        tau = bdot(gm, t) / xp.where(rt == 0, 1.0, rt)
        tau = xp.where(done, 0.0, tau)
        p_old = p
        p = p - col(tau) * t
        changed = bool(xp.any(p < 0))
        xp.maximum(p, 0.0, out=p)
        overlap = (gap < 0) & (p == 0)
        restart = bsum(overlap) > 0
        if bool(xp.any(restart)):
            changed = True
            p = xp.where(overlap, p - col(tau) * gap, p)
        scale = W / (bsum(p) * cell_area)
        p *= col(scale)
        if changed or it % REFRESH == 0:
            u = conv(p)
            nconv += 1
        else:
            u -= col(tau) * r_raw
            u *= col(scale)
        eps = bsum(xp.abs(p - p_old)) * cell_area / W
        newly = (eps < tol) & ~done
        iters = xp.where(newly, it, iters)
        done = done | newly
        if bool(xp.all(done)):
            break
    if not bool(xp.all(done)):
        worst = float(xp.max(eps))
        raise ConvergenceError(
            f"Polonsky-Keer CG did not reach tol={tol:g} within max_iter={max_iter} iterations "
            f"(largest relative pressure change {worst:.3g} in {int(xp.sum(~done))} of {B} "
            "problem(s)); raise max_iter or refine the grid"
        )
    u = conv(p)
    nconv += 1
    gap = u + g0
    inside = p > 0
    n_in = bsum(inside)
    delta = bsum(gap * inside) / n_in
    gap = gap - col(delta)
    scale_d = xp.abs(delta)
    residual = xp.sqrt(bsum(gap * gap * inside) / n_in) / scale_d
    penetration = xp.maximum(-xp.min(xp.where(inside, 0.0, gap), axis=ax), 0.0) / scale_d
    return PKSolution(
        p=b.to_numpy(p),
        u=b.to_numpy(u),
        delta=b.to_numpy(delta),
        iterations=b.to_numpy(iters),
        eps=b.to_numpy(eps),
        residual=b.to_numpy(residual),
        penetration=b.to_numpy(penetration),
        convolutions=nconv,
        wall_time=time.perf_counter() - t0,
    )
