"""DC-FFT contact solver for coated bodies (the paper's numerical method).

Public API
----------
:class:`~coathertz.fft.method.FFTMethod`
    ``FFTMethod(n=128, ...).solve(case) -> ContactResult``; ``.solve_many(cases)`` for sweeps.
:mod:`~coathertz.fft.frf`, :mod:`~coathertz.fft.influence`, :mod:`~coathertz.fft.grid`,
:mod:`~coathertz.fft.solver`, :mod:`~coathertz.fft.estimators`
    The building blocks (FRF of eq 13 and the transfer matrix, cell coefficients, grids,
    Polonsky-Keer CG, contact-size estimators).

Submodules are imported lazily by the method registry; importing this package is cheap.
"""
