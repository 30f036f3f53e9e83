r"""Transfer of a committed elastic-plastic state from one mesh to another (remeshing).

A deep indentation path grows its contact radius many times over. A mesh sized for the largest
contact has few elements across the early contacts (at delta/delta_c = 200 on the default mesh the
contact of the second increment is spanned by 3.6 elements, the last one by 25); the contact-
following path (:func:`coathertz.fem.plastic.method.solve_plastic` with ``follow_contact=True``)
instead rebuilds the mesh around the current contact radius and carries the committed state over:

- **Displacement** ``u``: the old Q2 field evaluated at the new nodes (:meth:`skfem.Basis.probes`:
  exact for a field the old element space holds); nodes outside the old domain (the new one is
  larger when the contact grew) take the far field of the current load, the same Boussinesq field
  the old mesh carried on its outer boundary.
- **History** (plastic strain ``eps_p`` and equivalent plastic strain ``ep`` at every quadrature
  point): in each old element the 3 x 3 Gauss-point values define one tensor-product quadratic
  (Lagrange interpolation through the points), evaluated at the new quadrature points it contains;
  a linear combination of traceless plastic strains stays traceless (plastic incompressibility
  holds exactly), ``ep`` is clipped at 0. New points outside the old domain are elastic (no
  history). Old elements of elastic regions carry no history.
- **Active contact set**: the new candidates inside the old contact radius.

The transferred state is not in equilibrium on the new mesh (the interpolated history is not the
new mesh's solution), so the caller solves the same target again from it (a *rebalance*: the
return mapping puts stresses beyond the yield surface back on it); the change of the load at that
target is the transfer's error, recorded per remesh.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from coathertz.errors import CoatHertzError
from coathertz.fem.plastic.contact import PathState

#: Relative tolerance of "inside the old domain" (points on its outer boundary are inside).
INSIDE_TOL = 1e-9


def _inside(lm, r: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Points ``(r, z)`` inside the old layered mesh's rectangle ``[0, L] x [-D, 0]``."""
    tol = INSIDE_TOL * lm.L
    return (r <= lm.L + tol) & (-z <= lm.D + tol)


