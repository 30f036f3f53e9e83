"""Hertz contact by every method.

A rigid sphere (R = 10 mm) pressed with W = 100 N on an uncoated steel half-space
(E = 210 GPa, nu = 0.3): the closed form, the DC-FFT solver and the exact axisymmetric method
each give the contact radius a, the approach delta and the peak pressure p0, printed next to
Hertz's eq (1) and as relative differences from it.

Run: ``python docs/examples/hertz_every_method.py``
"""

from coathertz import ContactCase, Material
from coathertz.methods import get_method

steel = Material(210e9, 0.3)
# an "uncoated" body is a coating of the substrate's own material (any thickness)
case = ContactCase.sphere_on_coated_half_space(R=10e-3, W=100.0, coating=steel, h=10e-6, substrate=steel)
hertz = case.hertz_s
print(f"Hertz eq (1): a = {hertz.a0 * 1e6:.4f} um, delta = {hertz.delta0 * 1e6:.5f} um, "
      f"p0 = {hertz.p0 / 1e6:.2f} MPa")
for name, settings in (("closed-form", {}), ("fft", {"n": 128}), ("axisym", {})):
    r = get_method(name, **settings).solve(case)
    print(f"{name:12s} a/a0 - 1 = {r.a / hertz.a0 - 1:+.2e}   delta/delta0 - 1 = "
          f"{r.delta / hertz.delta0 - 1:+.2e}   p0/p0H - 1 = {r.p0 / hertz.p0 - 1:+.2e}")
