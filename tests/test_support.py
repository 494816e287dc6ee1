"""simulate_support: physics invariants, agreement with scipy, hard cases, budgets."""
import math

import numpy as np
import pytest

from model import REGIMES, IntegrationError, Params, mu0, simulate_support

SLIDER = REGIMES["slider"]
HARD = {
    "compliant F_N=10": Params(k_r=0.01, k_theta=0.01, F_N=10.0),
    "slider theta0=0": SLIDER.replace(theta0=0.0),
    "slider theta0=pi": SLIDER.replace(theta0=math.pi),
    "slider theta0=pi+1e-6": SLIDER.replace(theta0=math.pi + 1e-6),
    "slider theta0=pi-1e-6": SLIDER.replace(theta0=math.pi - 1e-6),
    "stiff F_N=3 near pi": REGIMES["stiff"].replace(F_N=3.0, theta0=math.pi - 1e-3),
}
CASES = {**REGIMES, **HARD}


def _cost(res):
    """Work in right-hand-side evaluations; a Jacobian + LU + solves counts as 6."""
    return res.stats["n_rhs"] + 6 * res.stats["n_jac"]


@pytest.mark.parametrize("name", CASES)
def test_energy_balance_closes(name):
    res = simulate_support(CASES[name], rtol=1e-8)
    assert res.success, res.message
    assert res.relative_energy_residual < 1e-6
    assert res.D_x >= 0 and res.D_y >= 0 and res.K >= 0


@pytest.mark.parametrize("theta0", [0.3, math.pi / 2, 2.5, 3.0])
@pytest.mark.parametrize("regime", ["pendulum", "slider", "soft"])
def test_mirror_symmetry(regime, theta0):
    up = simulate_support(REGIMES[regime].replace(theta0=theta0), rtol=1e-9)
    down = simulate_support(REGIMES[regime].replace(theta0=-theta0), rtol=1e-9)
    mirror = np.array([1, -1, 1, -1, -1])
    np.testing.assert_allclose(down.state_out[:4], mirror[:4] * up.state_out[:4], atol=1e-10)
    assert down.state_out[4] + theta0 == pytest.approx(-(up.state_out[4] - theta0), abs=1e-10)
    assert down.t_out == pytest.approx(up.t_out, rel=1e-12)
    assert down.F_mean[0] == pytest.approx(up.F_mean[0], rel=1e-10)
    assert down.F_mean[1] == pytest.approx(-up.F_mean[1], abs=1e-12)


# Final-state error against DOP853 at rtol 1e-12 allowed at rtol 1e-9. Global error
# grows with the contact length (tau_out up to ~700 here), and a close pivot passage
# amplifies it (stiff F_N=3 near pi passes at r ~ 1e-5: 4e-6 at rtol 1e-9).
TOLERANCE = {"stiff F_N=3 near pi": 1e-5}


@pytest.mark.parametrize("name", [n for n in CASES if n != "compliant F_N=10"])
def test_agrees_with_scipy_reference(name, reference):
    _check_against_reference(CASES[name], reference, TOLERANCE.get(name, 1e-6))


@pytest.mark.slow
@pytest.mark.parametrize("F_N", [10.0, 30.0])
def test_agrees_with_scipy_reference_at_large_load(F_N, reference):
    """Stiff contacts: against scipy's Radau (implicit; DOP853's steps are bound by
    stability here, ~10x dearer at the same tolerance)."""
    _check_against_reference(HARD["compliant F_N=10"].replace(F_N=F_N), reference,
                             method="reference-radau")


