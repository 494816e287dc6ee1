"""The paper's qualitative findings (docs/model.md, "What the paper reports", 1-7).

Each finding is checked on computed numbers. Where the model as specified in
docs/model.md disagrees with the paper, the test is a strict xfail that states the
numbers: it fails loudly if the model ever starts to agree, so the record stays true.
"""
import math

import numpy as np
import pytest

from model import REGIMES, Params, orientation_sweep, simulate_support, uniform_array

R = REGIMES


@pytest.fixture(scope="module")
def arrays():
    return {name: uniform_array(p) for name, p in R.items()}


def test_1_stiff_no_reduction_no_transverse_dissipation(arrays):
    assert arrays["stiff"].FTx_over_mu0FN > 0.99
    assert arrays["stiff"].Dy_over_Dx < 0.02


def test_2_soft_low_friction_stored_energy_sticky(arrays):
    soft = arrays["soft"]
    assert soft.FTx_over_mu0FN == min(a.FTx_over_mu0FN for a in arrays.values())
    assert soft.Dy_over_Dx < 0.01
    assert uniform_array(Params(0.01, 0.03)).work_split["U_el"] == pytest.approx(0.7, abs=0.1)
    s = simulate_support(R["soft"], samples=2000).series  # Fig. 7b
    assert np.mean(np.hypot(s.v_x - 1, s.v_y) < 0.1) > 0.5  # long "sticky" phases


def test_3_pendulum_and_slider_transverse_motion(arrays):
    for name in ("pendulum", "slider"):
        assert 0.85 < arrays[name].FTx_over_mu0FN < 0.99  # moderate reduction
        assert 0.03 < arrays[name].Dy_over_Dx < 0.3  # "of order 0.1"
    s = simulate_support(R["pendulum"], samples=2000).series  # Fig. 7a
    assert np.all(s.F_x <= s.F_abs + 1e-12) and np.mean(np.abs(s.F_y)) > 0.1


LOADS = (0.1, 0.3, 1.0, 3.0, 10.0)


@pytest.mark.parametrize("regime", ["pendulum", "slider", "stiff"])
def test_4_larger_load_lowers_friction(regime):
    v = [uniform_array(R[regime].replace(F_N=f), tol=3e-3).FTx_over_mu0FN for f in LOADS]
    assert np.all(np.diff(v) <= 3e-3) and v[-1] < v[0] - 0.05


@pytest.mark.xfail(strict=True, reason=(
    "soft regime: F_T,x/(mu0 F_N) = 1.0008, 1.034, 0.842, 0.742, 0.687 at F_N = 0.1, 0.3, 1, "
    "3, 10: it rises above rigid contact at small loads (mu(v) peaks at v_R = V_s) before "
    "falling; the paper reports a decrease at every load"))
def test_4_soft_larger_load_lowers_friction():
    v = [uniform_array(R["soft"].replace(F_N=f), tol=3e-3).FTx_over_mu0FN for f in LOADS]
    assert np.all(np.diff(v) <= 3e-3)


def test_5_contact_count():
    k_r = (0.01, 0.03, 0.1, 0.3, 1.0, 3.0)
    nc = {kt: np.array([uniform_array(Params(kr, kt), tol=3e-3).Nc_over_Nc0 for kr in k_r])
          for kt in (0.01, 3.0)}
    for v in nc.values():
        assert np.all(v >= 1.0) and np.all(np.diff(v) < 0) and v[0] > 2
    assert np.all(nc[3.0] < nc[0.01])


def test_6_slider_length_and_fluctuations():
    r_end = {t: simulate_support(R["slider"].replace(theta0=t), samples=500).series.r[-1]
             for t in (math.pi / 4, math.pi / 2, 3 * math.pi / 4)}
    assert r_end[math.pi / 4] > 10 and r_end[math.pi / 2] > 10  # elongated
    assert r_end[3 * math.pi / 4] < 0.5  # shortened
    sw = orientation_sweep(R["slider"], np.linspace(0.05, math.pi - 0.05, 30), beta=1.0)
    assert sw.dtheta_rms.mean() < 0.05 * sw.dr_rms.mean()


@pytest.mark.xfail(strict=True, reason=(
    "pendulum (k_r = 3): r oscillates about ~1.35, not 1 (mean r = 1.36, 1.35, 1.30 for "
    "theta0 = pi/4, pi/2, 3pi/4), and Delta r_rms = 0.44 rather than ~0: the friction "
    "force f_N mu ~ 1 stretches a k_r = 3 spring by ~0.33"))
def test_6_pendulum_length_stays_near_one():
    for t in (math.pi / 4, math.pi / 2, 3 * math.pi / 4):
        r = simulate_support(R["pendulum"].replace(theta0=t), samples=500).series.r
        assert abs(r.mean() - 1.0) < 0.1
    sw = orientation_sweep(R["pendulum"], np.linspace(0.05, math.pi - 0.05, 30), beta=1.0)
    assert sw.dr_rms.mean() < 0.1


THETA = np.linspace(0, math.pi, 73)[1:-1]


@pytest.mark.parametrize("regime", ["pendulum", "slider"])
def test_7_polar_shapes(regime):
    sw = orientation_sweep(R[regime], THETA)
    edge = orientation_sweep(R[regime], [1e-3, math.pi - 1e-3])
    assert np.all(np.abs(edge.FTy_over_mu0FN) < 0.05)  # F_T,y -> 0 at theta0 -> 0, pi
    # Minima of F_T,x line up with maxima of D_y/D_x (within 0.25 rad).
    assert abs(THETA[np.argmin(sw.FTx_over_mu0FN)] - THETA[np.argmax(sw.Dy_over_Dx)]) < 0.25
    if regime == "slider":
        assert sw.FTy_over_mu0FN.min() < -0.1 and sw.FTy_over_mu0FN.max() > 0.05  # sign change


@pytest.mark.xfail(strict=True, reason=(
    "pendulum fixed arrays: F_T,y/(mu0 F_N) dips to -0.036 near theta0 = pi (at 71 pi/72), "
    "while the paper reports F_T,y >= 0 for all theta0"))
def test_7_pendulum_transverse_force_never_negative():
    sw = orientation_sweep(R["pendulum"], THETA)
    assert np.all(sw.FTy_over_mu0FN >= -1e-3)


@pytest.mark.xfail(strict=True, reason=(
    "on the fine 24 x 24 map (F_N = 1), N_c/N_c0 rises by 0.24 as k_r grows past 0.53 "
    "(1.14 -> 1.38 at k_theta = 0.01, likewise at every k_theta): not monotone in k_r as "
    "Fig. 8a suggests; the coarse trend of finding 5 holds (test_5_contact_count)"))
def test_5_contact_count_monotone_on_the_fine_map():
    from model.runs.shipped_map import load_regime_map

    m = load_regime_map()
    assert np.all(np.diff(m.Nc_over_Nc0, axis=0) <= 1e-3)


def test_friction_above_rigid_contact_near_unit_stiffness():
    """Not among the paper's findings, recorded as a model result: around k_r = k_theta
    ~ 1 the apparent friction exceeds rigid contact by up to 0.8 % (beyond its quadrature
    error), the paper's Fig. 5a shows no such increase."""
    res = uniform_array(Params(1.11, 1.11), tol=2e-4)
    assert res.FTx_over_mu0FN - 1 > 5 * res.quadrature_error["FTx_over_mu0FN"]
    assert res.FTx_over_mu0FN < 1.02
