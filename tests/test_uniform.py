"""Uniform-orientation arrays (Figs. 5, 6, 8)."""
import math

import numpy as np
import pytest

from model import REGIMES, Params, mu0, orientation_sweep, uniform_array


@pytest.mark.parametrize("regime", ["pendulum", "soft"])
def test_full_circle_gives_zero_transverse_force(regime):
    res = uniform_array(REGIMES[regime], beta=1.0, tol=1e-3, full_circle=True)
    assert abs(res.FTy_over_mu0FN) <= max(3 * res.quadrature_error["FTy_over_mu0FN"], 1e-6)
    half = uniform_array(REGIMES[regime], beta=1.0, tol=1e-3)
    assert res.FTx_over_mu0FN == pytest.approx(half.FTx_over_mu0FN, abs=2e-3)


@pytest.mark.parametrize("regime", ["pendulum", "slider", "stiff", "soft"])
def test_ensemble_energy_balance_and_work_split(regime):
    res = uniform_array(REGIMES[regime])
    assert sum(res.work_split.values()) == pytest.approx(1.0, abs=1e-4)
    assert res.integration_error < 1e-4
    assert res.success and res.n_failed == 0


def test_quadrature_error_brackets_true_error_on_rough_case():
    # Slider springs: the integrand switches between stretched and compressed near 0.61 pi.
    params = REGIMES["slider"]
    dense = uniform_array(params, beta=1.0, tol=1e-6, rtol=1e-8)
    for tol in (3e-2, 1e-2, 3e-3):
        res = uniform_array(params, beta=1.0, tol=tol, rtol=1e-8)
        true = abs(res.FTx_over_mu0FN - dense.FTx_over_mu0FN)
        assert true <= res.quadrature_error["FTx_over_mu0FN"] + 2 * dense.quadrature_error["FTx_over_mu0FN"]
        assert res.quadrature_error["FTx_over_mu0FN"] <= tol


def test_refines_where_integrand_is_rough():
    rough = uniform_array(REGIMES["slider"], beta=1.0, tol=1e-4)
    smooth = uniform_array(REGIMES["stiff"], beta=1.0, tol=1e-4)
    assert rough.n_members > smooth.n_members


def test_quadrature_agrees_with_dense_orientation_average():
    params = REGIMES["pendulum"]
    res = uniform_array(params, beta=1.0, tol=1e-5, rtol=1e-8)
    theta = (np.arange(2000) + 0.5) * math.pi / 2000  # midpoint rule, smooth integrand
    sweep = orientation_sweep(params, theta, beta=1.0, rtol=1e-8)
    assert res.FTx_over_mu0FN == pytest.approx(sweep.FTx_over_mu0FN.mean(), abs=1e-5)
    assert res.Nc_over_Nc0 == pytest.approx(sweep.Nc_over_Nc0.mean(), abs=1e-5)


def test_two_averages_differ_when_durations_differ():
    res = uniform_array(REGIMES["slider"])
    assert res.FTx_over_mu0FN_duration < res.FTx_over_mu0FN - 0.02  # several per cent
    stiff = uniform_array(REGIMES["stiff"])
    assert stiff.FTx_over_mu0FN_duration == pytest.approx(stiff.FTx_over_mu0FN, abs=2e-3)


def test_rigid_limit():
    res = uniform_array(Params(k_r=1e3, k_theta=1e3), beta=1.0)
    assert res.FTx_over_mu0FN == pytest.approx(1.0, abs=1e-4)
    assert res.Nc_over_Nc0 == pytest.approx(1.0, abs=1e-3)


def test_result_is_cached_and_serialisable():
    a = uniform_array(REGIMES["stiff"], tol=2e-3)
    assert uniform_array(REGIMES["stiff"], tol=2e-3) is a
    # A theta0 the uniform array would not use is refused, not silently ignored.
    with pytest.raises(ValueError, match=r"^theta0=1.0 is not used by uniform_array"):
        uniform_array(REGIMES["stiff"].replace(theta0=1.0), tol=2e-3)
    d = a.to_dict()
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "FTy_over_mu0FN", "Dy_over_Dx",
                "Nc_over_Nc0", "beta", "work_split", "quadrature_error", "success", "message"):
        assert key in d


@pytest.mark.parametrize("kwargs, match", [
    (dict(tol=0.0), "tol"), (dict(tol=float("nan")), "tol"), (dict(beta="auto"), "beta"),
    (dict(beta=2.0), "beta"), (dict(rtol=-1.0), "rtol")])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        uniform_array(REGIMES["stiff"], **kwargs)


def test_mu0_normalisation_is_used():
    res = uniform_array(REGIMES["stiff"], beta=1.0)
    assert res.FTx_over_mu0FN * mu0() == pytest.approx(res.FTx_over_mu0FN * 1.0082432, rel=1e-6)
