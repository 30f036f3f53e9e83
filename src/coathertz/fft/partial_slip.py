"""Partial slip under a tangential load ``Q < mu W`` on the FFT grid (Cattaneo--Mindlin).

The pressure ``p`` is the frictionless normal solution (Goodman's approximation: the
normal--tangential coupling through elastic dissimilarity, ``(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2``,
is neglected; its effect, measured with :mod:`coathertz.fft.coupling` for a rigid sphere on
steel, beta = 0.286, at Q = 0.5 mu W: -1.7 % in the tangential displacement, the stick radius
within a cell). The shear traction ``q`` acts along the load direction ``e`` only; in the stick
zone the relative tangential displacement along ``e`` is a rigid shift ``delta``, in the slip
zone ``|q| = mu p``. Surface compliance of a homogeneous half-space to a shear traction
(Cerruti, in Fourier form, Johnson 1985 sec. 3.2)::

    u_e(k) = sum_i (1 / G_i) (1 - nu_i (k . e)^2 / |k|^2) q(k) / |k|

(both bodies add; a rigid body adds nothing). A coated body adds its layered compliance
(:func:`surface_compliance`, from the tangential-load solution of
:class:`~coathertz.fft.stresses.CoatedStressFRF`): partial slip on coated bodies. Measured
(``tests/stresses/test_coated_partial_slip.py``): E = 4, h = 0.24 a on steel, Q = 0.5 mu W on
the coated pressure: stick radius 0.824 a against 0.847 a with any half-space compliance on the
same pressure (n = 64). The cell tractions are constant per cell
(transform ``sinc sinc``), zero padded to ``pad`` domain widths. The problem on the contact
cells is solved with a dense compliance matrix and an active set: stick cells solve
``C q = delta`` with ``sum q dA = Q``; cells with ``|q| > mu p`` go to slip at ``mu p``, slip
cells whose slip does not oppose ``q`` go back to stick, until the sets stop changing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft as sfft

from coathertz.errors import CoatHertzError
from coathertz.fft.grid import Grid

#: Largest number of contact cells of the dense solve (its matrix: 69 MiB; an LU of it about a
#: second): about a 64 x 64 FFT grid around a circular contact (2060 cells).
MAX_CONTACT_CELLS = 3000


@dataclass(frozen=True)
class PartialSlip:
    """Tangential traction ``q`` [Pa] along the load direction, stick mask, shift ``delta`` [m]."""

    q: np.ndarray
    stick: np.ndarray
    delta: float
    iterations: int


def surface_compliance(body, w: np.ndarray, ke2: np.ndarray) -> np.ndarray:
    """``|k|`` times the surface displacement along the load direction ``e`` per unit shear
    traction along ``e`` of one body [1/Pa], at wavenumbers ``w`` [1/m] with
    ``ke2 = (k . e)^2 / |k|^2``.

    ``body``: ``(G, nu)`` of a homogeneous half-space (Cerruti: ``(1 - nu ke2) / G``) or a
    :class:`~coathertz.fft.stresses.CoatedStressFRF` (a coating of thickness ``h`` on its
    substrate). For the coating the in-plane part along ``k`` comes from the tangential-load
    coefficients ``A, C`` of the Papkovich--Neuber solution (``2 G_c u_k(0) = A + C e^{-w h}``
    per unit traction and ``1/|k|``; the homogeneous half-space has ``A = 2 (1 - nu)``, ``C = 0``)
    and the antiplane part normal to ``k`` from ``G_c U(0) = alpha + beta e^{-w h}``:
    ``ke2 (A + C e^{-wh}) / (2 G_c) + (1 - ke2) (alpha + beta e^{-wh}) / G_c``. Both tend to
    the substrate's half-space values as ``w h -> 0`` and to the coating's as ``w h -> inf``.
    """
    if isinstance(body, tuple):
        G, nu = body
        return (1 - nu * ke2) / G
    Gc = body.layer.coating.G
    cc = body.coefficients(np.maximum(w, 1e-300))
    x, xa = cc.x, cc.xa
    e = np.exp(-np.asarray(w) * body.h)
    inplane = (x[..., 0, 1] + x[..., 2, 1] * e) / (2 * Gc)
    antiplane = (xa[..., 0] + xa[..., 1] * e) / Gc
    return ke2 * inplane + (1 - ke2) * antiplane


def _compliance(grid: Grid, bodies, direction: float, pad: int):
    ny, nx = grid.shape
    Ny, Nx = pad * ny, pad * nx
    kx = 2 * np.pi * sfft.fftfreq(Nx, grid.dx)[None, :]
    ky = 2 * np.pi * sfft.fftfreq(Ny, grid.dy)[:, None]
    w = np.hypot(kx, ky)
    safe = np.where(w > 0, w, 1.0)
    ke = (np.cos(direction) * kx + np.sin(direction) * ky) / safe
    K = np.zeros_like(w)
    for body in bodies:
        K = K + surface_compliance(body, w, ke**2)
    K = np.where(w > 0, K / safe, 0.0)
    K = K * np.sinc(kx * grid.dx / (2 * np.pi)) * np.sinc(ky * grid.dy / (2 * np.pi))
    return K, (Ny, Nx)


def solve_partial_slip(p: np.ndarray, grid: Grid, bodies, Q: float, mu: float,
                       direction: float = 0.0, pad: int = 2, max_iter: int = 200,
                       offset: np.ndarray | None = None) -> PartialSlip:
    """Cattaneo--Mindlin partial slip on the cell pressure ``p`` [Pa].

    Parameters
    ----------
    bodies
        Each deformable body: ``(G, nu)`` of a homogeneous one (shear modulus [Pa], Poisson's
        ratio) or the :class:`~coathertz.fft.stresses.CoatedStressFRF` of a coated one
        (:func:`surface_compliance`).
    Q
        Tangential load [N], ``0 <= Q < mu W``.
    mu
        Coulomb friction coefficient, ``> 0``.
    direction
        Load direction [rad] from x.
    offset
        Relative tangential displacement [m] along the load direction that the traction ``q``
        does not cause (shape ``grid.shape``; ``None``: zero): added to ``C q`` in the stick
        condition and the slip test. The normal--tangential coupling of dissimilar bodies enters
        here (:mod:`coathertz.fft.coupling`).
    """
    if not (np.isfinite(mu) and mu > 0):
        raise CoatHertzError(f"friction coefficient mu must be > 0 for partial slip, got {mu!r}")
    if not (np.isfinite(Q) and Q >= 0):
        raise CoatHertzError(f"tangential load Q must be >= 0 [N], got {Q!r}")
    dA = grid.dx * grid.dy
    W = float(np.sum(p)) * dA
    if Q >= mu * W:
        raise CoatHertzError(
            f"tangential load Q = {Q:g} N >= mu W = {mu * W:g} N: the contact slides "
            "(full sliding, q = mu p; partial slip needs Q < mu W)")
    idx = np.flatnonzero(p.ravel() > 0)
    n = idx.size
    if n > MAX_CONTACT_CELLS:
        raise CoatHertzError(
            f"partial slip: {n} contact cells; the dense active-set solve takes at most "
            f"{MAX_CONTACT_CELLS} ({MAX_CONTACT_CELLS**2 * 8 / 2**20:.0f} MiB): use a coarser grid "
            f"(--grid {int(grid.shape[1] * (MAX_CONTACT_CELLS / n) ** 0.5) // 8 * 8} or less for this "
            "contact)")
    if offset is not None and np.shape(offset) != p.shape:
        raise CoatHertzError(f"offset shape {np.shape(offset)} does not match the pressure {p.shape}")
    off = np.zeros(n) if offset is None else np.asarray(offset, dtype=float).ravel()[idx]
    K, (Ny, Nx) = _compliance(grid, bodies, direction, pad)
    ny, nx = grid.shape
    # the compliance is a convolution: one inverse transform gives the response at every offset,
    # and the dense matrix of the contact cells is that response read at their offsets
    g = np.real(sfft.ifft2(K))
    iy, ix = np.divmod(idx, nx)
    C = g[(iy[:, None] - iy[None, :]) % Ny, (ix[:, None] - ix[None, :]) % Nx]
    bound = mu * p.ravel()[idx]
    stick = np.ones(n, dtype=bool)
    q = np.zeros(n)
    delta = 0.0
    for it in range(1, max_iter + 1):
        s = np.flatnonzero(stick)
        sl = np.flatnonzero(~stick)
        q[sl] = bound[sl] * np.where(q[sl] < 0, -1.0, 1.0)  # slip: |q| = mu p, sign kept
        m = s.size
        A = np.zeros((m + 1, m + 1))
        A[:m, :m] = C[np.ix_(s, s)]
        A[:m, m] = -1.0
        A[m, :m] = dA
        rhs = np.concatenate([-C[np.ix_(s, sl)] @ q[sl] - off[s], [Q - dA * q[sl].sum()]])
        x = np.linalg.solve(A, rhs)
        q[s], delta = x[:m], x[m]
        slip = C @ q + off - delta  # relative displacement minus the rigid shift
        over = stick & (np.abs(q) > bound)
        back = ~stick & (slip * q > 0)  # slip running with the traction: not admissible
        if not over.any() and not back.any():
            iterations = it
            break
        stick = (stick & ~over) | back
    else:
        raise CoatHertzError(f"partial slip: active set did not settle in {max_iter} iterations")
    qf = np.zeros(ny * nx)
    qf[idx] = q
    st = np.zeros(ny * nx, dtype=bool)
    st[idx] = stick
    return PartialSlip(qf.reshape(ny, nx), st.reshape(ny, nx), float(delta), iterations)