def _clamped(lm, r: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Points ``[2, n]`` moved onto the mesh where round-off put them just outside its rectangle
    (the element search of a point on the boundary may otherwise miss by round-off)."""
    m = 1e-10 * lm.L
    return np.vstack([np.clip(r, m, lm.L - m), np.clip(z, -lm.D + m, -m)])


def _cell_finder(mesh):
    """``(r, z) -> element`` for a tensor-product mesh of rectangles (every plastic mesh: one block of
    :func:`coathertz.fem.mesh.build_mesh`'s grids): two sorted searches. Any other mesh gets
    scikit-fem's general element search."""
    r_grid, z_grid = np.unique(mesh.p[0]), np.unique(mesh.p[1])
    nr, nz = len(r_grid) - 1, len(z_grid) - 1
    if nr * nz != mesh.t.shape[1]:
        return mesh.element_finder()
    c = mesh.p[:, mesh.t].mean(axis=1)
    i = np.searchsorted(r_grid, c[0]) - 1
    j = np.searchsorted(z_grid, c[1]) - 1
    cell = np.full((nr, nz), -1)
    cell[i, j] = np.arange(mesh.t.shape[1])
    if (cell < 0).any():
        return mesh.element_finder()

    def find(r: np.ndarray, z: np.ndarray) -> np.ndarray:
        ii = np.clip(np.searchsorted(r_grid, r, side="right") - 1, 0, nr - 1)
        jj = np.clip(np.searchsorted(z_grid, z, side="right") - 1, 0, nz - 1)
        return cell[ii, jj]

    return find


def _probes(basis, x: np.ndarray, cells: np.ndarray) -> sp.csr_matrix:
    """Matrix of the values of a field of ``basis`` at the points ``x[2, n]`` lying in ``cells``
    (rows: component 0 of every point, then component 1), as :meth:`skfem.CellBasis.probes` with
    the elements known."""
    pts = basis.mapping.invF(x[:, :, None], tind=cells)
    phis = np.array([basis.elem.gbasis(basis.mapping, pts, k, tind=cells)[0]
                     for k in range(basis.Nbfun)]).ravel()
    n = x.shape[1]
    rows = np.tile(np.arange(2 * n), basis.Nbfun)
    cols = basis.element_dofs[:, np.tile(cells, 2)].ravel()
    return sp.coo_matrix((phis, (rows, cols)), shape=(2 * n, basis.N)).tocsr()


def _gauss_lagrange(X: np.ndarray) -> np.ndarray:
    """Inverse Vandermonde matrix of the tensor-product quadratics ``xi^i eta^j`` (i, j <= 2) at the
    reference quadrature points ``X[2, 9]``: ``weights = monomials(x) @ Vinv``."""
    if X.shape != (2, 9):
        raise CoatHertzError(f"state transfer needs 3 x 3 Gauss points per element, got {X.shape[1]} points")
    return np.linalg.inv(_monomials(X[0], X[1]))


def _monomials(xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    return np.stack([xi**i * eta**j for i in range(3) for j in range(3)], axis=-1)


def transfer_state(old_model, old_asm, old_state: PathState, new_model, new_asm, W: float,
                   new_cand_r: np.ndarray) -> PathState:
    """The committed ``old_state`` of ``old_model`` carried to ``new_model`` (module docstring).

    Parameters
    ----------
    old_model, old_asm, old_state
        The old mesh's :class:`~coathertz.fem.model.FEModel`, its
        :class:`~coathertz.fem.plastic.assembly.BBarAssembler` and the committed state.
    new_model, new_asm
        The new mesh's model and assembler (the same regions, in the same order).
    W
        Load [N] of the state: the far field of new nodes outside the old domain.
    new_cand_r
        Radii [m] of the new model's contact candidates (its ``ContactGeometry.r``).
    """
    if len(old_asm.regions) != len(new_asm.regions):
        raise CoatHertzError("state transfer: the two meshes have different regions (internal error)")
    old_lm = old_model.lm
    finder = _cell_finder(old_lm.mesh)
    # -- displacement at the new dofs ---------------------------------------------------------
    r, z, comp = new_model.r_dof, new_model.z_dof, new_model.comp
    u = np.zeros(new_model.n_u)
    inside = _inside(old_lm, r, z)
    idx = np.flatnonzero(inside)
    if idx.size:
        pts = _clamped(old_lm, r[idx], z[idx])
        P = _probes(old_asm.basis, pts, finder(pts[0], pts[1]))
        vals = P @ old_state.u[: old_asm.n]
        n = idx.size
        u[idx] = np.where(comp[idx] == 0, vals[:n], vals[n:])
    out = np.flatnonzero(~inside)
    if out.size and new_model.farfield_material is not None and not new_model.lm.rigid_base:
        uv = new_model.farfield.values(r[out], z[out], W, new_model.farfield_material)
        u[out] = uv[comp[out], np.arange(out.size)]
    # -- history at the new quadrature points --------------------------------------------------
    n_old = old_model.lm.mesh.t.shape[1]
    reg_of = np.full(n_old, -1)
    loc_of = np.zeros(n_old, dtype=np.int64)
    for k, (els, _) in enumerate(old_asm.regions):
        reg_of[els] = k
        loc_of[els] = np.arange(len(els))
    Vinv = _gauss_lagrange(np.asarray(old_asm.basis.X))
    states = []
    for k, ((els, law), (els_old, _), st_old) in enumerate(zip(new_asm.regions, old_asm.regions,
                                                                 old_state.states, strict=True)):
        shape = new_asm.w[els].shape
        st_new = law.initial_state(shape) if hasattr(law, "initial_state") else {}
        if not st_new:
            states.append(st_new)
            continue
        if set(st_new) != {"eps_p", "ep"}:
            raise CoatHertzError(f"state transfer knows the J2 state (eps_p, ep), got {sorted(st_new)}")
        D_el = law.elastic_matrix()
        # the old stress sigma = D_el (eps - eps_p) at the old points (the committed state's)
        sig_old = np.einsum("ij,jeq->ieq", D_el, old_asm.strain(old_state.u, els_old) - st_old["eps_p"])
        rq, zq = new_asm.rq[els].ravel(), new_asm.zq[els].ravel()
        ins = np.flatnonzero(_inside(old_lm, rq, zq))
        if ins.size == 0:
            states.append(st_new)
            continue
        x = np.vstack([rq[ins], zq[ins]])
        tind = finder(x[0], x[1])
        if np.any(reg_of[tind] != k):
            raise CoatHertzError("state transfer: a quadrature point fell in another region of the old "
                                 "mesh (internal error)")
        X = old_asm.basis.mapping.invF(x[:, :, None], tind=tind)[:, :, 0]
        wts = _monomials(X[0], X[1]) @ Vinv  # [npts, 9]
        loc = loc_of[tind]
        ep = np.maximum(np.einsum("pq,pq->p", st_old["ep"][loc], wts), 0.0)
        has = np.any(st_old["ep"][loc] > 0.0, axis=1)  # the old element has plastic history
        ep[~has] = 0.0
        sig = np.einsum("ipq,pq->ip", sig_old[:, loc], wts)
        # the plastic strain that gives the new points the transferred stress with the new strain
        eps = new_asm.strain(u, els).reshape(4, -1)[:, ins]
        eps_p = eps - np.linalg.solve(D_el, sig)
        eps_p[:, ep == 0.0] = 0.0
        flat_ep = st_new["ep"].reshape(-1)
        flat_ep[ins] = ep
        flat_p = st_new["eps_p"].reshape(4, -1)
        flat_p[:, ins] = eps_p
        states.append({"eps_p": flat_p.reshape(4, *shape), "ep": flat_ep.reshape(shape)})
    # -- active set: the new candidates inside the old contact --------------------------------
    old_cand_r = old_model.r_dof[old_model.candidates]
    a_old = float(old_cand_r[old_state.active].max()) if old_state.active.any() else -1.0
    active = new_cand_r <= a_old * (1 + 1e-12)
    return PathState(u, states, active, old_state.delta)
