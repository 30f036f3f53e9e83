"""A layer stack, and the identity it must satisfy.

TiN (3 um) over a Ti interlayer (1 um) on steel, pressed by a rigid sphere (R = 5 mm, W = 2 N),
solved by the exact axisymmetric method. Splitting the TiN layer into two bonded layers of
1.5 um each describes the same body, so it must give the same contact to round-off; the script
prints both results and their largest relative difference.

Run: ``python docs/examples/layer_stack.py``
"""

from coathertz import Body, ContactCase, Material
from coathertz.materials import Layer
from coathertz.methods import get_method

steel, tin, ti = Material(210e9, 0.3), Material(450e9, 0.25), Material(116e9, 0.32)
sphere = Body.rigid_sphere(5e-3)
stack = (Layer(tin, 3e-6), Layer(ti, 1e-6))
split = (Layer(tin, 1.5e-6), Layer(tin, 1.5e-6), Layer(ti, 1e-6))
exact = get_method("axisym")
one = exact.solve(ContactCase(sphere, Body(steel, layers=stack), 2.0))
two = exact.solve(ContactCase(sphere, Body(steel, layers=split), 2.0))
for label, r in (("TiN 3 um / Ti 1 um", one), ("TiN 1.5 + 1.5 um / Ti 1 um", two)):
    print(f"{label:28s} a = {r.a * 1e6:.6f} um, delta = {r.delta * 1e9:.4f} nm, p0 = {r.p0 / 1e9:.6f} GPa")
diff = max(abs(getattr(two, q) / getattr(one, q) - 1) for q in ("a", "delta", "p0"))
print(f"largest relative difference: {diff:.1e}")