def _check_against_reference(params, reference, tolerance=1e-6, method="reference"):
    ref = reference(params, method=method)
    errors = []
    for rtol in (1e-6, 1e-9):
        res = simulate_support(params, rtol=rtol)
        assert res.success, res.message
        errors.append(np.max(np.abs(res.state_out - ref.state_out)))
        assert res.t_out == pytest.approx(ref.t_out, rel=1e-3 if rtol == 1e-6 else 1e-6)
    assert errors[1] < tolerance
    assert errors[1] < errors[0] / 30  # the error shrinks as rtol shrinks
    np.testing.assert_allclose(res.F_mean, ref.F_mean, atol=1e-7)
    assert res.r_min == pytest.approx(ref.r_min, rel=0.5) or max(res.r_min, ref.r_min) < 1e-6
    # r_max: ours is refined at the turning points of r inside the steps, the reference's is
    # sampled at its steps (5e-4 low on the stiff regime).
    assert res.r_max == pytest.approx(ref.r_max, rel=1e-3)
    assert res.r_min <= min(1.0, float(np.hypot(*res.state_out[:2]))) <= res.r_max


@pytest.mark.parametrize("name", ["pendulum", "slider", "stiff", "soft", "slider theta0=0"])
def test_explicit_and_implicit_agree(name):
    ex = simulate_support(CASES[name], rtol=1e-9, method="explicit")
    im = simulate_support(CASES[name], rtol=1e-9, method="implicit")
    np.testing.assert_allclose(ex.state_out, im.state_out, atol=1e-6)
    assert ex.F_mean == pytest.approx(im.F_mean, abs=1e-8)


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_auto_never_much_worse_than_cheaper_method(name, rtol):
    costs = []
    for method in ("explicit", "implicit"):
        res = simulate_support(CASES[name], rtol=rtol, method=method, max_steps=300_000)
        if res.success:
            costs.append(_cost(res))
    auto = simulate_support(CASES[name], rtol=rtol)
    assert auto.success, auto.message
    assert _cost(auto) <= 10 * min(costs)


def test_large_load_uses_implicit_method():
    res = simulate_support(HARD["compliant F_N=10"], rtol=1e-6)
    assert res.stats["n_steps_implicit"] > 0 and res.stats["n_steps"] < 2000
    explicit = simulate_support(HARD["compliant F_N=10"], rtol=1e-6, method="explicit")
    assert explicit.stats["n_steps"] > 20 * res.stats["n_steps"]  # stability-bound


@pytest.mark.parametrize("F_N", [10.0, 30.0])
def test_hard_large_loads_succeed(F_N):
    res = simulate_support(Params(k_r=0.01, k_theta=0.01, F_N=F_N), rtol=1e-6)
    assert res.success, res.message
    assert res.t_out > 10 * res.params.L0  # long creep
    assert np.all(np.isfinite(res.state_out)) and math.isfinite(res.r_min)
    assert res.relative_energy_residual < 1e-6


@pytest.mark.parametrize("theta0", [0.0, math.pi, math.pi + 1e-6, math.pi - 1e-6])
@pytest.mark.parametrize("method", ["auto", "explicit"])
def test_hard_axis_orientations_succeed(theta0, method):
    res = simulate_support(SLIDER.replace(theta0=theta0), rtol=1e-6, method=method)
    assert res.success, res.message
    assert np.all(np.isfinite(res.state_out)) and np.all(np.isfinite(res.F_mean))
    assert res.relative_energy_residual < 1e-5
    assert 0.0 <= res.r_min <= 1.0
    assert res.pivot_approach == (theta0 != 0.0)
    if res.pivot_approach:
        assert "pivot" in res.message


def test_theta0_on_axis_keeps_motion_on_axis():
    res = simulate_support(SLIDER.replace(theta0=math.pi), rtol=1e-8, samples=200)
    assert np.all(res.series.y == 0.0) and res.F_mean[1] == 0.0


@pytest.mark.parametrize("k", [1e2, 1e3, 1e4])
def test_rigid_limit_gives_mu0(k):
    res = simulate_support(Params(k_r=k, k_theta=k), rtol=1e-9)
    assert res.F_mean[0] / mu0() == pytest.approx(1.0, abs=30 / k**1.5)
    assert abs(res.F_mean[1]) < 1e-3 / k**0.5
    assert res.t_out == pytest.approx(res.params.L0, rel=1e-3)


