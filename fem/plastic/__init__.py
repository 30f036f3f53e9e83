"""Elastic-plastic contact: a rigid sphere pressed into a (coated) axisymmetric body whose
materials have a yield stress (``coathertz fem --plastic``).

Modules, one job each:

:mod:`~coathertz.fem.plastic.j2`
    J2 (von Mises) plasticity: the radial return and its consistent tangent, isotropic
    hardening laws (perfect, linear, power, table).
:mod:`~coathertz.fem.plastic.assembly`
    B-bar assembly of the Q2 internal force and tangent (no volumetric locking as the plastic
    flow becomes incompressible).
:mod:`~coathertz.fem.plastic.contact`
    The incremental contact + plasticity Newton loop: load or approach control, adaptive
    sub-increments with cutbacks, unloading.
:mod:`~coathertz.fem.plastic.condense`
    Static condensation of the elastic far field: factorised once, so that each Newton
    iteration factorises only a box around the contact and the plastic zone (exact).
:mod:`~coathertz.fem.plastic.method`
    The load path as a user runs it: mesh and contact zone sized from the path's largest load or
    approach and grown when the contact nears the zone's edge (or, ``follow_contact``, meshes
    that follow the contact), the curves, final fields, JSON /
    CSV / VTU + ``.pvd`` output.
:mod:`~coathertz.fem.plastic.remesh`
    Remeshing: the committed state (displacement, plastic history, contact set) carried to a new
    mesh, for load paths whose mesh follows the growing contact.
:mod:`~coathertz.fem.plastic.edge`
    The contact edge: the node bracket and a radius estimator valid for elastic and plastic
    edges alike.
:mod:`~coathertz.fem.plastic.plot`
    Load-approach and plastic-zone figures.
:mod:`~coathertz.fem.plastic.onset`
    First yield from the elastic solution (load, location, region).
:mod:`~coathertz.fem.plastic.stored`
    Load paths and onset searches through the result store (keyed like every other result,
    resumable: an interrupted study recomputes only what had not finished).
:mod:`~coathertz.fem.plastic.published`
    Published fits of elastic-plastic spherical contact (Kogut & Etsion 2002, Jackson & Green
    2005), the reference of the ``indentation`` study.
:mod:`~coathertz.fem.plastic.hollow_sphere`
    Hill's pressurised hollow sphere: a verification problem with a closed form, for the return
    mapping and the B-bar assembly (``tests/plasticity/test_hill_sphere.py``).

The elastic model (:mod:`coathertz.fem`) is the other wing; this one builds on its mesh, model,
far field and post-processing.
"""
