"""A coated body between its two Hertz limits.

A rigid sphere (R = 5 mm, W = 10 N) on a hard coating (E_c = 4 E_s, nu = 0.3) on steel. As the
coating thickness H = h/a0s grows, the exact axisymmetric method's contact radius moves from the
substrate's Hertz value towards the coating's, which it reaches for a coating a hundred contact
radii thick; the paper's closed form (eqs 17-19, fitted for H in [0.01, 3]) follows it. Printed:
a over the substrate's Hertz radius a0s.

Run: ``python docs/examples/coating_limits.py``
"""

from coathertz import ContactCase, Material
from coathertz.methods import get_method

steel = Material(210e9, 0.3)
hard = Material(4 * 210e9, 0.3)
base = ContactCase.sphere_on_coated_half_space(R=5e-3, W=10.0, coating=hard, h=1e-6, substrate=steel)
a0s, a0c = base.hertz_s.a0, base.hertz_c.a0
print(f"Hertz limits: a0c/a0s = {a0c / a0s:.6f} (coating), 1 (substrate)")
exact, closed = get_method("axisym"), get_method("closed-form")
for H in (0.01, 0.1, 1.0, 3.0):
    case = base.with_thickness(H * a0s)
    print(f"H = {H:g}: exact a/a0s = {exact.solve(case).a / a0s:.6f}, "
          f"closed form a/a0s = {closed.solve(case).a / a0s:.6f}")
thick = exact.solve(base.with_thickness(100 * a0s))
print(f"H = 100: exact a/a0s = {thick.a / a0s:.8f}")