def test_budgets_stop_with_clear_status():
    res = simulate_support(REGIMES["soft"], max_steps=20)
    assert not res.success and res.status == 1 and "max_steps" in res.message
    with pytest.raises(IntegrationError, match="step budget"):
        res.check()
    res = simulate_support(REGIMES["soft"], tau_max=5.0)
    assert not res.success and res.status == 2 and "tau_max" in res.message
    res = simulate_support(REGIMES["soft"], max_steps=20, method="reference")
    assert not res.success and res.status == 1


def test_samples_cover_the_contact():
    res = simulate_support(REGIMES["pendulum"], rtol=1e-9, samples=501)
    s = res.series
    assert s.tau.size == 501 and s.tau[0] == 0 and s.tau[-1] == pytest.approx(res.t_out)
    assert s.x[-1] == pytest.approx(res.state_out[0], abs=1e-8)
    assert (s.F_x[0], s.F_y[0]) == (pytest.approx(mu0()), pytest.approx(0.0))
    np.testing.assert_allclose(s.F_abs, np.hypot(s.F_x, s.F_y))
    np.testing.assert_allclose(s.r, np.hypot(s.x, s.y))
    ref = simulate_support(REGIMES["pendulum"], rtol=1e-10, method="reference", samples=501).series
    np.testing.assert_allclose(s.x, ref.x, atol=1e-4)
    assert simulate_support(REGIMES["pendulum"]).series is None


@pytest.mark.parametrize("name", ["pendulum", "slider", "soft", "compliant F_N=10"])
def test_sampled_energy_split(name):
    """Eq. (12) at every sample; at tau_out the samples are the result's energies."""
    res = simulate_support(CASES[name], rtol=1e-9, samples=401)
    s = res.series
    for key in ("W", "D_x", "D_y", "U_el", "K"):
        assert getattr(s, key)[-1] == pytest.approx(getattr(res, key), rel=1e-7, abs=1e-9), key
    balance = s.W - (s.D_x + s.D_y + s.U_el + s.K)
    # Between steps the cubic interpolants of W and D carry O(h^4) errors: still far
    # below the size of the terms.
    assert np.max(np.abs(balance)) < 1e-4 * max(1.0, res.W)
    assert s.W[0] == 0.0 and s.U_el[0] == pytest.approx(0.0, abs=1e-15) and s.K[0] == 0.0
    assert np.all(np.diff(s.D_x + s.D_y) >= -1e-9)  # dissipation only grows
    ref = simulate_support(CASES[name], rtol=1e-11, method="reference", samples=401).series
    for key in ("W", "D_x", "D_y", "U_el", "K"):
        np.testing.assert_allclose(getattr(s, key), getattr(ref, key), atol=1e-4 * max(1, res.W),
                                   err_msg=key)


def test_results_are_cached_and_read_only():
    a = simulate_support(REGIMES["stiff"], rtol=1e-7)
    assert simulate_support(REGIMES["stiff"], rtol=1e-7) is a
    assert simulate_support(REGIMES["stiff"], rtol=1e-8) is not a
    with pytest.raises(ValueError):
        a.state_out[0] = 1.0


def test_uncached_call_computes_afresh_and_leaves_the_cache_alone():
    """``cache=False`` (what the benchmarks time) integrates again, to the same result, and
    neither reads nor fills the cache."""
    p = REGIMES["slider"].replace(theta0=0.7)
    fresh = simulate_support(p, rtol=1e-7, cache=False)
    again = simulate_support(p, rtol=1e-7, cache=False)
    assert fresh is not again and fresh.t_out == again.t_out
    np.testing.assert_array_equal(fresh.state_out, again.state_out)
    cached = simulate_support(p, rtol=1e-7)
    assert cached is not fresh and cached.t_out == fresh.t_out
    assert simulate_support(p, rtol=1e-7, cache=False) is not cached
    assert simulate_support(p, rtol=1e-7) is cached
    with pytest.raises(TypeError, match="cache must be True or False, not 'no'"):
        simulate_support(p, cache="no")


