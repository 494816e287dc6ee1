"""Fixed-orientation arrays and orientation sweeps (Figs. 9-11)."""
import math

import numpy as np
import pytest

from model import REGIMES, fixed_orientation, mu0, orientation_sweep, simulate_support

THETA = np.linspace(0.1, math.pi - 0.1, 12)


@pytest.mark.parametrize("regime", ["pendulum", "slider", "soft"])
def test_even_and_odd_in_theta0(regime):
    up = orientation_sweep(REGIMES[regime], THETA, beta=1.0)
    down = orientation_sweep(REGIMES[regime], -THETA, beta=1.0)
    np.testing.assert_allclose(down.FTx_over_mu0FN, up.FTx_over_mu0FN, rtol=1e-10)
    np.testing.assert_allclose(down.FTy_over_mu0FN, -up.FTy_over_mu0FN, atol=1e-12)
    np.testing.assert_allclose(down.Dy_over_Dx, up.Dy_over_Dx, rtol=1e-9)


def test_sweep_matches_single_supports():
    sweep = orientation_sweep(REGIMES["pendulum"], THETA, beta=0.7, rtol=1e-8)
    m0 = mu0()
    for i in (0, 5, 11):
        one = simulate_support(REGIMES["pendulum"].replace(theta0=THETA[i], beta=0.7), rtol=1e-8)
        assert sweep.FTx_over_mu0FN[i] == pytest.approx(one.F_mean[0] / m0, rel=1e-12)
        assert sweep.Nc_over_Nc0[i] == pytest.approx(one.t_out / 10.0, rel=1e-12)


def test_self_consistent_sweep_solves_every_orientation():
    sweep = orientation_sweep(REGIMES["soft"], THETA)
    np.testing.assert_allclose(sweep.beta, 1 / sweep.Nc_over_Nc0, rtol=1e-7)
    assert np.all(np.abs(sweep.beta_residual) < 1e-7) and np.all(sweep.success)


@pytest.mark.parametrize("regime", ["pendulum", "slider", "stiff", "soft"])
def test_work_split_sums_to_one(regime):
    res = fixed_orientation(REGIMES[regime].replace(theta0=2.0))
    assert sum(res.work_split.values()) == pytest.approx(1.0, abs=1e-5)
    assert res.work_split["D_x"] > 0 and res.work_split["D_y"] >= 0


def test_fixed_result_fields():
    res = fixed_orientation(REGIMES["stiff"], beta=1.0)
    d = res.to_dict()
    for key in ("FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0", "work_split",
                "dtheta_rms", "dr_rms", "beta", "success", "message", "r_min", "r_max"):
        assert key in d
    assert 0.0 <= res.r_min <= 1.0 <= res.r_max
    assert res.beta == 1.0 and res.beta_residual == 0.0


@pytest.mark.parametrize("kwargs, match", [
    (dict(beta="half"), "beta"), (dict(beta=1.5), "beta"), (dict(beta=0.0), "beta"),
    (dict(rtol=1.0), "rtol"), (dict(method="euler"), "method")])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        fixed_orientation(REGIMES["stiff"], **kwargs)


@pytest.mark.parametrize("theta0", [[], [float("nan")], [7.0]])
def test_bad_orientations(theta0):
    with pytest.raises(ValueError, match="theta0"):
        orientation_sweep(REGIMES["stiff"], theta0)


def test_callers_arrays_stay_writable():
    theta = np.array([0.5, 1.0])
    orientation_sweep(REGIMES["stiff"], theta)
    theta[0] = 0.6  # would raise if the sweep had frozen the caller's array
    assert theta.flags.writeable


@pytest.mark.parametrize("regime, F_N", [
    ("pendulum", 0.1), ("pendulum", 3.0), ("pendulum", 10.0), ("soft", 0.1), ("soft", 3.0),
    pytest.param("soft", 10.0, marks=pytest.mark.slow)])
def test_array_members_agree_with_scipy_reference(regime, F_N):
    """The members of an array (one batched kernel call) against scipy at rtol 1e-11 (DOP853;
    Radau at F_N = 10, where the contacts are stiff), one support at a time: exit time, mean
    friction and energy split."""
    params = REGIMES[regime].replace(F_N=F_N)
    theta0 = np.array([0.4, 1.3, 2.2, 3.0])
    s = orientation_sweep(params, theta0, beta=0.7, rtol=1e-9)
    for i, t in enumerate(theta0):
        ref = simulate_support(params.replace(theta0=float(t), beta=0.7), rtol=1e-11,
                               method="reference-radau" if F_N >= 10 else "reference",
                               max_steps=5_000_000)
        c = s.contacts
        assert c.t_out[i] == pytest.approx(ref.t_out, rel=1e-6)
        assert c.F_x[i] == pytest.approx(ref.F_mean[0], abs=1e-6)
        assert c.D_y[i] == pytest.approx(ref.D_y, abs=1e-5 * ref.W)
        assert c.r_max[i] == pytest.approx(ref.r_max, rel=1e-3)
