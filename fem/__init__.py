"""Axisymmetric finite-element model of (coated) bodies in contact: elastic, and elastic-plastic.

scikit-fem, Q2 quadrilaterals (Taylor-Hood Q2-Q1 for nu >= 0.45), frictionless node-to-rigid
paraboloid contact under load control (or an elastic indenter meshed as a second half-space);
bonded or frictionless coating/substrate interface; a layer stack (``Body.layers``) with each
interface bonded or frictionless (elastic only). Independent of :mod:`coathertz.fft`,
:mod:`coathertz.axisym` and :mod:`coathertz.stack` (imports only the shared case model).
Modules, one job each:

``mesh`` graded tensor-product mesh; ``forms`` axisymmetric weak forms; ``affine`` the
stiffness of the rectangles of that mesh without skfem's quadrature basis; ``material`` laws at
quadrature points; ``model`` assembly and boundary conditions; ``farfield`` outer boundary
(Boussinesq); ``contact`` active set / penalty, condensed on the candidates (one factorisation
per solve), elastic indenter in series; ``ordering`` nested dissection with the candidates
last; ``solvers`` direct / condensed LU / nested-dissection LU / AMG-CG; ``loading`` increments
and Newton loop; ``post`` contact radius, p0, stresses; ``io`` VTU output; ``method``
:class:`~coathertz.fem.method.FEMMethod` (the ``fem`` entry of the method registry).

Elasticity is one wing; plasticity (a rigid sphere on a (coated) body whose materials have a
yield stress) is the other, in the subpackage :mod:`coathertz.fem.plastic` (J2 return mapping,
B-bar assembly, incremental contact, load path, contact edge, figures, yield onset, Hill's hollow
sphere).
"""
