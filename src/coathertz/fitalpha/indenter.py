"""The fitting half of the elastic-indenter form (:mod:`coathertz.closedform.refit.indenter`):
its correction surfaces ``D_q`` by least squares on the ``indenter`` training grid.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from coathertz.closedform.refit import indenter as IND
from coathertz.closedform.refit import model as M
from coathertz.closedform.refit.surface import Surface
from coathertz.errors import CoatHertzError
from coathertz.fitalpha.corrected import fit_tensor
from coathertz.fitalpha.fit import FitSettings

ZERO = IND.IndenterForm({})


def base_log_bars(rigid_bars: Callable, cols: Mapping) -> dict[str, np.ndarray]:
    """``ln`` of the form's base (the rigid indenter's bars at the equivalent ``E'`` and ``s'`` of
    :func:`coathertz.closedform.refit.indenter.equivalent_problem`) at the rows ``cols``."""
    E, H, nu_c, nu_s, g = (np.asarray(cols[k], dtype=float) for k in ("E", "H", "nu_c", "nu_s", "gamma"))
    E_eq, nu_eq, _ = IND.equivalent_problem(E, nu_c, nu_s, g)
    base = rigid_bars(E_eq, H, nu_eq, nu_s)
    return {q: np.log(base[q]) for q in M.QUANTITIES}


def fit_indenter_form(table_rows: Mapping, rigid_bars: Callable, settings: FitSettings) -> IND.IndenterForm:
    """``D_q`` of every quantity, fitted to ``ln bar_exact - ln base`` on the training rows
    (a complete tensor grid in (log10 H, log10 E, s, gamma); :func:`coathertz.fitalpha.corrected.fit_tensor`,
    one variable at a time, on the residual over ``gamma (1 - gamma)`` with the row weight
    ``v(H)``), or by general least squares (a ridge of ``settings.ridge``) where the grid is
    incomplete."""
    cols = table_rows
    E, H, nu_c, nu_s, g = (np.asarray(cols[k], dtype=float) for k in ("E", "H", "nu_c", "nu_s", "gamma"))
    if len(H) == 0:
        raise CoatHertzError("indenter fit: no training rows")
    X = IND.variables(E, H, nu_c, nu_s, g)
    base = base_log_bars(rigid_bars, cols)
    terms = IND.full_tensor(settings.degrees)
    lo, hi = tuple(b[0] for b in IND.BOX), tuple(b[1] for b in IND.BOX)
    proto = Surface(IND.VARIABLES, lo, hi, terms, tuple(0.0 for _ in terms))
    gg = g * (1.0 - g)
    wH = IND.weight(H, 0.5) / 0.25  # v(H)
    surfaces = {}
    for q in M.QUANTITIES:
        y = np.log(np.asarray(cols[f"{q}_bar"], dtype=float)) - base[q]
        c = fit_tensor(proto, X, y / gg, wH)
        if c is None:
            A = IND.weight(H, g)[:, None] * proto.design(X)
            reg = np.sqrt(settings.ridge) * np.eye(len(terms))
            c = np.linalg.lstsq(np.vstack([A, reg]), np.concatenate([y, np.zeros(len(terms))]), rcond=None)[0]
        surfaces[q] = Surface(IND.VARIABLES, lo, hi, terms,
                              tuple(float(f"{x:.{IND.COEF_DIGITS}g}") for x in c))
    return IND.IndenterForm(surfaces)


def errors(form: IND.IndenterForm, rigid_bars: Callable, cols: Mapping) -> dict[str, np.ndarray]:
    """Errors [%] of ``form`` on the rows ``cols``."""
    args = (np.asarray(cols[k], dtype=float) for k in ("E", "H", "nu_c", "nu_s", "gamma"))
    lb = form.log_bars(rigid_bars, *args)
    return {q: 100.0 * np.expm1(lb[q] - np.log(np.asarray(cols[f"{q}_bar"], dtype=float)))
            for q in M.QUANTITIES}
