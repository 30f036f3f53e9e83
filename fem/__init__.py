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

Elasticity is one wing; plasticity (rigid sphere on a (coated) body whose materials have a yield
stress) is the other, in the ``plastic_*`` modules and ``j2``: ``j2`` the J2 radial return with
its consistent tangent; ``plastic_assembly`` B-bar Q2 assembly of internal force and tangent;
``plastic_contact`` the incremental contact + plasticity Newton loop (load or approach control,
adaptive sub-increments); ``plastic_method`` the load path (mesh sized from the path's largest
load or approach, grown when the contact nears its candidate zone's edge), curves, final fields,
JSON / CSV / VTU + ``.pvd`` output; ``plastic_edge`` contact-edge bracket and radius;
``plastic_plot`` load-approach and plastic-zone figures; ``plastic_onset`` elastic onset of
yield; ``plastic_sphere`` Hill's hollow sphere (a verification problem with a closed form).
"""
