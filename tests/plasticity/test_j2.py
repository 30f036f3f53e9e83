"""J2 return mapping against closed-form strain paths; consistent tangent; Newton convergence."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from coathertz.errors import CoatHertzError
from coathertz.fem.plastic.j2 import J2Plastic, equivalent_stress
from coathertz.materials import Plasticity

E, NU, Y = 200e9, 0.3, 1.0e9
LAWS = {
    "perfect": Plasticity(Y),
    "linear": Plasticity(Y, "linear", H=20e9),
    "power": Plasticity(Y, "power", n=0.2, eps0=0.002),
    "table": Plasticity(Y, "table", table=((0.0, Y), (0.002, 1.1 * Y), (0.01, 1.3 * Y), (0.05, 1.5 * Y))),
}


def _path(law: J2Plastic, comp: int, values: np.ndarray):
    """Drive one strain component through ``values`` (others 0) in increments; return stresses, ep."""
    st = law.initial_state((1,))
    out, eps_bar = [], []
    for v in values:
        e = np.zeros((4, 1))
        e[comp] = v
        sig, _, st = law.stress(e, st)
        out.append(sig[:, 0])
        eps_bar.append(st["ep"][0])
    return np.array(out), np.array(eps_bar)


def _ep_closed(pl: Plasticity, drive: float, G: float) -> float:
    """Solve ``drive - 3 G ep = Y(ep)`` (``drive`` = trial q) for ep >= 0; 0 if elastic."""
    if drive <= pl.Y:
        return 0.0
    return brentq(lambda x: drive - 3 * G * x - pl.flow_stress(x)[0], 0.0, drive / (3 * G),
                  xtol=1e-18, rtol=1e-15)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_uniaxial_strain_path(name):
    """eps_zz only: p = K eps, q = 2G |eps| - 3G ep = Y(ep); s_zz = p + 2/3 q sign, s_rr = p - q/3."""
    law = J2Plastic(E, NU, LAWS[name])
    G, K = law.shear, law.bulk
    eps = -np.linspace(0.0, 0.03, 61)[1:]  # compression, 60 increments, far into the plastic range
    sig, ep = _path(law, 1, eps)
    for k, e in enumerate(eps):
        x = _ep_closed(LAWS[name], 2 * G * abs(e), G)
        q = 2 * G * abs(e) - 3 * G * x
        s_zz, s_rr = K * e - 2 / 3 * q, K * e + 1 / 3 * q
        scale = abs(s_zz)
        assert abs(sig[k, 1] - s_zz) <= 1e-10 * scale, (name, k)
        assert abs(sig[k, 0] - s_rr) <= 1e-10 * scale and abs(sig[k, 2] - s_rr) <= 1e-10 * scale
        assert abs(ep[k] - x) <= 1e-10 * max(x, 1e-3)
    assert ep[-1] > 0.005  # the path is plastic


@pytest.mark.parametrize("name", sorted(LAWS))
def test_pure_shear_strain_path(name):
    """gamma_rz only: q = sqrt(3) tau, sqrt(3) G gamma - 3 G ep = Y(ep), tau = (Y(ep)) / sqrt(3)."""
    law = J2Plastic(E, NU, LAWS[name])
    G = law.shear
    gam = np.linspace(0.0, 0.05, 51)[1:]
    sig, ep = _path(law, 3, gam)
    for k, g in enumerate(gam):
        x = _ep_closed(LAWS[name], math.sqrt(3) * G * g, G)
        tau = G * (g - math.sqrt(3) * x)
        assert abs(sig[k, 3] - tau) <= 1e-10 * tau, (name, k)
        assert np.all(np.abs(sig[k, :3]) <= 1e-10 * tau)
        assert abs(ep[k] - x) <= 1e-10 * max(x, 1e-3)
    assert ep[-1] > 0.01


def _random_states(law: J2Plastic, n: int, seed: int):
    rng = np.random.default_rng(seed)
    pre = rng.normal(size=(4, n)) * 6e-3
    st = law.initial_state((n,))
    _, _, st = law.stress(pre, st)  # some history
    eps = pre + rng.normal(size=(4, n)) * 4e-3
    return eps, st


@pytest.mark.parametrize("name", sorted(LAWS))
def test_consistent_tangent_matches_finite_differences(name):
    law = J2Plastic(E, NU, LAWS[name])
    eps, st = _random_states(law, 40, seed=3)
    _, D, new = law.stress(eps, st)
    plastic = new["ep"] > st["ep"]
    assert plastic.sum() >= 10 and (~plastic).sum() >= 1, "the sample must hold plastic and elastic points"
    h = 1e-8
    for j in range(4):
        de = np.zeros_like(eps)
        de[j] = h
        sp_, _, _ = law.stress(eps + de, st)
        sm_, _, _ = law.stress(eps - de, st)
        fd = (sp_ - sm_) / (2 * h)
        err = np.abs(fd - D[:, j]).max() / np.abs(D).max()
        assert err < 1e-6, f"column {j}: max rel. difference {err:.2e}"
    assert np.allclose(D, np.swapaxes(D, 0, 1), rtol=1e-12, atol=1e-6 * np.abs(D).max())


def _uniaxial_stress_newton(law: J2Plastic, ezz: float, tangent: str):
    """Find eps_rr = eps_tt with sigma_rr = 0 at eps_zz given (one plastic step from zero)."""
    st = law.initial_state(())
    x, hist = 0.0, []
    for _ in range(60):
        e = np.array([x, ezz, x, 0.0])
        sig, D, _ = law.stress(e, st)
        r = sig[0]
        hist.append(abs(r))
        if abs(r) < 1e-6:  # [Pa]: round-off level for stresses ~1e9 Pa
            break
        Dt = D if tangent == "consistent" else law.elastic_matrix()
        x -= r / (Dt[0, 0] + Dt[0, 2])
    return x, np.array(hist)


def test_newton_converges_quadratically_with_the_consistent_tangent():
    law = J2Plastic(E, NU, LAWS["power"])
    x, hist = _uniaxial_stress_newton(law, -0.02, "consistent")
    _, hist_el = _uniaxial_stress_newton(law, -0.02, "elastic")
    # quadratic: r_{k+1} / r_k^2 bounded (scaled by the stress level) once in the basin
    r = hist / Y
    ratios = r[1:-1][r[:-2] < 1e-2] / r[:-2][r[:-2] < 1e-2] ** 2
    assert len(hist) <= 7, f"consistent tangent: residual history {hist}"
    assert len(ratios) >= 1 and np.all(ratios < 10.0), f"r_(k+1)/r_k^2 = {ratios}"
    assert len(hist_el) > 3 * len(hist), f"elastic tangent: {len(hist_el)} iterations vs {len(hist)}"
    sig, _, st = law.stress(np.array([x, -0.02, x, 0.0]), law.initial_state(()))
    assert abs(equivalent_stress(sig) - law.plasticity.flow_stress(st["ep"])[0]) < 1e-9 * Y


def test_unloading_is_elastic_and_reloading_retraces():
    law = J2Plastic(E, NU, LAWS["linear"])
    st = law.initial_state((1,))
    e = np.zeros((4, 1))
    e[1] = -0.01
    s1, _, st = law.stress(e, st)
    ep1 = st["ep"].copy()
    e2 = e.copy()
    e2[1] = -0.008
    s2, D2, st2 = law.stress(e2, st)
    assert np.array_equal(st2["ep"], ep1)
    assert np.allclose(s2 - s1, law.elastic_matrix() @ (e2 - e), rtol=1e-12)
    assert np.allclose(D2[..., 0], law.elastic_matrix())
    s3, _, st3 = law.stress(e, st2)  # back to the old strain: same stress, still elastic
    assert np.allclose(s3, s1, rtol=1e-12) and np.array_equal(st3["ep"], ep1)


@pytest.mark.parametrize("kw, word", [
    ({"Y": -1.0}, "yield stress Y"),
    ({"Y": 1e9, "hardening": "kinematic"}, "hardening must be one of"),
    ({"Y": 1e9, "hardening": "linear", "H": -1.0}, "0 <= H"),
    ({"Y": 1e9, "hardening": "power", "n": 1.5, "eps0": 0.01}, "0 <= n < 1"),
    ({"Y": 1e9, "hardening": "power", "n": 0.1}, "eps0"),
    ({"Y": 1e9, "hardening": "table", "table": ((0.0, 1e9), (0.0, 2e9))}, "ep increasing"),
    ({"Y": 1e9, "hardening": "table", "table": ((0.0, 2e9), (0.1, 3e9))}, "start at"),
])
def test_bad_plasticity_input(kw, word):
    with pytest.raises(CoatHertzError, match=word):
        Plasticity(**kw)


def test_table_and_power_flow_stress():
    tab = LAWS["table"]
    Yv, dY = tab.flow_stress(np.array([0.0, 0.001, 0.006, 0.2]))
    assert np.allclose(Yv, [Y, 1.05 * Y, 1.2 * Y, 1.5 * Y]) and np.allclose(dY, [50 * Y, 50 * Y, 25 * Y, 0])
    pw = LAWS["power"]
    assert np.isclose(pw.flow_stress(0.002)[0], Y * 2**0.2)
