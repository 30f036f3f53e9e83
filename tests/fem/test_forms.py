"""Axisymmetric forms: manufactured solution, generic material-law assembly, locking."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sy
from skfem import Basis, ElementQuad2, ElementVector, MeshQuad, asm, condense, solve

from coathertz.fem import forms
from coathertz.fem.loading import internal_force, tangent
from coathertz.fem.material import LinearElastic


def _manufactured(lam, mu):
    r, z = sy.symbols("r z", positive=True)
    ur = r * (1 - r) * sy.sin(sy.pi * z)
    uz = sy.cos(sy.pi * r) * z**2
    err, ezz, ett, grz = sy.diff(ur, r), sy.diff(uz, z), ur / r, sy.diff(ur, z) + sy.diff(uz, r)
    tr = err + ezz + ett
    srr, szz, stt, srz = lam * tr + 2 * mu * err, lam * tr + 2 * mu * ezz, lam * tr + 2 * mu * ett, mu * grz
    fr = -(sy.diff(srr, r) + sy.diff(srz, z) + (srr - stt) / r)  # equilibrium in cylindrical coordinates
    fz = -(sy.diff(srz, r) + sy.diff(szz, z) + srz / r)
    lam_ = sy.lambdify((r, z), (ur, uz), "numpy")
    f_ = sy.lambdify((r, z), (fr, fz), "numpy")
    return lam_, f_


def test_manufactured_solution_converges_at_order_3():
    lam, mu = 1.5, 1.0
    exact, f = _manufactured(lam, mu)
    hs, errs = [], []
    for n in (2, 4, 8):
        m = MeshQuad.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
        ib = Basis(m, ElementVector(ElementQuad2()), intorder=6)
        nq = ib.X.shape[-1]
        nel = m.t.shape[1]
        K = asm(forms.elasticity, ib, lam=np.full((nel, nq), lam), mu=np.full((nel, nq), mu))
        X = ib.global_coordinates()
        fq = [np.broadcast_to(c, X[0].shape) * 1.0 for c in f(X[0], X[1])]
        b = asm(forms.body_force, ib, fr=fq[0], fz=fq[1])
        x = np.zeros(ib.N)
        locs = ib.doflocs
        comp = np.zeros(ib.N, dtype=int)
        for d in (ib.nodal_dofs, ib.facet_dofs, ib.interior_dofs):
            comp[d[1]] = 1
        bnd = (np.isclose(locs[0], 1) | np.isclose(locs[1], 0) | np.isclose(locs[1], 1)) | (
            np.isclose(locs[0], 0) & (comp == 0)
        )
        D = np.nonzero(bnd)[0]
        ex = np.array(exact(locs[0], locs[1]))
        x[D] = ex[comp[D], D]
        x = solve(*condense(K, b, x=x, D=D))
        uh = ib.interpolate(x)
        X = ib.global_coordinates()
        ue = np.array(exact(X[0], X[1]))
        e2 = ((uh[0] - ue[0]) ** 2 + (uh[1] - ue[1]) ** 2) * 2 * np.pi * X[0]
        errs.append(np.sqrt(np.sum(e2 * ib.dx)))
        hs.append(1.0 / n)
    order = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert order > 2.7, f"observed L2 order {order:.2f} (errors {errs}); Q2 theory: 3"


def test_generic_law_assembly_equals_fast_path(fx):
    from coathertz.fem.farfield import BoussinesqFarField
    from coathertz.fem.mesh import MeshSpec, build_mesh
    from coathertz.fem.model import FEModel, Region

    lm = build_mesh(1.0, 0.2, MeshSpec(n_a=6, growth=1.6, L=10))
    regions = [
        Region(lm.coating, LinearElastic(400e9, 0.25)),
        Region(lm.substrate, LinearElastic(200e9, 0.3)),
    ]
    model = FEModel(lm, regions, fx.STEEL, BoussinesqFarField())
    K = model.stiffness()
    states = [{}, {}]
    Kt = tangent(model, np.zeros(model.n_u), states)
    assert abs(K - Kt).max() <= 1e-10 * abs(K).max()
    u = np.random.default_rng(0).normal(size=model.n_u)
    F, _ = internal_force(model, u, states)
    assert np.allclose(F, K @ u, rtol=1e-10, atol=1e-10 * np.abs(K @ u).max())


def test_locking_of_displacement_form_and_not_of_taylor_hood(fx):
    """Thin nu -> 0.5 layer on a rigid base: the axial stress at the bonded bottom.

    Measured (sigma_zz / p0c at r = 0, z = -h; nu_c = 0.4999): displacement form -8.55, -5.37,
    -3.43 on the coarse/default/fine meshes (locked: the volumetric constraint pollutes the
    pressure); Taylor-Hood Q2-Q1 -2.962, -2.958, identical to nu = 0.5 within 0.1 %.
    """
    case = fx.rigid_base_case(0.4999)
    case5 = fx.rigid_base_case(0.5)

    def bottom(res, c):
        return res.fields["axis_sigma_zz"][-1] / c.p0c

    disp = [bottom(fx.solve(case, mesh=m, mixed="never", stresses=True), case) for m in ("coarse", "default")]
    th = [bottom(fx.solve(case, mesh=m, mixed="always", stresses=True), case) for m in ("coarse", "default")]
    th5 = bottom(fx.solve(case5, mesh="default", stresses=True), case5)
    assert abs(th[1] - th[0]) < 0.01 * abs(th[1]), th
    assert abs(th5 - th[1]) < 0.01 * abs(th[1]), (th5, th)
    assert abs(disp[0] - th[1]) > 0.5 * abs(th[1]), (disp, th)  # locked: > 50 % off
    assert abs(disp[1] - disp[0]) > 0.2 * abs(th[1]), disp  # and far from mesh-converged
    with pytest.raises(Exception, match="mixed"):
        fx.solve(case5, mesh="coarse", mixed="never")


def test_rectangle_tables_equal_skfem_basis():
    """:mod:`coathertz.fem.affine` against skfem's generic basis on a graded tensor mesh with a
    quadrature-point field: stiffness (measured 4e-16 relative), dof locations (exact), surface
    ring weights (measured 1e-15); a mesh that is not made of axis-aligned rectangles is refused."""
    from skfem import FacetBasis, LinearForm
    from skfem.assembly import Dofs

    from coathertz.fem.affine import RectQ2, dof_locations, ring_weights
    from coathertz.fem.mesh import MeshSpec, build_mesh
    from coathertz.fem.model import INTORDER

    mesh = build_mesh(1.0, 0.2, MeshSpec(n_a=6, growth=1.6, L=10)).mesh
    elem = ElementVector(ElementQuad2())
    basis = Basis(mesh, elem, intorder=INTORDER)
    nel, nq = mesh.t.shape[1], basis.X.shape[-1]
    rng = np.random.default_rng(1)
    lam, mu = rng.uniform(1.0, 3.0, (2, nel, nq))
    K0 = asm(forms.elasticity, basis, lam=lam, mu=mu)
    dofs = Dofs(mesh, elem)
    K1 = RectQ2.build(mesh, INTORDER).elasticity(lam, mu, dofs.element_dofs, dofs.N)
    assert abs(K1 - K0).max() <= 1e-13 * abs(K0).max()
    locs = dof_locations(mesh, elem, dofs)
    assert np.array_equal(locs, basis.doflocs)
    uz = np.concatenate([dofs.nodal_dofs[1], dofs.facet_dofs[1]])
    top = uz[np.abs(locs[1, uz]) < 1e-12]
    top = top[np.argsort(locs[0, top])]
    facets = mesh.facets_satisfying(lambda x: np.abs(x[1]) < 1e-12)
    fb = FacetBasis(mesh, elem, facets=facets, intorder=INTORDER)
    w0 = asm(LinearForm(lambda v, w: v[1] * 2 * np.pi * w.x[0]), fb)
    w1 = ring_weights(locs[0, top])
    assert np.allclose(w1, w0[top], rtol=0, atol=1e-13 * w0.max())
    skew = MeshQuad(mesh.p + np.array([[0.0], [0.01]]) * mesh.p[0], mesh.t)  # parallelograms
    with pytest.raises(ValueError, match="axis-aligned"):
        RectQ2.build(skew, INTORDER)


def test_rectangle_tables_strain_and_projection_equal_skfem(fx):
    """The table-based strain at the quadrature points and the L2 projection of the stresses
    (:class:`coathertz.fem.post.StressField` on the rectangle tables) against skfem's generic
    basis and assembly: the same quadrature, so equal to round-off (1e-12 relative; measured
    ~1e-15)."""
    from skfem import LinearForm

    from coathertz.fem.farfield import BoussinesqFarField
    from coathertz.fem.mesh import MeshSpec, build_mesh
    from coathertz.fem.model import FEModel, Region
    from coathertz.fem.post import StressField, quad_stress

    lm = build_mesh(1.0, 0.2, MeshSpec(n_a=6, growth=1.6, L=10))
    regions = [Region(lm.coating, LinearElastic(400e9, 0.25)),
               Region(lm.substrate, LinearElastic(200e9, 0.3))]
    model = FEModel(lm, regions, fx.STEEL, BoussinesqFarField())
    assert model.rect is not None
    u = np.random.default_rng(1).normal(size=model.n_u)
    ref = forms.quad_strain(model.basis, u)
    assert np.abs(model.quad_strain(u) - ref).max() <= 1e-12 * np.abs(ref).max()
    X = model.basis.global_coordinates()
    assert np.abs(model.quad_points() - np.array([X[0], X[1]])).max() <= 1e-12 * lm.L
    sig = quad_stress(model, u)
    sf = StressField(model, u, sig)
    for k, reg in enumerate(model.regions):  # skfem's projection of region k (the generic path)
        sb = Basis(lm.mesh, ElementQuad2(), intorder=4, elements=reg.elements)
        dofs = np.unique(sb.element_dofs)
        M = asm(forms.mass, sb).tocsc()[dofs][:, dofs]
        b = asm(LinearForm(lambda v, w: w["s"] * v * 2 * np.pi * w.x[0]), sb, s=sig[k][1])
        want = np.linalg.solve(M.toarray(), b[dofs])
        sf.at(k, np.array([[0.1], [-0.1 if k == 0 else -1.0]]))
        got = sf.nodal[k][1, dofs]
        assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max(), np.abs(got - want).max()
