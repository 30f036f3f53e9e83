"""The response rows of a layered body's stresses at one depth (:class:`StressRows`): the type
every FFT stress response (:mod:`coathertz.fft.stresses`, :mod:`coathertz.fft.stack_stresses`)
returns, in a module of its own so that neither imports the other for it."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class StressRows:
    """Real response rows at one depth, per wavenumber (see the module docstring).

    ``normal``: ``(kk, pp, zz, kz)`` under ``P cos kx`` (sigma_kz ~ sin kx);
    ``tangential``: the same rows under ``Q cos kx`` along ``k`` (sigma_kz ~ -cos kx, the others
    ~ sin kx); ``antiplane``: ``(kp, pz)`` under ``Q cos kx`` normal to ``k``
    (sigma_pz = pz cos kx, sigma_kp = -kp sin kx).
    """

    normal: tuple
    tangential: tuple
    antiplane: tuple
