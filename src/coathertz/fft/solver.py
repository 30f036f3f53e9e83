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
* the work arrays (pressure, gap, direction, its response, masks, the transform buffers of
  :class:`Convolver`) are allocated once per solve; the iteration runs in in-place ufuncs
  and transforms with ``out=`` / ``overwrite_x``, so no grid-size array is allocated inside
  it (numpy backend; tested with ``tracemalloc``). Fresh large arrays each iteration cost
  page faults worth about half a solve at n <= 256;
* ``scipy.fft`` caches its plans; ``workers`` sets its threads (1 by default up to n = 256,
  :func:`default_workers`); the kernel transform is computed once per (grid, bodies);
* the displacement is updated from the search direction's response
  (``u <- s (u - tau K t)``), so an iteration costs one convolution. When the projections
  (clipping negative pressures, re-activating overlapping points) change at most
  :data:`MAX_DIRECT_CELLS` cells, their response is added directly from the kernel; more
  changes, and every ``REFRESH`` iterations, take a fresh ``K p``;
* the CG direction is preconditioned by the inverse of the kernel's transform
  (:meth:`Convolver.precondition`, one more transform pair per iteration): the exact inverse
  of the operator on the padded grid, so that CG is left with the restriction to the contact
  set and its changes. Iterations stay flat in n and in the layer: 6-15 over 30 cases of the
  paper's families at n = 128-512 (a ``|k|`` preconditioner, the inverse for a half-space
  only, cost up to 5x on thin layers over a rigid base; plain CG needed 9-38 there, growing
  with n). With the nested start of :class:`~coathertz.fft.method.FFTMethod`, the transform
  pairs per solve (coarse pairs weighted by their size, re-gridding included) over the 30
  cases are 18-37 (median 23) at n = 128, 19-41 (24) at 256 and 22-42 (25) at 512
  (``tests/benchmarks/bench_fft.py --family``; the previous path: 15-48, 18-47, 19-53);
* a point contact's problem is even in ``x`` and ``y`` about the centre cell (``g0``, the
  kernel, and a start prolonged or carried over from such a problem): with ``symmetric=True``
  the iteration runs on the quarter plane ``x, y >= 0`` (a quarter of the cells), sums
  weighted by the mirror images, and the convolution is a DCT-I of length ``n + 1`` per axis
  (:meth:`Convolver.quarter`: the same ``2n``-periodic operator, half the transform work).
  A :meth:`Convolver.from_quadrant` builds the whole grid's transforms only if they are used
  (an uneven start, a contact reaching the cells without mirror image). Measured on the quick
  verification run's 348 FFT results (2 shared cores): 24.5 -> 15 CPU-s; against the
  whole-grid iteration from the same starts, 334 results within 1e-10 (delta, a, p0), 347
  within 1e-7, and one re-gridding decision at its threshold taken the other way (a moved
  by 1.9e-4, a grid of other cells);
* the array namespace is chosen at run time (``backend="numpy"`` or ``"cupy"``), so the same
  code runs on a GPU with CuPy (whole grid only).

Nomenclature: ``p`` pressure [Pa] per cell, ``u`` total surface displacement of both bodies
(positive into the bodies), ``g0`` initial separation, ``gap = u + g0 - delta``.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from coathertz.errors import CoatHertzError, ConvergenceError

REFRESH = 16
#: Floor of the kernel transform, relative to its maximum, in the preconditioner.
PRECONDITION_FLOOR = 1e-6
#: Up to this many cells changed by the projections, their response is added directly from the
#: kernel (three passes over the grid per cell) instead of a fresh transform pair; the two cost
#: about the same at ~20 cells for n = 128-512 (the pair's cost per cell grows like log n).
MAX_DIRECT_CELLS = 16


#: Grids with at most this many cells per side use one FFT thread by default: two threads were
#: slower there (128^2: 44 vs 27 ms per solve, 2-core x86-64), they pay off from 512^2 (1.25-1.46x).
SINGLE_THREAD_MAX_N = 256


