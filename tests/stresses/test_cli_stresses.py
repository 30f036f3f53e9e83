"""``coathertz stresses``: JSON keys, numbers and one-line errors."""

from __future__ import annotations

import json

import pytest

from coathertz.cli import main

BASE = ["--substrate", "200 GPa,0.3", "--W", "100 N", "--R", "10 mm"]
KEYS = ("vm_max_coating", "vm_max_substrate", "vm_max", "tensile_max_surface", "tensile_max",
        "interface_shear_max", "interface_normal_max")


def test_json_homogeneous(capsys):
    assert main(["stresses", *BASE, "--grid", "64", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert all(k in d for k in KEYS)
    vm = d["vm_max"]
    # Hertz: 0.620 p0 at z = 0.48a on the axis (measured 0.620 p0 at 0.475a with n = 128)
    assert vm["over_p0"] == pytest.approx(0.620, abs=0.006)
    assert vm["at"][2] / d["a"] == pytest.approx(0.48, abs=0.03)
    assert d["vm_max_coating"] is None and d["interface_shear_max"] is None
    assert d["tensile_max_surface"]["over_p0"] == pytest.approx((1 - 0.6) / 3, abs=0.01)


def test_json_coated_sliding(capsys):
    args = ["stresses", *BASE, "--coating", "400 GPa,0.25,30 um", "--mu", "0.3", "--grid",
            "64", "--json"]
    assert main(args) == 0
    d = json.loads(capsys.readouterr().out)
    for k in KEYS:
        e = d[k]
        assert set(e) == {"value", "over_p0", "at"} and len(e["at"]) == 3
    assert d["interface_shear_max"]["at"][2] == pytest.approx(30e-6)
    assert d["vm_max_coating"]["at"][2] <= 30e-6 < d["vm_max_substrate"]["at"][2]
    # sliding tension at the trailing edge (x < 0), on the surface
    assert d["tensile_max_surface"]["at"][0] < 0


@pytest.mark.parametrize("extra, text", [
    (["--mu", "-0.1"], "--mu: friction coefficient must be in [0, 1]"),
    (["--depths", "-5"], "--depths: body2 depth -5 um outside the body"),
    (["--substrate", "rigid", "--coating", "400 GPa,0.25,30 um", "--depths", "40"],
     "--depths: body2 depth 40 um outside the body (valid: 0 to 30 um)"),
])
def test_bad_input_one_line(capsys, extra, text):
    assert main(["stresses", *BASE, *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert text in err and "\n" not in err and "Traceback" not in err


def test_png_and_vtu_files(tmp_path, capsys):
    """--png draws the slices; --vtu holds the whole field: one point per (x, y, z) of the
    lattice, the six components, and a von Mises maximum equal to the printed one."""
    meshio = pytest.importorskip("meshio")
    png, vtu = tmp_path / "s.png", tmp_path / "s.vtu"
    args = ["stresses", *BASE, "--coating", "400 GPa,0.25,30 um", "--grid", "32", "--json",
            "--png", str(png), "--vtu", str(vtu)]
    assert main(args) == 0
    d = json.loads(capsys.readouterr().out)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    m = meshio.read(vtu)
    nz = len(d["depths"])
    assert m.points.shape == (nz * 32 * 32, 3)
    assert m.cells_dict["hexahedron"].shape == ((nz - 1) * 31 * 31, 8)
    assert {f"sigma_{c}" for c in ("xx", "yy", "zz", "yz", "xz", "xy")} <= set(m.point_data)
    assert float(m.point_data["von_mises"].max()) == pytest.approx(d["vm_max"]["value"], rel=1e-12)
    assert m.points[:, 2].max() == 0.0 and m.points[:, 2].min() == pytest.approx(-max(d["depths"]))


@pytest.mark.parametrize("flag, name, words", [
    ("--png", "out.jpg", "must end in .png"),
    ("--vtu", "out.vtk", "must end in .vtu"),
    ("--vtu", "missing/out.vtu", "does not exist"),
])
def test_bad_output_file_is_refused_before_solving(tmp_path, capsys, flag, name, words):
    assert main(["stresses", *BASE, "--grid", "32", flag, str(tmp_path / name)]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1


def test_partial_slip_between_frictionless_and_sliding(capsys):
    # measured on 64^2 (W = 100 N, mu = 0.3): surface tension 0.133 (Q = 0), 0.404 (Q = 15 N),
    # 0.550 (Q = 29.7 N), 0.552 p0 (full sliding)
    out = {}
    for extra in ([], ["--mu", "0.3", "--Q", "15 N"], ["--mu", "0.3", "--Q", "29.7 N"],
                  ["--mu", "0.3"]):
        assert main(["stresses", *BASE, "--grid", "64", "--json", *extra]) == 0
        d = json.loads(capsys.readouterr().out)
        out[d["Q"], d["mu"]] = d["tensile_max_surface"]["over_p0"]
    t0, t_half, t_near, t_slide = out.values()
    assert t0 < t_half < t_near <= t_slide * (1 + 1e-9), out
    assert t_near == pytest.approx(t_slide, rel=0.02), out


@pytest.mark.parametrize(("extra", "text"), [
    (["--mu", "0.3", "--Q", "30 N"], "the contact slides"),
    (["--mu", "0.3", "--Q=-1 N"], "--Q: tangential load Q"),
    (["--Q", "1 N"], "--Q: partial slip needs a friction coefficient --mu > 0"),
    (["--coating", "400 GPa,0.25,10 um", "--coating", "200 GPa,0.3,20 um", "--mu", "0.3",
      "--Q", "1 N"], "stack of 2 layers is not modelled yet"),
])
def test_partial_slip_bad_input_one_line(capsys, extra, text):
    assert main(["stresses", *BASE, "--grid", "32", *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert text in err and len(err.splitlines()) == 1, err


def test_partial_slip_coated_cli(capsys):
    """A single coating takes partial slip through its layered tangential compliance: the stick
    zone shrinks as Q grows and the surface tension rises towards full sliding (64^2 grid)."""
    coat = ["--coating", "400 GPa,0.25,30 um", "--grid", "64", "--json", "--mu", "0.3"]
    out = []
    for Q in ("5 N", "20 N"):
        assert main(["stresses", *BASE, *coat, "--Q", Q]) == 0
        out.append(json.loads(capsys.readouterr().out)["tensile_max_surface"]["over_p0"])
    assert main(["stresses", *BASE, *coat]) == 0
    slide = json.loads(capsys.readouterr().out)["tensile_max_surface"]["over_p0"]
    assert out[0] < out[1] <= slide * (1 + 1e-9), (out, slide)


def test_partial_slip_too_many_cells_is_refused(capsys):
    """The dense partial-slip solve is bounded (MAX_CONTACT_CELLS): at the default 128^2 grid a
    circular contact has about 8000 cells, refused in one line that names a grid that fits."""
    assert main(["stresses", *BASE, "--mu", "0.3", "--Q", "1 N"]) == 2
    err = capsys.readouterr().err.strip()
    assert "use a coarser grid (--grid" in err and len(err.splitlines()) == 1, err


def test_json_axisym_matches_fft(capsys):
    """--method axisym: the same keys, the exact maxima (radii clustered at the edge, r = a
    included) and the FFT's within its discretisation. Measured on the coated case (128^2 FFT):
    von Mises maxima equal to 3e-4 p0."""
    coat = ["--coating", "400 GPa,0.25,30 um"]
    d = {}
    for m in ("axisym", "fft"):
        assert main(["stresses", *BASE, *coat, "--method", m, "--json"]) == 0
        d[m] = json.loads(capsys.readouterr().out)
    ax, ff = d["axisym"], d["fft"]
    assert all(ax[k] is not None for k in KEYS)
    for k in ("vm_max", "vm_max_coating", "vm_max_substrate", "interface_shear_max"):
        assert ax[k]["over_p0"] == pytest.approx(ff[k]["over_p0"], abs=2e-3), k
    # the surface tension peaks just outside the edge under this stiff coating (measured 0.2222
    # p0 at 1.1a: the FFT's 64 cells across the domain see 0.221 at 1.09a)
    r_t = ax["tensile_max_surface"]["at"][0] / ax["a"]
    assert 1.0 <= r_t <= 1.2 and ax["tensile_max_surface"]["at"][1:] == [0.0, 0.0]
    assert ax["tensile_max_surface"]["over_p0"] == pytest.approx(
        ff["tensile_max_surface"]["over_p0"], abs=0.01)
    assert ax["vm_max_coating"]["at"][2] <= 30e-6 < ax["vm_max_substrate"]["at"][2]


def test_axisym_homogeneous_known_maxima(capsys):
    assert main(["stresses", *BASE, "--method", "axisym", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    # default depths: 0 to a in steps of a/40, so the maximum 0.6202 p0 at 0.481a is sampled at
    # 0.475a (0.6201 p0); the surface tension is exact: (1 - 2 nu)/3 at r = a
    assert d["vm_max"]["over_p0"] == pytest.approx(0.620, abs=1e-3)
    assert d["tensile_max_surface"]["over_p0"] == pytest.approx(0.4 / 3, abs=1e-12)
    assert d["vm_max_coating"] is None and d["interface_shear_max"] is None


def test_axisym_stack(capsys):
    """A layer stack is solved by --method axisym (and fft, test_fft_stack_stresses); the interfaces are all
    scanned (the shear maximum lies on one of them)."""
    stack = ["--coating", "300 GPa,0.2,10 um", "--coating", "150 GPa,0.3,15 um"]
    assert main(["stresses", *BASE, *stack, "--method", "axisym", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["interface_shear_max"]["at"][2] in (pytest.approx(10e-6), pytest.approx(25e-6))
    assert d["vm_max_coating"]["at"][2] <= 25e-6


@pytest.mark.parametrize(("extra", "text"), [
    (["--mu", "0.2"], "--method axisym: the exact method gives the frictionless normal solution only"),
    (["--R", "10 mm", "--depths", "1e-9"], "too close to the surface"),
    (["--coating", "300 GPa,0.2,50 nm"], "is thinner than the smallest depth the Hankel quadrature"),
])
def test_axisym_bad_input_one_line(capsys, extra, text):
    assert main(["stresses", *BASE, "--method", "axisym", *extra]) == 2
    # the 50 nm layer also warns (Legendre modes capped): one error line after it
    lines = [ln for ln in capsys.readouterr().err.strip().splitlines() if "warning:" not in ln]
    assert len(lines) == 1 and text in lines[0], lines


def test_json_fem_matches_axisym(capsys):
    """--method fem: the FE's recovered stresses on the same r-z points as the exact method.
    Measured on the coated case (default mesh): von Mises maxima within 1e-4 p0 of the exact
    ones, interface shear 0.2257 against 0.2250 p0, surface tension 0.2225 against 0.2223 p0."""
    coat = ["--coating", "400 GPa,0.25,30 um"]
    d = {}
    for m in ("axisym", "fem"):
        assert main(["stresses", *BASE, *coat, "--method", m, "--json"]) == 0
        d[m] = json.loads(capsys.readouterr().out)
    ax, fe = d["axisym"], d["fem"]
    assert all(fe[k] is not None for k in KEYS)
    for k in ("vm_max", "vm_max_coating", "vm_max_substrate", "interface_shear_max"):
        assert fe[k]["over_p0"] == pytest.approx(ax[k]["over_p0"], abs=2e-3), k
    assert fe["tensile_max_surface"]["over_p0"] == pytest.approx(
        ax["tensile_max_surface"]["over_p0"], abs=0.01)


def test_fem_with_friction_is_refused(capsys):
    assert main(["stresses", *BASE, "--method", "fem", "--mu", "0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--method fem: the FE model is frictionless" in err and len(err.splitlines()) == 1
