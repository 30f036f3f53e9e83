"""Axisymmetric finite-element model of a (coated) half-space pressed by a rigid sphere.

scikit-fem, Q2 quadrilaterals (Taylor-Hood Q2-Q1 for nu >= 0.45), frictionless node-to-rigid
paraboloid contact under load control (or an elastic indenter meshed as a second half-space);
bonded or frictionless coating/substrate interface. Independent of :mod:`coathertz.fft`
(imports only the shared case model). Modules, one job each:

``mesh`` graded tensor-product mesh; ``forms`` axisymmetric weak forms; ``affine`` the
stiffness of the rectangles of that mesh without skfem's quadrature basis; ``material`` laws at
quadrature points; ``model`` assembly and boundary conditions; ``farfield`` outer boundary
(Boussinesq); ``contact`` active set / penalty, condensed on the candidates (one factorisation
per solve), elastic indenter in series; ``ordering`` nested dissection with the candidates
last; ``solvers`` direct / condensed LU / nested-dissection LU / AMG-CG; ``loading`` increments
and Newton loop; ``post`` contact radius, p0, stresses; ``io`` VTU output; ``method``
:class:`~coathertz.fem.method.FEMMethod` (the ``fem`` entry of the method registry).
"""
