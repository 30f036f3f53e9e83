"""Uniform computational grids for the DC-FFT solver, chosen from the Hertz estimate.

One resolution knob: ``n``, the number of cells along each side of the (rectangular) domain.
The domain is centred on the first point of contact and its half-widths are
``margin * (estimated semi-axis)``, so that the contact radius gets ``n / (2 margin)`` cells.

Estimate of the semi-axes
-------------------------
A coated contact on elastic substrates normally lies between the Hertz contacts of its two limits
(coatings removed, ``a0s``; coatings as half-spaces, ``a0c``), so the grid is first sized on the
larger of the two; all ``H`` of one material pair then share a grid (fast sweeps). The contact
is often smaller than that estimate (a stiff thick coating: ``a`` near ``a0c < a0s``; a soft
coating: near ``a0s < a0c``; a thin layer on a rigid base: much smaller than ``a0c``), and its
radius would get fewer cells than the nominal ``n / (2 margin)``. The solver therefore checks
the contact (``FFTMethod(adapt=True)``) and re-grids on it when its extent is less than
``REFIT_BELOW`` of the estimated semi-axis or when it comes within two cells of the boundary
(then the estimate grows 1.5x): the domain contains the contact with margin at every ``H``.
The contact of the nested start's coarse solve decides this before the fine solve (in a sweep
with warm starts, the previous case's contact does), so a re-grid costs about a coarse solve;
the fine solve is repeated only when its own contact fills less than ``RESOLVE_BELOW`` of the
new estimate (or touches the boundary). The radius thus gets at least
``RESOLVE_BELOW n / (2 margin)`` cells (43 at the defaults; normally 46 or more).

The error of the sub-cell radius falls like the square of the cell size, so this uniform
resolution matters: with the former ``REFIT_BELOW = 0.5`` (radii with 26-51 cells at
n = 128) the largest error in ``a`` over 23 of the 24 coated cases of
``tests/fft/test_radius.py`` was 0.103 %, with 0.9 it is 0.051 % (the 24th, a coating half a
cell thick, is limited by the layer: see :data:`coathertz.fft.method.LAYER_CELLS_MIN`).

Anisotropic spacing
-------------------
``spacing_ratio = dy/dx``. ``None`` gives square cells for circular contacts and, for
ellipses, ``dy/dx = r_b/r_a`` (the same number of cells across both semi-axes); the paper's
elliptical study uses ``dy = dx/3`` (``spacing_ratio=1/3``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from coathertz.errors import CoatHertzError

N_MIN, N_MAX = 16, 4096
DEFAULT_N = 128
DEFAULT_MARGIN = 1.25
REFIT_BELOW = 0.9
#: After the fine solve, the solve is repeated on a new grid only below this fill (hysteresis:
#: a contact at 0.89 of the estimate on the coarse start and 0.91 on the fine grid, or the
#: reverse, does not cost a second fine solve).
RESOLVE_BELOW = 0.85


@dataclass(frozen=True)
class Grid:
    """``nx x ny`` cells of ``dx x dy`` [m]; cell ``(nx//2, ny//2)`` is centred on the origin."""

    nx: int
    ny: int
    dx: float
    dy: float

    def __post_init__(self) -> None:
        for name in ("nx", "ny"):
            v = getattr(self, name)
            if not isinstance(v, int | np.integer) or isinstance(v, bool) or not (
                N_MIN <= v <= N_MAX
            ):
                raise CoatHertzError(
                    f"grid size {name} must be an integer in [{N_MIN}, {N_MAX}], got {v!r}"
                )
        for name in ("dx", "dy"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise CoatHertzError(f"grid spacing {name} must be finite and > 0 [m], got {v!r}")

    @property
    def shape(self) -> tuple[int, int]:
        return (self.ny, self.nx)

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    @property
    def half_widths(self) -> tuple[float, float]:
        """Distance from the origin to the nearest domain edge along x and y [m]."""
        return ((self.nx // 2 - 0.5) * self.dx, (self.ny - self.ny // 2 - 0.5) * self.dy)

    @cached_property
    def x(self) -> np.ndarray:
        return (np.arange(self.nx) - self.nx // 2) * self.dx

    @cached_property
    def y(self) -> np.ndarray:
        return (np.arange(self.ny) - self.ny // 2) * self.dy

    def key(self) -> tuple:
        return (self.nx, self.ny, float(self.dx), float(self.dy))

    def describe(self) -> dict:
        return {"nx": self.nx, "ny": self.ny, "dx": self.dx, "dy": self.dy}


def check_n(n) -> int:
    """Validate the resolution knob."""
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not (N_MIN <= n <= N_MAX):
        raise CoatHertzError(f"grid n must be an integer in [{N_MIN}, {N_MAX}], got {n!r}")
    return int(n)


def grid_for_axes(
    r_a: float,
    r_b: float,
    n: int = DEFAULT_N,
    margin: float = DEFAULT_MARGIN,
    spacing_ratio: float | None = None,
) -> Grid:
    """Grid of ``n x n`` cells whose domain contains the ellipse ``r_a x r_b`` with ``margin``.

    Parameters
    ----------
    r_a, r_b
        Estimated semi-axes along x and y [m].
    n
        Cells along each side (resolution knob), ``16 <= n <= 4096``.
    margin
        Domain half-width over semi-axis, ``margin > 1``.
    spacing_ratio
        ``dy/dx``; ``None``: ``r_b/r_a`` (square cells for circles).
    """
    n = check_n(n)
    if not (isinstance(margin, int | float) and 1.0 < margin <= 10.0):
        raise CoatHertzError(f"grid margin must satisfy 1 < margin <= 10, got {margin!r}")
    for name, v in (("r_a", r_a), ("r_b", r_b)):
        if not (math.isfinite(v) and v > 0):
            raise CoatHertzError(f"estimated semi-axis {name} must be finite and > 0, got {v!r}")
    ratio = r_b / r_a if spacing_ratio is None else spacing_ratio
    if not (isinstance(ratio, int | float) and 1e-3 <= ratio <= 1e3):
        raise CoatHertzError(f"spacing_ratio dy/dx must be in [1e-3, 1e3], got {spacing_ratio!r}")
    half = n / 2 - 0.5
    dx = margin * max(r_a, r_b / ratio) / half
    return Grid(n, n, dx, dx * ratio)


def fast_n(n: int) -> int:
    """The smallest even ``m >= n`` without a prime factor above 5: the padded transforms
    (length ``2m``) then run on pocketfft's fast radices. A refinement's ``n`` comes from the
    coating's thickness and can have a large prime factor; one transform pair (one thread, 2
    shared cores) took 15.1 ms at n = 262 (2 x 131) against 4.1 ms at 270, and 16.0 ms at
    376 (8 x 47) against 7.7 ms at 384."""
    m = max(2, int(n) + int(n) % 2)
    while True:
        k = m
        for f in (2, 3, 5):
            while k % f == 0:
                k //= f
        if k == 1:
            return m
        m += 2
