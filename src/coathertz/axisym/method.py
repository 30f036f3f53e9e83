"""The exact axisymmetric method: :class:`AxisymMethod` (a :class:`coathertz.methods.Method`)."""

from __future__ import annotations

import contextlib
import math
import time
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np

from coathertz.axisym.edge import edge_basis
from coathertz.axisym.kernel import INTERFACES, pair_compliance
from coathertz.axisym.solver import (
    XiRule,
    direct_end,
    displacement,
    initial_radius,
    peak_pressure,
    pressure,
    pressure_shape,
    solve_load,
)
from coathertz.blas import blas_threads
from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.methods import require_case
from coathertz.results import ContactResult
from coathertz.validity import check as check_validity


def single_thread_blas() -> contextlib.AbstractContextManager:
    """Pin BLAS/LAPACK to one thread while solving (:func:`coathertz.blas.blas_threads`): the
    Galerkin systems are at most ~160 x 160 and the xi products ~160 x 10^4, where threaded BLAS
    only adds wake-up and contention costs (~480 ms per case against ~10 ms with one thread)."""
    return blas_threads(1)


#: Fewest and most automatic Legendre modes. Against 96 modes over 348 cases (E 0.1-10,
#: H 0.03-10, four Poisson pairs, and rigid substrates with H 0.03-10, nu_c 0-0.5) the automatic
#: rule with N_MIN = 16 and c_modes = 7 left p0 off by up to 3.2e-9 (1.66e-9 was reported
#: against an independent solution, at 16-32 modes), beyond the 1e-9 the method states; with
#: N_MIN = 32 and c_modes = 9 the largest differences were 1.5e-11 (p0), 2.2e-12 (a) and 2.5e-13
#: (delta), for 1.38 times the time of the 348 solves (1.43 s against 1.04 s, one core).
N_MIN, N_MAX = 32, 160


#: Edge functions (``edge=True``): scales from ``h / EDGE_FINE`` up to ``EDGE_COARSE / (2N - 2)^2``.
EDGE_FINE, EDGE_COARSE = 32.0, 200.0
#: Edge functions replace the Legendre rule where it would need more modes than this
#: (``h/a < (c_modes / EDGE_SWITCH)^2``, 0.0088 at the default ``c_modes``).
EDGE_SWITCH = 96
#: Below this ``h/a`` no edge functions: ``N_MIN`` Legendre modes with the energy edge condition
#: leave ``a`` off by ~0.17 h/a (measured from 1e-7 to 1e-9 against the first-order trend of the
#: enriched solutions: 8.5e-9 at 5e-8, 1.8e-9 at 1e-8), and the finest edge functions lose
#: accuracy in p0 (5e-9 at 1e-8).
EDGE_H_MIN = 2e-8


def modes_needed(tau: float, c_modes: float = 9.0) -> int:
    """Legendre modes for thickness ratio ``tau = h_min / a``: ``c_modes / sqrt(tau)`` (the
    boundary layer of width ~h at the contact edge needs ``N^2 ~ a/h``), rounded up to a
    multiple of 8 (so that cases share cached Bessel tables), at least ``N_MIN``."""
    if not math.isfinite(tau):
        return N_MIN
    return max(math.ceil(c_modes / math.sqrt(max(tau, 1e-12)) / 8.0) * 8, N_MIN)


def default_modes(tau: float, c_modes: float = 9.0) -> int:
    """:func:`modes_needed` capped at ``N_MAX`` (cost grows like ``N^2 a/h``)."""
    return min(modes_needed(tau, c_modes), N_MAX)


