"""Memory guard: a mesh too large for the machine is refused before it is built."""

from __future__ import annotations

import time
import tracemalloc

import pytest

from coathertz.case import ContactCase
from coathertz.errors import CoatHertzError
from coathertz.fem.mesh import MESH_LEVELS, build_mesh, mesh_size
from coathertz.fem.method import FEMMethod, estimate_memory
from coathertz.materials import RIGID, Body, Coating, Material

STEEL = Material(200e9, 0.3)


def _thin(H: float) -> ContactCase:
    c0 = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(400e9, 0.3), 1.0, STEEL)
    return c0.with_thickness(H * c0.a0s)


def _refused(case: ContactCase, **kw) -> tuple[str, float, float]:
    """Message, seconds and peak traced allocation [bytes] of a refused solve."""
    tracemalloc.start()
    t = time.perf_counter()
    try:
        with pytest.raises(CoatHertzError) as info:
            FEMMethod(**kw).solve(case)
        return str(info.value), time.perf_counter() - t, tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_H_1e_6_is_refused_without_allocating():
    """Before: the default mesh grew to 23 GB and was killed after 198 s. Now: refused in
    milliseconds; measured peak traced allocation 5 kB (estimate 2.7e6 elements, 224 GiB)."""
    msg, secs, peak = _refused(_thin(1e-6))
    assert peak < 5e6 and secs < 2.0, (peak, secs)
    for word in ("mesh='default'", "H = h/a = 1e-06", "max_memory_gb = ", "GiB", "fft", "coarse"):
        assert word in msg, (word, msg)


def test_very_soft_coating_is_refused_and_says_a_over_R():
    """Ec = 1e-3 Pa: a ~ 58 mm on R = 10 mm (before: MemoryError for 1.78 M elements)."""
    case = ContactCase.sphere_on_coated_half_space(10e-3, 1.0, Material(1e-3, 0.3), 1e-6, STEEL)
    msg, secs, peak = _refused(case)
    assert peak < 20e6 and secs < 2.0, (peak, secs)
    assert "a/R" in msg and "very thin" in msg, msg


def test_budget_is_respected_on_an_ordinary_case():
    msg, _, _ = _refused(_thin(0.3), mesh="coarse", max_memory_gb=0.05)
    assert "20 elements across the contact radius" in msg and "max_memory_gb = 0.05" in msg, msg
    with pytest.raises(CoatHertzError, match="max_memory_gb"):
        FEMMethod(max_memory_gb=-1.0)


@pytest.mark.parametrize(
    ("h", "nu_c", "nu_s", "rigid"),
    [(0.0, 0.3, 0.3, False), (1e-6, 0.25, 0.3, False), (3e-6, 0.5, 0.3, False), (1e-5, 0.3, 0.5, False),
     (2e-5, 0.5, 0.3, True), (5e-7, 0.3, 0.3, True)],
)
def test_estimated_unknowns_are_exact(h, nu_c, nu_s, rigid):
    """The estimate counts exactly the unknowns the model assembles (without building it)."""
    from coathertz.fem.farfield import BoussinesqFarField
    from coathertz.fem.material import LinearElastic
    from coathertz.fem.model import FEModel, Region

    a = 3e-5
    spec = MESH_LEVELS["coarse"]
    size = mesh_size(a, h, spec, rigid)
    lm = build_mesh(a, h, spec, rigid)
    regions = []
    if h > 0:
        regions.append(Region(lm.coating, LinearElastic(400e9, nu_c), nu_c >= 0.45))
    if not rigid:
        els = lm.substrate if h > 0 else range(lm.n_elements)
        regions.append(Region(els, LinearElastic(200e9, nu_s), nu_s >= 0.45))
    model = FEModel(lm, regions, None if rigid else STEEL, BoussinesqFarField())
    model.stiffness()
    dofs, mem = estimate_memory(size, h > 0 and nu_c >= 0.45, not rigid and nu_s >= 0.45)
    assert size.elements == lm.n_elements
    assert dofs == model.n_dofs
    assert mem > 0


def test_cli_reports_the_refusal(tmp_path, capsys):
    from coathertz.cli import main

    f = tmp_path / "thin.toml"
    f.write_text('W = "1 N"\n[body1]\nmaterial = "rigid"\nR = "10 mm"\n'
                 '[body2]\nmaterial = { E = "200 GPa", nu = 0.3 }\n'
                 'coating = { E = "400 GPa", nu = 0.3, h = "3e-11 m" }\n')
    assert main(["fem", str(f)]) == 2
    err = capsys.readouterr().err
    assert "max_memory_gb" in err and "very thin" in err, err


def test_rigid_body_case_needs_no_guard_bypass():
    """The guard runs on every remesh too (a rigid base, coarse: ordinary size, solves)."""
    case = ContactCase(Body.rigid_sphere(0.01), Body(RIGID, Coating(Material(200e9, 0.3), 20e-6)), 1.0)
    r = FEMMethod(mesh="coarse").solve(case)
    assert r.meta["dofs"] == estimate_memory(
        mesh_size(r.meta["a_ref"], 20e-6, MESH_LEVELS["coarse"], True), False, False)[0]
