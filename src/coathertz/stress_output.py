"""Files from a stress field on an ``(x, y, z)`` lattice: a PNG of the von Mises stress on the x-z
and y-z slices through its maximum, and a VTU of the whole field for ParaView.

Method-independent like :mod:`coathertz.stress_summary`: the field is ``sigma[z, component, y, x]``
[Pa] in the Voigt order ``xx, yy, zz, yz, xz, xy``, ``z`` the depth [m] below the body's surface.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from coathertz.stress_summary import COMPONENTS, first_principal, von_mises


def slice_figure(x, y, z, sigma: np.ndarray, *, a_x: float, a_y: float, h: float | None,
                 title: str):
    """The von Mises stress [MPa] on the x-z slice (at the y of its maximum) and the y-z slice (at
    its x), the maximum marked, the contact edge (semi-axes ``a_x`` along x, ``a_y`` along y
    [m]) at the surface and the interface depth ``h`` [m] drawn (``None``: no coating)."""
    from coathertz.figstyle import figure

    vm = von_mises(sigma)  # (nz, ny, nx)
    k, j, i = np.unravel_index(np.argmax(vm), vm.shape)
    fig, axes = figure(2, 1, width=5.2, height=3.6)
    um = 1e6
    vmax = float(vm.max()) / 1e6
    for ax, (name, s, c, cut, edge) in zip(axes[0], (
            ("x", x, vm[:, j, :], ("y", y[j]), a_x * np.sqrt(max(0.0, 1 - (y[j] / a_y) ** 2))),
            ("y", y, vm[:, :, i], ("x", x[i]), a_y * np.sqrt(max(0.0, 1 - (x[i] / a_x) ** 2)))),
            strict=True):
        im = ax.pcolormesh(s * um, z * um, c / 1e6, shading="nearest", cmap="viridis", vmin=0, vmax=vmax)
        ax.plot(s[i if name == "x" else j] * um, z[k] * um, ls="none", marker="X", mfc="w", mec="k", ms=9,
                label=f"max {vmax:.4g} MPa")
        if edge > 0:
            for e in (-edge, edge):
                ax.axvline(e * um, color="w", ls=":", lw=1)
        if h is not None and h <= z.max():
            ax.axhline(h * um, color="r", ls="--", lw=1, label=f"interface, z = {h * um:.3g} um")
        ax.set_ylim(z.max() * um, z.min() * um)  # depth downwards
        ax.set_xlabel(f"{name} [um]")
        ax.set_ylabel("depth z [um]")
        ax.set_title(f"{name}-z slice at {cut[0]} = {cut[1] * um:.3g} um (dotted: contact edge)", fontsize=8)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.18), frameon=False, ncol=2)
    cb = fig.colorbar(im, ax=list(axes[0]), fraction=0.03, pad=0.02)
    cb.set_label("von Mises stress [MPa]")
    fig.suptitle(title, fontsize=9)
    fig.set_layout_engine("constrained")
    return fig


def write_png(path: str | Path, fig) -> Path:
    """Save ``fig`` to ``path`` (150 dpi) and close it."""
    import matplotlib.pyplot as plt

    fig.savefig(path, dpi=150)
    plt.close(fig)
    return Path(path)


def write_vtu(path: str | Path, x, y, z, sigma: np.ndarray) -> Path:
    """The field on its lattice as hexahedral cells (VTK unstructured grid, meshio): point data
    ``sigma_xx`` ... ``sigma_xy``, ``von_mises`` and ``first_principal`` [Pa]; coordinates [m]
    with the depth as ``-z`` (the surface at 0, the body below)."""
    import meshio

    nz, ny, nx = len(z), len(y), len(x)
    Z, Y, X = np.meshgrid(-np.asarray(z, float), y, x, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    idx = np.arange(nz * ny * nx).reshape(nz, ny, nx)
    c = idx[:-1, :-1, :-1]
    hexa = np.stack([c, c + 1, c + 1 + nx, c + nx,
                     c + ny * nx, c + 1 + ny * nx, c + 1 + nx + ny * nx, c + nx + ny * nx], -1).reshape(-1, 8)
    data = {f"sigma_{name}": sigma[:, n].ravel() for n, name in enumerate(COMPONENTS)}
    data["von_mises"] = von_mises(sigma).ravel()
    data["first_principal"] = first_principal(sigma).ravel()
    meshio.write(str(path), meshio.Mesh(points, [("hexahedron", hexa)], point_data=data))
    return Path(path)
