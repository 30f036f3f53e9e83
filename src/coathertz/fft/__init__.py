"""DC-FFT contact solver for coated bodies (the paper's numerical method).

Public API
----------
:class:`~coathertz.fft.method.FFTMethod`
    ``FFTMethod(n=128, ...).solve(case) -> ContactResult``; ``.solve_many(cases)`` for sweeps.
The building blocks
    :mod:`~coathertz.fft.frf` (FRF of eq 13 and the transfer matrix),
    :mod:`~coathertz.fft.influence` (cell coefficients), :mod:`~coathertz.fft.grid` (grids),
    :mod:`~coathertz.fft.solver` (Polonsky-Keer CG), :mod:`~coathertz.fft.estimators`
    (contact-size estimators).

Submodules are imported lazily by the method registry; importing this package is cheap.
"""
