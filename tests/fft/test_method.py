"""FFTMethod as a registered Method: protocol, settings, errors, batches, CLI."""

from __future__ import annotations

import json

import numpy as np
import pytest

from coathertz.cli import main
from coathertz.errors import CoatHertzError, ConvergenceError
from coathertz.fft.grid import Grid, grid_for_axes
from coathertz.fft.method import FFTMethod
from coathertz.fft.solver import get_backend
from coathertz.materials import RIGID
from coathertz.methods import Method, get_method

from .conftest import coated


def test_registered_and_protocol():
    m = get_method("fft", n=32)
    assert isinstance(m, FFTMethod) and isinstance(m, Method)
    assert m.name == "fft"
    json.dumps(m.settings())


def test_result_meta_is_json_and_fields_present():
    r = FFTMethod(n=32).solve(coated(2.0, 0.5))
    json.dumps(dict(r.meta))
    for k in ("iterations", "residual", "wall_time", "grid", "a_num", "a_fit", "area"):
        assert k in r.meta
    assert r.fields["pressure"].shape == (32, 32) == r.fields["displacement"].shape
    assert r.method == "fft" and r.W == 1.0


@pytest.mark.parametrize(
    ("kw", "word"),
    [
        ({"n": 8}, "n"),
        ({"n": 12.5}, "n"),
        ({"n": "many"}, "n"),
        ({"n": 5000}, "n"),
        ({"margin": 0.9}, "margin"),
        ({"interface": "glued"}, "interface"),
        ({"tol": 0.5}, "tol"),
        ({"tol": -1.0}, "tol"),
        ({"radius": "guess"}, "radius"),
        ({"backend": "fortran"}, "backend"),
    ],
)
def test_bad_settings_raise(kw, word):
    with pytest.raises(CoatHertzError, match=word):
        m = FFTMethod(**kw)
        m.solve(coated(2.0, 0.5))  # margin is checked when the grid is built


def test_bad_grid_and_spacing():
    with pytest.raises(CoatHertzError, match=r"nx .*\[16, 4096\]"):
        Grid(8, 32, 1e-6, 1e-6)
    with pytest.raises(CoatHertzError, match="dx"):
        Grid(32, 32, -1e-6, 1e-6)
    with pytest.raises(CoatHertzError, match="spacing_ratio"):
        grid_for_axes(1e-5, 1e-5, 32, 1.25, 0.0)


def test_not_converging_raises_with_tolerance_and_cap():
    with pytest.raises(ConvergenceError, match=r"tol=1e-06.*max_iter=3"):
        FFTMethod(n=32, max_iter=3).solve(coated(2.0, 0.5))


def test_batch_and_warm_start_match_single_solves():
    cases = [coated(0.5, H) for H in (0.2, 0.3, 0.4)]
    m = FFTMethod(n=48, adapt=False)
    single = [m.solve(c) for c in cases]
    for kw in ({"batch": 3}, {"batch": 1, "warm_start": True}):
        many = m.solve_many(cases, **kw)
        for a, b in zip(single, many, strict=True):
            assert b.delta == pytest.approx(a.delta, rel=1e-6)
            assert b.p0 == pytest.approx(a.p0, rel=1e-6)


def test_cupy_backend_skips_without_gpu():
    cupy = pytest.importorskip("cupy")
    if cupy.cuda.runtime.getDeviceCount() == 0:  # pragma: no cover
        pytest.skip("no CUDA device")
    get_backend("cupy")
    case = coated(2.0, 0.5)
    a = FFTMethod(n=64, backend="cupy").solve(case)
    b = FFTMethod(n=64).solve(case)
    assert a.delta == pytest.approx(b.delta, rel=1e-8)


def test_cli_json_and_fields(tmp_path, capsys):
    out = tmp_path / "f.npz"
    rc = main(["fft", "example:b4c_on_steel", "--grid", "32", "--json", "--save-fields", str(out)])
    assert rc == 0
    data = json.loads(capsys.readouterr().out)
    assert data["meta"]["grid"]["nx"] == 32 and data["delta"] > 0
    with np.load(out) as f:
        assert f["pressure"].shape == (32, 32) and f["pressure"].max() == pytest.approx(data["p0"])


def test_cli_text_and_bad_grid(capsys):
    assert main(["fft", "example:keer_case_a", "--grid", "32"]) == 0
    assert "CG iterations" in capsys.readouterr().out
    assert main(["fft", "example:keer_case_a", "--grid", "4"]) == 2
    assert "[16, 4096]" in capsys.readouterr().err


def test_solve_many_without_fields():
    cases = [coated(3.0, H) for H in (0.1, 0.2)]
    res = FFTMethod(n=32, keep_fields=False).solve_many(cases)
    assert all(r.fields == {} for r in res)
    assert res[0].meta["grid"] == res[1].meta["grid"]  # one grid per material pair


@pytest.mark.parametrize(
    "case",
    [coated(3.0, 0.3), coated(0.0, 0.05, nu_c=0.5, substrate=RIGID)],
    ids=["E3-H0.3", "rigid-base-nu0.5-H0.05"],
)
def test_preconditioned_cg_agrees_and_needs_fewer_iterations(case):
    """The kernel-inverse preconditioner changes the path, not the solution, and pays also on a
    thin incompressible layer on a rigid base (where the former ``|k|`` preconditioner cost up
    to 5x): measured at n = 64, tol 1e-10, 63 -> 22 and 17 -> 11 iterations."""
    a = FFTMethod(n=64, precondition=False, tol=1e-10).solve(case)
    b = FFTMethod(n=64, precondition=True, tol=1e-10).solve(case)
    for q in ("delta", "p0", "a"):
        assert getattr(b, q) == pytest.approx(getattr(a, q), rel=1e-8), q
    assert b.meta["iterations"] < a.meta["iterations"], (a.meta["iterations"], b.meta["iterations"])


def test_kernel_inverse_preconditioner():
    """``precondition`` undoes the convolution on the padded grid (the operator CG sees)."""
    from coathertz.fft.method import case_coefficients
    from coathertz.fft.solver import Convolver

    case = coated(3.0, 0.3)
    g = FFTMethod(n=32).grid_for(case)
    conv = Convolver(case_coefficients(case, g), get_backend())
    assert np.all(conv.khat.real > 1e-3 * conv.khat.real.max())  # positive definite
    prod = conv.mhat.real * conv.khat.real
    assert np.allclose(prod, prod.flat[0], rtol=1e-12)
    with pytest.raises(CoatHertzError, match="precondition"):
        FFTMethod(precondition=None)
