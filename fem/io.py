"""VTU output (meshio) of the mesh, displacement and stresses for ParaView."""

from __future__ import annotations

import meshio
import numpy as np

from coathertz.fem.model import FEModel
from coathertz.fem.post import quad_stress, von_mises


def write_vtu(path: str, model: FEModel, x: np.ndarray) -> None:
    """Write the quadrilateral mesh with nodal displacement ``(u_r, u_z)`` and element-mean
    stresses (``sigma_rr, sigma_zz, sigma_tt, sigma_rz, von_mises``) and region ids."""
    mesh = model.lm.mesh
    nodal = model.basis.nodal_dofs
    u = x[: model.n_u]
    disp = np.zeros((mesh.p.shape[1], 3))
    disp[:, 0] = u[nodal[0]]
    disp[:, 1] = u[nodal[1]]
    nel = mesh.t.shape[1]
    cell = {k: np.zeros(nel) for k in ("sigma_rr", "sigma_zz", "sigma_tt", "sigma_rz", "von_mises", "region")}
    for k, sig in quad_stress(model, x).items():
        els = model.regions[k].elements
        mean = sig.mean(axis=-1)
        for name, v in zip(("sigma_rr", "sigma_zz", "sigma_tt", "sigma_rz"), mean, strict=True):
            cell[name][els] = v
        cell["von_mises"][els] = von_mises(mean)
        cell["region"][els] = k
    points = np.column_stack([mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])])
    meshio.write(
        path,
        meshio.Mesh(points, [("quad", mesh.t.T)], point_data={"u": disp},
                    cell_data={k: [v] for k, v in cell.items()}),
    )
