"""The Newton loop's assembly (``BBarAssembler.evaluate(..., stresses=False)``: the law only at the
elements that may depart from elasticity, ``F_int = K^E u`` plus their correction) against the
assembly over every element, on a coated body (an elastic coating: a linear law; a J2 substrate)
at a loaded state with yielded points and at an unloaded one where the yielded points keep their
plastic strain but respond elastically."""

from __future__ import annotations

import numpy as np
import pytest

from coathertz.fem.farfield import BoussinesqFarField
from coathertz.fem.material import LinearElastic
from coathertz.fem.mesh import MeshSpec, build_mesh
from coathertz.fem.model import FEModel, Region
from coathertz.fem.plastic.assembly import BBarAssembler
from coathertz.fem.plastic.j2 import J2Plastic
from coathertz.materials import Material, Plasticity


@pytest.fixture(scope="module")
def setup():
    a = 1e-4
    lm = build_mesh(a, 2e-5, MeshSpec(n_a=6, L=8.0, growth=1.6), False)
    j2 = J2Plastic(200e9, 0.3, Plasticity(1e9))
    regs = [Region(lm.coating, LinearElastic(400e9, 0.25)), Region(lm.substrate, j2)]
    model = FEModel(lm, regs, Material(200e9, 0.3), BoussinesqFarField())
    asm = BBarAssembler(model.basis, [(reg.elements, reg.law) for reg in regs])
    r, z = model.basis.doflocs
    # a smooth dent 1 % of the contact radius deep: strains ~ 1e-2 >> Y/E = 5e-3 under it
    u = np.where(model.comp == 1, -1e-6 * np.exp(-(r**2 + z**2) / a**2), 0.0)
    states = [law.initial_state(asm.w[els].shape) for els, law in asm.regions]
    return asm, u, states


def _compare(asm, u, states):
    F0, K0, _, st0 = asm.evaluate(u, states)
    F1, K1, sig1, st1 = asm.evaluate(u, states, stresses=False)
    assert sig1 is None
    # F_int = K^E u + corrections: round-off of K^E u, whose terms are up to |K^E| |u|
    KE = asm.elastic_matrix(np.ones(asm.w.shape[0], dtype=bool))
    scale = float(np.max(abs(KE) @ np.abs(u)))
    err = float(np.max(np.abs(F1 - F0))) / scale
    assert err < 1e-13, f"internal force differs by {err:.2e} of max(|K^E| |u|)"
    assert np.array_equal(np.sort(K0.nonelastic), np.sort(K1.nonelastic))
    errK = float(abs(K1 - K0).max() / abs(K0).max())
    assert errK < 1e-13, f"tangent differs by {errK:.2e} (relative)"
    for a, b in zip(st0, st1, strict=True):
        assert a.keys() == b.keys()
        for k in a:
            assert np.allclose(a[k], b[k], rtol=0, atol=1e-13 * max(float(np.abs(a[k]).max()), 1e-300)), k
    return K0, st0


def test_loaded_and_unloaded_states(setup):
    asm, u, states = setup
    K, trial = _compare(asm, u, states)
    n_yield = len(K.nonelastic)
    assert n_yield > 5, n_yield  # the test must see yielded elements
    assert float(trial[1]["ep"].max()) > 1e-3
    # unloaded to 40 %: the yielded points keep their plastic strain and respond elastically
    K2, _ = _compare(asm, 0.4 * u, trial)
    assert len(K2.nonelastic) < n_yield


def test_element_stiffness_is_the_quadrature_sum(setup):
    """``_element_stiffness`` (two batched matrix products on the element-major operator) against
    the quadrature sum ``sum_q w B^T D B`` written out as one einsum over ``[4, 18, nel, nq]``, with
    a random symmetric ``D`` per point: the same matrices to 1e-13 of their largest entry (round-off
    of a 36-term sum of products; measured 5e-16 on the deep benchmark path)."""
    asm = setup[0]
    rng = np.random.default_rng(3)
    Bq, w, Be = asm._Bq[1], asm._wq[1], asm._Be[1]
    ne, nq = w.shape
    A = rng.standard_normal((ne, nq, 4, 4))
    D = (A + A.transpose(0, 1, 3, 2)).transpose(2, 3, 0, 1) * 1e11  # [4, 4, nel, nq] symmetric
    ref = np.einsum("iaeq,ijeq,jbeq,eq->eab", Bq, D, Bq, w)
    Ke = asm._element_stiffness(Be, D, w)
    err = float(np.abs(Ke - ref).max() / np.abs(ref).max())
    assert err < 1e-13, f"element stiffness differs from the quadrature sum by {err:.2e} (relative)"