@dataclass(frozen=True)
class AxisymMethod:
    """Exact (semi-analytical) frictionless axisymmetric contact on layered bodies.

    Parameters
    ----------
    interface
        ``bonded`` (eq 13, the paper's model) or ``frictionless`` coating/substrate interface.
    n_modes
        Legendre modes ``P_0, P_2, ..., P_{2N-2}`` of the auxiliary function; ``None``: automatic
        from ``h/a`` (:func:`default_modes` with ``c_modes``).
    c_modes
        Constant of the automatic rule ``N = c_modes / sqrt(h/a)``.
    edge
        Thin layers (the automatic rule asking for more than ``EDGE_SWITCH`` modes:
        ``2e-8 <= h/a < 0.0088``): ``edge_modes`` Legendre modes (``n_modes`` if given)
        enriched with edge functions ``exp((r/a - 1) a/L_j)``, the scales ``L_j`` geometric with
        ratio ``edge_ratio`` from ``h/32`` up to the resolution of the Legendre modes
        (:mod:`coathertz.axisym.edge`), and the smooth edge as stationarity of the load
        (``edge_condition="energy"`` of :func:`~coathertz.axisym.solver.solve_at_radius`): cost
        and accuracy no longer depend on ``h``. ``None`` (default): with automatic modes only;
        ``False``: Legendre modes only (``N = c_modes / sqrt(h/a)``, capped at ``N_MAX``).
    edge_modes, edge_ratio
        Legendre modes and scale ratio of the edge functions with ``edge``.
    order, panel
        Gauss--Legendre nodes per panel and uniform panel width of the ``xi = k a`` quadrature.
    decay
        The ``xi`` integral stops at ``decay * a / h_min`` (``M`` ~ ``t^2 exp(-2 t)`` ~ 1e-10 there;
        the neglected tail changes the results by < 1e-10, measured).
    rtol
        Tolerance on ``|log W(a) - log W|`` of the load iteration.
    keep_fields
        Return ``r``, ``pressure`` and ``u_z`` profiles in ``ContactResult.fields``.
    """

    interface: str = "bonded"
    n_modes: int | None = None
    c_modes: float = 9.0
    edge: bool | None = None
    edge_modes: int = 64
    edge_ratio: float = 1.25
    order: int = 8
    panel: float = 4.0
    decay: float = 14.0
    rtol: float = 1e-12
    keep_fields: bool = True
    name: str = "axisym"

    cost: ClassVar[str] = "cheap"
    marker: ClassVar[str] = "D"
    label: ClassVar[str] = "exact axisymmetric"
    reference_rank: ClassVar[int] = 30
    source_packages: ClassVar[tuple[str, ...]] = ("coathertz.axisym",)

    def __post_init__(self) -> None:
        if self.interface not in INTERFACES:
            raise CoatHertzError(f"interface must be one of {INTERFACES}, got {self.interface!r}")
        if self.n_modes is not None and not (isinstance(self.n_modes, int) and 2 <= self.n_modes <= 400):
            raise CoatHertzError(f"axisym: n_modes (--modes) must be None or an integer in [2, 400], "
                                 f"got {self.n_modes!r}")
        if not (isinstance(self.c_modes, float | int) and 1.0 <= self.c_modes <= 100.0):
            raise CoatHertzError(f"c_modes must be in [1, 100], got {self.c_modes!r}")
        if not (self.edge is None or isinstance(self.edge, bool)):
            raise CoatHertzError(f"edge must be None, True or False, got {self.edge!r}")
        if not (isinstance(self.edge_modes, int) and 8 <= self.edge_modes <= 160):
            raise CoatHertzError(f"edge_modes must be an integer in [8, 160], got {self.edge_modes!r}")
        if not (isinstance(self.edge_ratio, float | int) and 1.05 <= self.edge_ratio <= 8.0):
            raise CoatHertzError(f"edge_ratio must be in [1.05, 8], got {self.edge_ratio!r}")
        if not (isinstance(self.order, int) and 4 <= self.order <= 64):
            raise CoatHertzError(f"order must be an integer in [4, 64], got {self.order!r}")
        if not (isinstance(self.panel, float | int) and 0.1 <= self.panel <= 20.0):
            raise CoatHertzError(f"panel must be in [0.1, 20], got {self.panel!r}")
        if not (isinstance(self.decay, float | int) and 5.0 <= self.decay <= 100.0):
            raise CoatHertzError(f"decay must be in [5, 100], got {self.decay!r}")
        if not (isinstance(self.rtol, float) and 0.0 < self.rtol < 1e-3):
            raise CoatHertzError(f"rtol must satisfy 0 < rtol < 1e-3, got {self.rtol!r}")

    # registry metadata --------------------------------------------------------------------------
    @classmethod
    def settings_for(cls, resolution: str) -> dict:
        """Constructor keyword arguments at a study resolution: the default quadrature everywhere
        (converged to ~1e-9 and costing milliseconds), without the profiles (studies compare
        scalars; ``keep_fields`` does not change the numbers and is not in :meth:`settings`)."""
        if resolution not in ("tiny", "quick", "full"):
            raise CoatHertzError(f"resolution must be one of ('tiny', 'quick', 'full'), got {resolution!r}")
        return {"keep_fields": False}

    @classmethod
    def refined_settings(cls, resolution: str) -> dict[str, Any]:
        """Twice the Legendre modes, four more ``xi`` nodes per panel and, for thin layers, 96
        Legendre modes with edge functions at ratio 1.15: a study re-solves the cases it marks
        ``refine`` with these, and the difference is this reference's numerical uncertainty there
        (a convergence estimate, about 1e-9; see the package docstring)."""
        return {**cls.settings_for(resolution), "c_modes": 2.0 * cls.c_modes, "order": cls.order + 4,
                "edge_modes": 96, "edge_ratio": 1.15}

    # Method protocol ---------------------------------------------------------------------------
    def settings(self) -> Mapping[str, Any]:
        # the fields' values directly (all plain numbers and strings): ``asdict`` deep-copies
        # each one, and a run asks for the settings of each result several times
        skip = ("name", "keep_fields")
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in skip}

    def supports(self, case: ContactCase) -> bool:
        """Circular point contacts (``Rx = Ry`` finite): the problem is axisymmetric."""
        return case.is_circular and math.isfinite(case.Rx)

    def _rule(self) -> XiRule:
        return XiRule(order=self.order, panel=float(self.panel))

    def solve(self, case: ContactCase) -> ContactResult:
        """Solve one circular case under load control; raises for elliptical cases."""
        with single_thread_blas():
            return self._solve(require_case(case, self.name))

    def _solve(self, case: ContactCase) -> ContactResult:
        if not isinstance(case, ContactCase):
            raise CoatHertzError(f"case must be a ContactCase, got {case!r}")
        if not self.supports(case):
            raise CoatHertzError(
                "axisym: the case is not axisymmetric (relative radii "
                f"Rx = {case.Rx * 1e3:.4g} mm, Ry = {case.Ry * 1e3:.4g} mm differ); "
                "the exact axisymmetric method needs a circular contact (use fft)"
            )
        t0 = time.perf_counter()
        interface = case.interface_for(self.interface)
        pc = pair_compliance(case, interface)
        R = case.R
        rule = self._rule()
        a_init = initial_radius(pc, R, case.W)
        auto = self.n_modes is None
        H_init = pc.h_min / a_init
        use_edge = auto if self.edge is None else self.edge
        layered = bool(pc.terms)
        # three regimes (package docstring, "Thin layers"): edge functions where the Legendre rule
        # would need more than EDGE_SWITCH modes; below EDGE_H_MIN the layer is invisible at 1e-8
        # and N_MIN modes with the energy edge condition suffice; else Legendre modes, g(1) = 0
        faint = auto and layered and H_init < EDGE_H_MIN
        thin = (use_edge and layered and not faint
                and modes_needed(H_init, self.c_modes) > EDGE_SWITCH)
        beta = None
        condition = "energy" if (thin or faint) else "point"
        if thin:
            n_modes = self.edge_modes if auto else self.n_modes
            beta = edge_basis(H_init, n_modes, float(self.edge_ratio), EDGE_FINE, EDGE_COARSE).array()
        elif faint:
            n_modes = N_MIN
        else:
            n_modes = default_modes(H_init, self.c_modes) if auto else self.n_modes
        sol, iters = solve_load(pc, R, case.W, n_modes, rule, self.decay, self.rtol, a_start=a_init,
                                beta=beta, edge_condition=condition)
        if auto and not (thin or faint) and default_modes(pc.h_min / sol.a, self.c_modes) > n_modes:
            # the estimate of a was too large: more modes at the converged radius
            n_modes = default_modes(pc.h_min / sol.a, self.c_modes)
            sol, more = solve_load(pc, R, case.W, n_modes, rule, self.decay, self.rtol, a_start=sol.a,
                                   edge_condition=condition)
            iters += more
        shape = pressure_shape(sol)
        rho_in = 0.5 * (1.0 - np.cos(np.linspace(0.0, math.pi, 121)))
        p_in = None
        if self.keep_fields:
            p_in = pressure(pc, sol, rho_in, shape)
        # with edge functions each pressure value costs a quadrature: the profile is the scan
        scan = (rho_in, p_in) if (p_in is not None and sol.e.size) else None
        p0, r_p0 = peak_pressure(pc, sol, shape=shape, scan=scan)
        meta: dict[str, Any] = {
            "r_p0": r_p0,
            "n_modes": n_modes,
            "n_xi": sol.n_xi,
            "n_edge": int(sol.e.size),
            # the edge functions' decay rates (thin layers): what rebuilds this g (axisym.stresses)
            "edge_rates": [float(b) for b in sol.beta],
            "edge_condition": condition,
            "iterations": iters,
            "h_over_a": pc.h_min / sol.a if math.isfinite(pc.h_min) else None,  # None: uncoated
            "E_ref": pc.E_ref,
            "interface": interface,
            "settings": dict(self.settings()),
        }
        if auto and not (thin or faint) and modes_needed(pc.h_min / sol.a, self.c_modes) > 1.5 * N_MAX:
            msg = (f"h/a = {pc.h_min / sol.a:.3g}: the rule asks for "
                   f"{modes_needed(pc.h_min / sol.a, self.c_modes)} Legendre modes, capped at {N_MAX}; "
                   "a and p0 may be less accurate than 1e-8 (to refine, give more Legendre modes: "
                   "--modes N on the command line, n_modes=N in Python, up to 400)")
            warnings.warn(msg, UserWarning, stacklevel=2)
            meta["accuracy"] = msg
        fields: dict[str, np.ndarray] = {}
        if self.keep_fields:
            x_end = direct_end(n_modes, rule)
            rho = np.concatenate([rho_in, np.linspace(1.0, 3.0, 25)[1:]])
            p = np.zeros_like(rho)
            p[: rho_in.size] = p_in
            fields = {
                "r": rho * sol.a,
                "pressure": p,
                "u_z": displacement(pc, sol, rho, R, rule, self.decay, max_xi=x_end),
            }
            if math.isfinite(pc.h_min) and self.decay * sol.a / pc.h_min > x_end:
                meta["u_z"] = (f"layer term of u_z outside the contact integrated to xi = {x_end:.0f} "
                               f"(of {self.decay * sol.a / pc.h_min:.3g}): ~1e-8 of delta")
        meta["wall_time"] = time.perf_counter() - t0
        res = ContactResult(self.name, sol.delta, sol.a, p0, case.W, sol.a, sol.a, meta, fields)
        return check_validity(case, res)

    def solve_many(self, cases: Sequence[ContactCase]) -> list[ContactResult]:
        """Solve cases one after another (Bessel tables are shared through a cache)."""
        with single_thread_blas():
            return [self._solve(c) for c in cases]
