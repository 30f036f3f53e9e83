r"""The reduced material coordinates of a bonded coating on an elastic substrate.

The layered kernel of eq (13) depends on the two materials only through :math:`\lambda` and
:math:`\kappa` (:func:`coathertz.materials.lam_kappa`) and :math:`k h`: the compliance
normalised by :math:`E_c^*` is

.. math::

    \frac{1 + 4kh\kappa e^{-2kh} - \lambda\kappa e^{-4kh}}
         {1 - (\lambda + \kappa + 4\kappa k^2h^2) e^{-2kh} + \lambda\kappa e^{-4kh}},

whose :math:`kh \to 0` limit gives :math:`E = E_c^*/E_s^* = (1-\lambda\kappa)/((1-\lambda)(1-\kappa))`.
So for a rigid indenter every bar of eq (7a) is a function of three variables
:math:`(H, \lambda, \kappa)`, not four :math:`(H, E, \nu_c, \nu_s)` (checked against the exact
method to 1e-15 in ``tests/refit/test_reduced.py``).

The pair :math:`(\lambda, \kappa)` is equivalent to Dundurs' parameters

.. math::

    \alpha_D = \frac{E - 1}{E + 1}, \qquad
    \beta_D = \frac{1}{2}\,\frac{\Gamma(1 - 2\nu_s) - (1 - 2\nu_c)}{\Gamma(1 - \nu_s) + (1 - \nu_c)},
    \qquad \Gamma = G_c/G_s,

(Dundurs 1969; Barber, *Elasticity*, eq 12.13), and the image of the box
:math:`\nu_c, \nu_s \in [0, 1/2]` at fixed :math:`E` is the whole segment
:math:`\beta_D \in [(\alpha_D - 1)/4, (\alpha_D + 1)/4]` of Dundurs' parallelogram. The
normalised second coordinate

.. math::

    s = \frac{4\beta_D - \alpha_D + 1}{2} \in [0, 1]

therefore maps the four-dimensional box onto the rectangle
:math:`(\log_{10} H, \log_{10} E, s)`: s = 0 at (nu_c, nu_s) = (0, 1/2) and s = 1 at (1/2, 0)
for every E. :func:`poisson_of` returns one pre-image (on the anti-diagonal
nu_c + nu_s = 1/2) of a point of the rectangle, for building design grids.
"""

from __future__ import annotations

import numpy as np

from coathertz.closedform.extended import mu_from_ratio
from coathertz.errors import CoatHertzError


def dundurs(E, nu_c, nu_s) -> tuple[np.ndarray, np.ndarray]:
    """Dundurs' ``(alpha_D, beta_D)`` of a coating/substrate pair from E = Ec*/Es* and the
    Poisson's ratios (broadcast arrays)."""
    E, nu_c, nu_s = (np.asarray(v, dtype=float) for v in (E, nu_c, nu_s))
    G = mu_from_ratio(E, nu_c, nu_s)  # Gc/Gs, eq (13)
    beta = 0.5 * (G * (1.0 - 2.0 * nu_s) - (1.0 - 2.0 * nu_c)) / (G * (1.0 - nu_s) + (1.0 - nu_c))
    return (E - 1.0) / (E + 1.0), beta


def s_coordinate(E, nu_c, nu_s) -> np.ndarray:
    """The normalised second coordinate ``s = (4 beta_D - alpha_D + 1)/2`` in [0, 1]."""
    al, be = dundurs(E, nu_c, nu_s)
    return np.clip(0.5 * (4.0 * be - al + 1.0), 0.0, 1.0)


def poisson_of(E: float, s: float, tol: float = 1e-14) -> tuple[float, float]:
    """``(nu_c, nu_s)`` on the anti-diagonal ``nu_c + nu_s = 1/2`` with coordinate ``s`` at the
    modulus ratio ``E`` (bisection: s grows monotonically from 0 at (0, 1/2) to 1 at (1/2, 0))."""
    if not (0.0 <= s <= 1.0):
        raise CoatHertzError(f"s must lie in [0, 1], got {s!r}")
    if not (E > 0.0 and np.isfinite(E)):
        raise CoatHertzError(f"modulus ratio E = Ec*/Es* must satisfy 0 < E < inf, got {E!r}")
    lo, hi = 0.0, 0.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if float(s_coordinate(E, mid, 0.5 - mid)) < s:
            lo = mid
        else:
            hi = mid
        if hi - lo < tol:
            break
    nu_c = 0.0 if s == 0.0 else 0.5 if s == 1.0 else round(0.5 * (lo + hi), 13)
    return nu_c, 0.5 - nu_c