def default_workers(n: int) -> int:
    """FFT threads for an ``n x n`` grid: 1 up to :data:`SINGLE_THREAD_MAX_N`, else all cores.

    Inside a worker process of a sweep (a ``multiprocessing`` child) it is always 1: the sweep
    already keeps the cores busy with one process each.
    """
    import multiprocessing

    if n <= SINGLE_THREAD_MAX_N or multiprocessing.parent_process() is not None:
        return 1
    return -1


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

    :meth:`precondition` multiplies by the inverse of the kernel's transform (the CG
    preconditioner of :func:`polonsky_keer`; its scale does not matter to CG).

    Work buffers
    ------------
    On the numpy backend the transform is done axis by axis into two buffers allocated once per
    Convolver and batch shape: a real FFT of the ``ny`` non-zero rows (length ``2 nx``,
    ``numpy.fft.rfft`` with ``out=``), a complex FFT of the ``2 ny``-long columns in place
    (``scipy.fft.fft`` with ``overwrite_x`` on a complex array, ``workers`` threads), the
    product with ``khat`` in place, the inverse column FFT in place and the inverse real FFT
    of the first ``ny`` rows only (the others are cut off). No grid-size array is allocated
    per call when ``out`` is given, and the zero rows and the discarded half are never
    transformed: 1.3-2x faster than a padded ``rfft2``/``irfft2`` pair (measured at
    n = 128-512, one thread, 2 shared cores).

    :meth:`add_cells` adds the response to pressure on a few cells directly from the kernel in
    real space (``G``, offsets ``-(n-1)..(n-1)``), which is cheaper than a transform pair when
    only a few cells change.
    """

    def __init__(self, kernel_circ, backend: Backend):
        self.backend = backend
        kc = backend.asarray(kernel_circ)
        self.shape2 = tuple(kc.shape[-2:])
        self.ny, self.nx = self.shape2[0] // 2, self.shape2[1] // 2
        self._kc, self._quadrant, self.batched = kc, None, kc.ndim == 3
        self._init_lazy()

    @classmethod
    def from_quadrant(cls, quadrant, backend: Backend) -> Convolver:
        """The convolver of the even kernel given by its quadrant ``K[..., |dy|, |dx|]``
        (offsets ``0..n``, :func:`coathertz.fft.influence.circulant`'s input). The whole grid's
        transforms are built only when first used; the quarter plane's
        (:meth:`quarter`) come from the quadrant's DCT-I directly."""
        self = cls.__new__(cls)
        self.backend = backend
        q = np.asarray(quadrant, dtype=float)
        self.ny, self.nx = q.shape[-2] - 1, q.shape[-1] - 1
        self.shape2 = (2 * self.ny, 2 * self.nx)
        self._kc, self._quadrant, self.batched = None, q, q.ndim == 3
        self._init_lazy()
        return self

    def _init_lazy(self) -> None:
        self._khat = self._mhat = self._khat_sym = self._mhat_sym = None
        self._G = None
        self._buffers: dict = {}
        self._sym_buffers: dict = {}

    @property
    def kernel_batch(self) -> int:
        """Problems with their own kernel (1: one kernel for all)."""
        k = self._quadrant if self._quadrant is not None else self._kc
        return int(k.shape[0]) if self.batched else 1

    @property
    def kernel_circ(self):
        """The wrap-around (``2ny x 2nx``) coefficients."""
        if self._kc is None:
            from coathertz.fft.influence import circulant

            q = self._quadrant
            self._kc = self.backend.asarray(
                np.stack([circulant(k) for k in q]) if q.ndim == 3 else circulant(q))
        return self._kc

    @property
    def khat(self):
        """The kernel's transform on the padded grid (``rfft2``; built when first used)."""
        if self._khat is None:
            b = self.backend
            self._khat = b.rfft2(self.kernel_circ, s=self.shape2)
            # the preconditioner: the inverse of the kernel's transform (real and positive for
            # the even, positive-definite kernels of elastic bodies), floored against round-off
            # (stored complex like ``khat``: a real factor would make the in-place product cast
            # through numpy's ufunc buffer, an allocation of 128 KiB per call)
            self._mhat = _inverse(self._khat.real, b.xp).astype(complex)
        return self._khat

    @property
    def mhat(self):
        """The preconditioner's multiplier (:meth:`precondition`)."""
        if self._mhat is None:
            _ = self.khat
        return self._mhat

    @property
    def buffered(self) -> bool:
        """Whether calls run in preallocated buffers (the numpy backend)."""
        return self.backend.name == "numpy"

    def _bufs(self, lead: tuple):
        b = self._buffers.get(lead)
        if b is None:
            ny, nx = self.ny, self.nx
            b = (np.empty((*lead, 2 * ny, nx + 1), complex), np.empty((*lead, ny, 2 * nx)))
            self._buffers[lead] = b
        return b

    def _apply(self, p, mult, out=None):
        ny, nx = self.ny, self.nx
        if self.buffered:
            # rows: numpy.fft with out= (the ny non-zero rows only); columns: scipy.fft in place
            # (overwrite_x on a complex array writes into it), with the backend's threads
            sf, w = self.backend.fft, self.backend.workers
            col, back = self._bufs(tuple(p.shape[:-2]))
            np.fft.rfft(p, n=2 * nx, axis=-1, out=col[..., :ny, :])
            col[..., ny:, :] = 0.0
            r = sf.fft(col, axis=-2, overwrite_x=True, workers=w)
            if not np.shares_memory(r, col):  # pragma: no cover - scipy always works in place
                col[...] = r
            np.multiply(col, mult, out=col)
            r = sf.ifft(col, axis=-2, overwrite_x=True, workers=w)
            if not np.shares_memory(r, col):  # pragma: no cover
                col[...] = r
            np.fft.irfft(col[..., :ny, :], n=2 * nx, axis=-1, out=back)
            res = back[..., :ny, :nx]
            if out is None:
                return res.copy()
            out[...] = res
            return out
        b = self.backend
        ph = b.rfft2(p, s=self.shape2)
        ph *= mult
        res = b.irfft2(ph, s=self.shape2)[..., :ny, :nx]
        if out is None:
            return res
        out[...] = res
        return out

    def __call__(self, p, out=None):
        """``K * p``; written into ``out`` when given (no allocation on the buffered path)."""
        return self._apply(p, self.khat, out)

    # the quarter-plane operator of problems symmetric about the centre cell ------------------
    @property
    def quadrant_shape(self) -> tuple[int, int]:
        """``(My, Mx)``: cells of the quarter plane ``x, y >= 0`` (the centre cell included)."""
        return (self.ny - self.ny // 2, self.nx - self.nx // 2)

    def _sym_setup(self):
        """The kernel's and preconditioner's DCT-I multipliers (built once): the real transform
        of the (even) circulant at ``k = 0..n`` (the quadrant's 2-D DCT-I), scaled by the
        inverse DCT-I's ``1 / (2n)`` per axis."""
        if self._khat_sym is None:
            norm = 1.0 / (4 * self.nx * self.ny)
            if self._quadrant is not None:
                kh = self.backend.fft.dctn(self._quadrant, type=1, axes=(-2, -1))
                mh = _inverse(kh, np)
            else:
                kh = np.ascontiguousarray(self.khat.real[..., : self.ny + 1, :])
                mh = np.ascontiguousarray(self.mhat.real[..., : self.ny + 1, :])
            self._khat_sym, self._mhat_sym = kh * norm, mh * norm
        return self._khat_sym, self._mhat_sym

    def _apply_sym(self, p, mult, out):
        """``K * p`` on the quarter plane, for ``p`` even in ``x`` and ``y`` about the centre cell.

        The zero-padded pressure of period ``2n`` is then whole-sample symmetric, and so is the
        (even) circulant kernel: the cyclic convolution is diagonal in the DCT-I of length
        ``n + 1`` (Martucci, IEEE Trans. Signal Process. 42 (1994) 1038), the real transform of
        the same ``2n``-periodic sequences. The ``My`` non-zero rows are transformed along
        ``x``, then all ``nx + 1`` columns along ``y``; in place in one buffer per batch shape.
        Half the transform work of :meth:`_apply` (real, and half the rows) on a quarter of the
        cells; the same operator to round-off.
        """
        sf, w = self.backend.fft, self.backend.workers
        My, Mx = self.quadrant_shape
        lead = tuple(p.shape[:-2])
        buf = self._sym_buffers.get(lead)
        if buf is None:
            buf = self._sym_buffers[lead] = np.empty((*lead, self.ny + 1, self.nx + 1))
        top = buf[..., :My, :]
        top[..., :Mx] = p
        top[..., Mx:] = 0.0
        _dct1(sf, top, -1, w)
        buf[..., My:, :] = 0.0
        _dct1(sf, buf, -2, w)
        np.multiply(buf, mult, out=buf)
        _dct1(sf, buf, -2, w)
        R, C = out.shape[-2:]  # My x Mx, or up to the cells without mirror image
        top = buf[..., :R, :]
        _dct1(sf, top, -1, w)
        out[...] = top[..., :C]
        return out

    def quarter(self, p, out):
        """``K * p`` on the quarter plane (``p``: ``(..., My, Mx)``, even about the centre
        cell; the DCT-I convolution of ``_apply_sym``), written into ``out``: ``(..., My, Mx)``, or
        ``(..., ny//2 + 1, nx//2 + 1)`` to include the cells without mirror image (their
        images at ``+n/2``; ``_unfold`` makes the whole grid of it)."""
        return self._apply_sym(p, self._sym_setup()[0], out)

    def precondition_quarter(self, r, out):
        """:meth:`precondition` on the quarter plane of an even ``r``."""
        return self._apply_sym(r, self._sym_setup()[1], out)

    def add_cells_quarter(self, u, k: int, iy, ix, c, tmp) -> None:
        """:meth:`add_cells` on the quarter plane: quadrant cell ``(i, j)`` stands for its
        mirror images ``(+-i, +-j)`` (one per axis where the index is 0). ``tmp``: ``(My, Mx)``."""
        G = self.prepare_cells()[k if self._G.shape[0] > 1 else 0]
        My, Mx = self.quadrant_shape
        y0, x0 = self.ny - 1, self.nx - 1  # G's row and column of offset 0
        for i, j, cj in zip(iy, ix, c, strict=True):
            rows = [y0 - i] + ([y0 + i] if i else [])  # offsets a - i and a + i
            cols = [x0 - j] + ([x0 + j] if j else [])
            for r0 in rows:
                for c0 in cols:
                    np.copyto(tmp, G[r0 : r0 + My, c0 : c0 + Mx])
                    tmp *= cj
                    u[k] += tmp

    def precondition(self, r, out=None):
        """``K^-1 r`` on the padded grid: the exact inverse of the (unrestricted, cyclic)
        convolution, an approximate inverse of the operator restricted to the contact."""
        return self._apply(r, self.mhat, out)

    def prepare_cells(self):
        """The kernel by offset, ``G[., ny - 1 + dy, nx - 1 + dx]`` (built once)."""
        if self._G is None:
            if self._quadrant is not None:
                oy = np.abs(np.arange(-(self.ny - 1), self.ny))
                ox = np.abs(np.arange(-(self.nx - 1), self.nx))
                G = self._quadrant[..., oy[:, None], ox[None, :]]
            else:
                kc = self.backend.to_numpy(self._kc)
                oy = np.arange(-(self.ny - 1), self.ny) % self.shape2[0]
                ox = np.arange(-(self.nx - 1), self.nx) % self.shape2[1]
                G = kc[..., oy[:, None], ox[None, :]]
            self._G = G if G.ndim == 3 else G[None]
        return self._G

    def add_cells(self, u, k: int, iy, ix, c, tmp) -> None:
        """``u[k] += sum_j c_j K(. - cell_j)`` for a few cells ``(iy_j, ix_j)`` of problem ``k``.

        ``tmp`` is an ``(ny, nx)`` scratch array. Exact (no transform round-off); costs three
        passes over the grid per cell.
        """
        G = self.prepare_cells()[k if self._G.shape[0] > 1 else 0]
        ny, nx = self.ny, self.nx
        for i, j, cj in zip(iy, ix, c, strict=True):
            # copy first: a ufunc on the strided view would allocate an iteration buffer
            np.copyto(tmp, G[ny - 1 - i : 2 * ny - 1 - i, nx - 1 - j : 2 * nx - 1 - j])
            tmp *= cj
            u[k] += tmp


#: A start ``p_init`` counts as even about the centre cell when its mirror images differ by at
#: most this fraction of its peak (round-off of a solution on the whole grid: ~1e-15).
EVEN_TOL = 1e-12


def _is_even(p, ny: int, nx: int) -> bool:
    """Whether ``p`` (``(..., ny, nx)``) is even in ``y`` and ``x`` about the centre cell to
    :data:`EVEN_TOL` of its peak, and 0 on the cells without a mirror image. A start prolonged
    from a contact that reaches the edge of a coarser grid is not (the edge cells there are
    extrapolated on one side, interpolated towards 0 on the other); the whole grid takes it."""
    p = np.asarray(p)
    cy, cx = ny // 2, nx // 2
    top = float(np.max(np.abs(p))) if p.size else 0.0
    if top == 0.0:
        return True
    lim = EVEN_TOL * top
    if (ny % 2 == 0 and np.max(np.abs(p[..., 0, :])) > lim) or (
            nx % 2 == 0 and np.max(np.abs(p[..., :, 0])) > lim):
        return False
    My, Mx = ny - cy, nx - cx
    dy = p[..., cy + 1 :, :] - p[..., cy - My + 1 : cy, :][..., ::-1, :]
    dx = p[..., :, cx + 1 :] - p[..., :, cx - Mx + 1 : cx][..., ::-1]
    return bool(np.max(np.abs(dy), initial=0.0) <= lim and np.max(np.abs(dx), initial=0.0) <= lim)


def _unfold(q: np.ndarray, ny: int, nx: int) -> np.ndarray:
    """The whole ``(B, ny, nx)`` field, even about the centre cell, from its quarter plane
    ``q``: ``(B, My, Mx)`` (cells ``y, x >= 0``; the cells without a mirror image are then 0)
    or ``(B, ny//2 + 1, nx//2 + 1)`` (with those cells' values at their images ``+n/2``)."""
    cy, cx = ny // 2, nx // 2
    My, Mx = ny - cy, nx - cx
    e = np.zeros((*q.shape[:-2], cy + 1, cx + 1))
    e[..., : q.shape[-2], : q.shape[-1]] = q
    rows = np.empty((*q.shape[:-2], ny, cx + 1))
    rows[..., cy:, :] = e[..., :My, :]
    rows[..., :cy, :] = e[..., cy:0:-1, :]
    f = np.empty((*q.shape[:-2], ny, nx))
    f[..., cx:] = rows[..., :Mx]
    f[..., :cx] = rows[..., cx:0:-1]
    return f


def _inverse(kh, xp):
    """The preconditioner's multiplier from the kernel's (real) transform ``kh``: its inverse,
    scaled by the largest value and floored at :data:`PRECONDITION_FLOOR` of it."""
    top = kh.max(axis=(-2, -1), keepdims=True)
    return top / xp.maximum(kh, PRECONDITION_FLOOR * top)


def _dct1(sf, a, axis: int, workers) -> None:
    """Unnormalised DCT-I of ``a`` along ``axis``, in place."""
    r = sf.dct(a, type=1, axis=axis, overwrite_x=True, workers=workers)
    if not np.shares_memory(r, a):  # pragma: no cover - scipy works in place
        a[...] = r


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
    symmetric: bool = False,
    callback: Callable[[int], None] | None = None,
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
        Iteration cap; not converging within it raises :class:`~coathertz.errors.ConvergenceError`.
    p_init
        Initial pressure (any non-negative field; rescaled to the load), default uniform.
    precondition
        Precondition the CG direction with the inverse of the kernel
        (:meth:`Convolver.precondition`): the exact inverse of the operator on the whole
        padded grid, so that only the restriction to the contact set and the changes of that
        set are left to CG. Each iteration costs one more transform pair; the iterations
        stay flat in ``n`` and in the layer (6-15 at n = 128-512 over 30 cases of the paper's
        families, against 9-38 without, growing with ``n``), and at equal ``tol`` the
        solution is closer to the converged one (four coated cases at n = 128, ``tol`` 1e-6:
        within 1.3e-9 in delta and 1.4e-8 in p0 of the solution at 1e-12; without: 1.1e-8
        and 8.9e-7).
    symmetric
        The problems are even in ``x`` and in ``y`` about the centre cell ``(ny//2, nx//2)``
        (``g0`` and the kernel; ``p_init`` is read on the quarter plane ``x, y >= 0``): iterate
        on that quarter plane (numpy backend; :meth:`Convolver.quarter`), with every sum over
        the grid weighted by the cell's mirror images (2 per axis off the centre line). The
        iteration is the same as on the whole grid to round-off, as long as the cells without
        a mirror image (row and column 0 of an even ``n``) stay out of contact; the result is
        measured on the whole grid, and where such a cell ends up penetrating, the solve goes
        on on the whole grid from there. At n = 128 an iteration costs about 0.45 of one on
        the whole grid (half the transform work, a quarter of the cells).
    callback
        Called with the iteration number at the start of each iteration (diagnostics; the
        allocation test uses it).
    """
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
    B = max(W.shape[0], conv.kernel_batch)
    if g0.ndim == 3:
        B = max(B, g0.shape[0])
    W = xp.broadcast_to(W, (B,)).copy()
    ax = (-2, -1)
    sym = bool(symmetric) and b.name == "numpy" and (p_init is None or _is_even(p_init, ny, nx))
    g0_full = g0
    if sym:
        cy, cx = ny // 2, nx // 2
        My, Mx = conv.quadrant_shape
        shape = (B, My, Mx)
        # mirror images of each quarter-plane cell: 1 on the centre lines, else 2 per axis
        wts = np.outer(np.where(np.arange(My) > 0, 2.0, 1.0), np.where(np.arange(Mx) > 0, 2.0, 1.0))
        g0 = np.ascontiguousarray(g0[..., cy:, cx:])
        if p_init is not None:
            p_init = np.asarray(p_init)[..., cy:, cx:]
        apply, precond, add_cells = conv.quarter, conv.precondition_quarter, conv.add_cells_quarter

        def bsum(a):
            return np.einsum("bij,ij->b", a, wts)

        def bdot(a, c):
            return np.einsum("bij,bij,ij->b", a, c, wts)
    else:
        shape = (B, ny, nx)
        apply, precond, add_cells = conv, conv.precondition, conv.add_cells

        def bsum(a):
            return a.sum(axis=ax)

        def bdot(a, c):
            return xp.einsum("bij,bij->b", a, c)

    def col(v):
        return v[:, None, None]

    # work buffers, allocated once: nothing of grid size is allocated inside the iteration
    # (numpy backend with one FFT thread; see Convolver)
    p = xp.empty(shape)
    p[...] = 1.0 if p_init is None else b.asarray(p_init)
    xp.maximum(p, 0.0, out=p)
    p *= col(W / (bsum(p) * cell_area))
    u = xp.empty(shape)
    apply(p, out=u)
    nconv = 1
    t = xp.zeros(shape)
    p_old = xp.empty(shape)
    gap = xp.empty(shape)
    gm = xp.empty(shape)
    m = xp.empty(shape)
    r_raw = xp.empty(shape)
    z = xp.empty(shape) if precondition else gm
    tmp = xp.empty(shape)
    mask = xp.empty(shape, dtype=bool)
    mask2 = xp.empty(shape, dtype=bool)
    cell_tmp = np.empty(shape[1:]) if b.name == "numpy" else None
    if cell_tmp is not None:
        conv.prepare_cells()
    max_cells = MAX_DIRECT_CELLS
    G_old = xp.ones(B)
    restart = xp.ones(B, dtype=bool)
    done = xp.zeros(B, dtype=bool)
    iters = xp.zeros(B, dtype=int)
    eps = xp.full(B, np.inf)
    for it in range(1, max_iter + 1):
        if callback is not None:
            callback(it)
        xp.add(u, g0, out=gap)
        xp.greater(p, 0.0, out=mask)
        m[...] = mask
        n_in = bsum(m)
        gap -= col(bdot(gap, m) / n_in)
        xp.multiply(gap, m, out=gm)
        if precondition:
            precond(gm, out=z)
            nconv += 1
            z *= m
            z -= col(bdot(z, m) / n_in)
            z *= m
            G = bdot(gm, z)
        else:
            G = bdot(gm, gap)
        beta = xp.where(restart, 0.0, G / xp.where(G_old == 0, 1.0, G_old))
        t *= col(beta)
        t *= m
        t += z
        G_old = G
        apply(t, out=r_raw)
        nconv += 1
        rt = bdot(r_raw, t) - bdot(r_raw, m) / n_in * bsum(t)
        tau = bdot(gm, t) / xp.where(rt == 0, 1.0, rt)
        tau = xp.where(done, 0.0, tau)
        p_old[...] = p
        # p <- p - tau t, then projections: clip negative pressures, re-activate overlaps
        xp.multiply(t, col(tau), out=tmp)
        p -= tmp
        pre = gm  # gm is free until the next iteration: keep p before the projections
        pre[...] = p
        xp.less(p, 0.0, out=mask)
        changed = bool(mask.any())
        xp.maximum(p, 0.0, out=p)
        xp.less(gap, 0.0, out=mask)
        xp.equal(p, 0.0, out=mask2)
        mask &= mask2
        restart = mask.any(axis=ax)
        if bool(restart.any()):
            changed = True
            xp.multiply(gap, col(tau), out=tmp)
            if b.name == "numpy":
                xp.subtract(p, tmp, out=p, where=mask)
            else:
                p[...] = xp.where(mask, p - tmp, p)
        scale = W / (bsum(p) * cell_area)
        u_stepped = False
        if changed and it % REFRESH != 0 and cell_tmp is not None:
            # the projections changed a few cells by c: u <- s (u - tau K t + K c), K c summed
            # directly (cheaper than a transform pair for a few cells)
            xp.not_equal(p, pre, out=mask)
            tmp[...] = mask  # counted in floats: a bool -> int sum allocates a cast buffer
            if int(bsum(tmp).max()) <= max_cells:
                xp.multiply(r_raw, col(tau), out=tmp)
                u -= tmp
                for k in range(B):
                    iy, ix = np.nonzero(mask[k])
                    if iy.size:
                        add_cells(u, k, iy, ix, p[k, iy, ix] - pre[k, iy, ix], cell_tmp)
                changed, u_stepped = False, True
        p *= col(scale)
        if changed or it % REFRESH == 0:
            apply(p, out=u)
            nconv += 1
        else:
            if not u_stepped:
                xp.multiply(r_raw, col(tau), out=tmp)
                u -= tmp
            u *= col(scale)
        xp.subtract(p, p_old, out=tmp)
        xp.abs(tmp, out=tmp)
        eps = bsum(tmp) * cell_area / W
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
    if sym:  # back on the whole grid: the mirror images, measured there
        g0 = g0_full
        edge_u = np.empty((B, ny // 2 + 1, nx // 2 + 1))
        conv.quarter(p, edge_u)
        u = _unfold(edge_u, ny, nx)
        p = _unfold(p, ny, nx)
    else:
        u = conv(p)
    nconv += 1
    gap = u + g0
    inside = p > 0
    n_in = inside.sum(axis=ax)
    delta = (gap * inside).sum(axis=ax) / n_in
    gap = gap - col(delta)
    # the cells without a mirror image (row 0 of an even ny, column 0 of an even nx) were held
    # at p = 0: where one penetrates, the quarter-plane problem is not the whole one; go on on
    # the whole grid from here
    edges = ([gap[:, 0, :]] if ny % 2 == 0 else []) + ([gap[:, :, 0]] if nx % 2 == 0 else [])
    if sym and any(bool((e < 0).any()) for e in edges):
        full = polonsky_keer(conv, g0_full, W, cell_area, tol=tol, max_iter=max_iter,
                             p_init=p, precondition=precondition, callback=callback)
        full.iterations = full.iterations + iters
        full.convolutions += nconv
        full.wall_time = time.perf_counter() - t0
        return full
    scale_d = xp.abs(delta)
    residual = xp.sqrt((gap * gap * inside).sum(axis=ax) / n_in) / scale_d
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
