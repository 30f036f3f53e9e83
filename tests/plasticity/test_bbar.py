"""The B-bar assembler: patch test (linear volumetric strain reproduced exactly) and agreement of
the plain form with the elastic model's stiffness."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fem.farfield import BoussinesqFarField
from coathertz.fem.material import LinearElastic
from coathertz.fem.mesh import MeshSpec, build_mesh
from coathertz.fem.model import FEModel, Region
from coathertz.fem.plastic.assembly import BBarAssembler
from coathertz.materials import Material


@pytest.fixture(scope="module")
def model():
    lm = build_mesh(1e-4, 2e-5, MeshSpec(n_a=6, L=8.0, growth=1.6), False)
    law = LinearElastic(200e9, 0.3)
    regs = [Region(lm.coating, LinearElastic(400e9, 0.25)), Region(lm.substrate, law)]
    return FEModel(lm, regs, Material(200e9, 0.3), BoussinesqFarField())


@pytest.mark.parametrize("bbar", [True, False])
def test_patch_quadratic_displacement(model, bbar):
    """u_r = c r + d r^2, u_z = e z + f r z: div u is linear in (r, z), so the projection keeps it."""
    x, z = model.basis.doflocs
    c, d, e, f = 1e-3, 2.0, -5e-4, 3.0
    u = np.where(model.comp == 0, c * x + d * x**2, e * z + f * x * z)
    regs = [(reg.elements, reg.law) for reg in model.regions]
    A = BBarAssembler(model.basis, regs, bbar=bbar)
    for els, _ in regs:
        eps = A.strain(u, els)
        r, zz = A.rq[els], A.zq[els]
        exact = np.array([c + 2 * d * r, e + f * r, c + d * r, f * zz])
        assert np.abs(eps - exact).max() < 1e-10 * np.abs(exact).max()


def test_plain_form_matches_the_elastic_stiffness(model):
    regs = [(reg.elements, reg.law) for reg in model.regions]
    A = BBarAssembler(model.basis, regs, bbar=False)
    u = np.random.default_rng(1).normal(size=model.n_u) * 1e-6
    F, K, _, _ = A.evaluate(u, [law.initial_state(()) for _, law in regs])
    K0 = model.stiffness()
    assert abs(K - K0).max() < 1e-12 * abs(K0).max()
    assert np.abs(F - K0 @ u).max() < 1e-12 * np.abs(F).max()
    Kb = BBarAssembler(model.basis, regs, bbar=True).evaluate(u, [{}, {}])[1]
    assert abs(Kb - Kb.T).max() < 1e-12 * abs(Kb).max()  # B-bar tangent of an elastic law is symmetric