def test_to_dict_has_documented_keys():
    d = simulate_support(REGIMES["pendulum"]).to_dict()
    for key in ("t_out", "state_out", "F_mean_x", "F_mean_y", "W", "D_x", "D_y", "U_el", "K",
                "energy_residual", "dtheta_rms", "dr_rms", "r_min", "r_max", "success", "message",
                "stats"):
        assert key in d


@pytest.mark.parametrize("kwargs, match", [
    (dict(rtol=0.0), "rtol"), (dict(rtol=float("nan")), "rtol"), (dict(atol=-1.0), "atol"),
    (dict(method="rk4"), "method"), (dict(samples=-1), "samples"), (dict(samples=2.5), "samples"),
    (dict(max_steps=0), "max_steps"), (dict(tau_max=float("inf")), "tau_max"),
])
def test_bad_solver_input_is_rejected(kwargs, match):
    with pytest.raises(ValueError, match=match):
        simulate_support(REGIMES["pendulum"], **kwargs)


def test_params_must_be_params():
    with pytest.raises(TypeError, match="Params"):
        simulate_support({"k_r": 1.0, "k_theta": 1.0})


def test_inaccurate_result_is_flagged():
    # Driven through its pivot at rtol 1e-2, Rodas4 alone misses the energy balance by 2.5 W
    # (tau_out 210 instead of 144). The 8th-order explicit pair kept the balance within 3 rtol
    # on every hard case tried at rtol 1e-2 ... 3e-4, so the flag is shown on Rodas4.
    params = HARD["slider theta0=pi"]
    junk = simulate_support(params, rtol=1e-2, method="implicit")
    assert junk.success and not junk.accurate and "inaccurate" in junk.message
    assert abs(junk.t_out - simulate_support(params).t_out) > 10  # it really is wrong
    good = simulate_support(HARD["compliant F_N=10"], rtol=1e-3)
    assert good.accurate and "warning" not in good.message


@pytest.mark.parametrize("offset", [1e-7, 1e-9, 1e-12])
@pytest.mark.parametrize("base", ["slider", "stiff F_N=3"])
def test_pivot_bounce_below_time_resolution(base, offset):
    # The bounce happens at r ~ 1e-13 ... 1e-22, below what tau resolves; the Sundman
    # time transformation resolves it, and theta0 -> pi converges to one limit.
    params = (SLIDER if base == "slider" else REGIMES["stiff"].replace(F_N=3.0))
    near = simulate_support(params.replace(theta0=math.pi - offset), rtol=1e-8)
    limit = simulate_support(params.replace(theta0=math.pi - 1e-6), rtol=1e-8)
    assert near.success and near.accurate, near.message
    assert near.pivot_approach and near.r_min < 1e-12
    assert near.t_out == pytest.approx(limit.t_out, rel=1e-6)
    assert near.F_mean[0] == pytest.approx(limit.F_mean[0], rel=1e-5)


def test_compliant_large_load_near_pi_stays_explicit_at_the_pivot():
    res = simulate_support(Params(k_r=0.01, k_theta=0.01, F_N=10.0, theta0=math.pi - 1e-9))
    assert res.success and res.accurate, res.message
    assert res.stats["n_steps"] < 20_000


LOADS = [(r, F_N) for F_N in (0.1, 3.0, 10.0) for r in ("pendulum", "stiff", "slider")
         if not (r == "slider" and F_N == 10.0)]  # slider at F_N=10: see the slow test above


@pytest.mark.parametrize("regime, F_N", LOADS)
def test_agrees_with_scipy_reference_at_other_loads(regime, F_N, reference):
    """Exit state within 1e-6 of DOP853 at rtol 1e-12, shrinking with rtol, at light and
    heavy loads (where the motion sticks and the automatic method goes implicit)."""
    _check_against_reference(REGIMES[regime].replace(F_N=F_N, theta0=1.2), reference)
