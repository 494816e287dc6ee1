"""The self-consistent load factor beta = L0/<tau_out>(beta)."""
import math

import numpy as np
import pytest

from model import REGIMES, fixed_orientation, simulate_support, uniform_array
from model.arrays.beta import solve_beta, solve_beta_scalar, solve_beta_secant
from model.arrays.uniform import BETA_GTOL


def test_vectorised_solver_on_known_roots():
    # tau(beta) = L0 (1 + k beta): beta (1 + k beta) = 1.
    k = np.array([1.0, 3.0, 10.0])
    sol = solve_beta(lambda b, rows: 10.0 * (1 + k[rows] * b), 10.0, 3)
    np.testing.assert_allclose(sol.beta, (np.sqrt(1 + 4 * k) - 1) / (2 * k), rtol=1e-7)
    assert np.all(sol.converged) and not np.any(sol.capped | sol.jump)


def test_no_root_below_one_is_capped():
    sol = solve_beta(lambda b, rows: np.full(b.size, 5.0), 10.0, 1)  # tau < L0 always
    assert sol.capped[0] and sol.beta[0] == 1.0


def test_discontinuity_is_reported_as_jump():
    tau = lambda b, rows: np.where(b < 0.5, 10.0 / 0.8, 10.0 / 0.2)  # noqa: E731
    sol = solve_beta(tau, 10.0, 1)
    assert sol.jump[0] and abs(sol.beta[0] - 0.5) < 1e-6


def test_scalar_solver_matches_vectorised():
    tau = lambda b: 10.0 * (1 + 3.0 * b)  # noqa: E731
    root = (math.sqrt(13) - 1) / 6
    s = solve_beta_scalar(tau, 10.0, xtol=1e-12)
    assert s.converged and not s.capped and s.beta == pytest.approx(root, rel=1e-10)
    s2 = solve_beta_scalar(tau, 10.0, xtol=1e-12, guess=0.43)
    assert s2.beta == pytest.approx(root, rel=1e-10) and s2.evaluations <= s.evaluations


def _naive(next_beta, n):
    beta, history = 1.0, []
    for _ in range(n):
        beta = min(1.0, next_beta(beta))
        history.append(beta)
    return np.array(history)


def test_fixed_array_where_naive_iteration_two_cycles():
    params = REGIMES["slider"]  # theta0 = pi/2: beta -> L0/tau_out(beta) has slope << -1
    history = _naive(lambda b: params.L0 / simulate_support(params.replace(beta=b)).t_out, 30)
    assert abs(history[-1] - history[-2]) > 0.5  # a 2-cycle, not a fixed point
    assert history[-1] == pytest.approx(history[-3], rel=1e-6)
    res = fixed_orientation(params)
    tau = simulate_support(params.replace(beta=res.beta)).t_out
    assert res.beta == pytest.approx(params.L0 / tau, rel=1e-7)
    assert abs(res.beta_residual) < 1e-7 and res.success


def test_uniform_array_where_naive_iteration_does_not_settle():
    params = REGIMES["slider"]
    history = _naive(lambda b: 1.0 / uniform_array(params, beta=b).Nc_over_Nc0, 10)
    assert np.max(np.abs(np.diff(history[-4:]))) > 2e-3  # still oscillating
    res = uniform_array(params)
    assert abs(res.beta - 1.0 / res.Nc_over_Nc0) < 1e-4
    assert abs(res.beta_residual) < 1e-4 and res.beta_iterations > 0


@pytest.mark.parametrize("regime", ["pendulum", "stiff", "soft"])
def test_self_consistent_beta_for_fixed_arrays(regime):
    res = fixed_orientation(REGIMES[regime].replace(theta0=1.0))
    assert 0 < res.beta <= 1 and res.beta == pytest.approx(1 / res.Nc_over_Nc0, rel=1e-7)
    assert math.isclose(res.params.beta, res.beta)


def test_secant_solver_on_known_root_cold_and_from_a_guess():
    tau = lambda b: 10.0 * (1 + 3.0 * b)  # noqa: E731
    root = (math.sqrt(13) - 1) / 6
    cold = solve_beta_secant(tau, 10.0, xtol=1e-12)
    warm = solve_beta_secant(tau, 10.0, xtol=1e-12, guess=root * 1.01, slope=1.5)
    for s in (cold, warm):
        assert s.converged and not s.capped and s.beta == pytest.approx(root, rel=1e-10)
    assert warm.evaluations < cold.evaluations
    # The returned beta is the last point evaluated (its members can be reused).
    seen = []
    s = solve_beta_secant(lambda b: seen.append(b) or tau(b), 10.0, xtol=1e-12, guess=0.5)
    assert seen[-1] == s.beta


def test_secant_solver_steps_through_a_known_point():
    """With the residual at one point already known (the quadrature's, in a uniform
    array), the second step is the secant through it: a wrong slope costs no extra steps."""
    tau = lambda b: 10.0 / (1.0 - 0.5 * (b - 0.4))  # noqa: E731  G = 1.5 (b - 0.8): linear
    b0 = 0.85
    plain = solve_beta_secant(tau, 10.0, xtol=1e-10, guess=0.81, slope=15.0)
    known = solve_beta_secant(tau, 10.0, xtol=1e-10, guess=0.81, slope=15.0,
                              known=(b0, 1.5 * (b0 - 0.8)))
    for s in (plain, known):
        assert s.converged and s.beta == pytest.approx(0.8, abs=1e-9)
    assert known.evaluations < plain.evaluations


def test_secant_solver_caps_and_survives_a_jump():
    capped = solve_beta_secant(lambda b: 5.0, 10.0, guess=0.7)  # tau < L0 always
    assert capped.capped and capped.beta == 1.0
    jump = solve_beta_secant(lambda b: 10.0 / 0.8 if b < 0.5 else 10.0 / 0.2, 10.0, xtol=1e-9,
                             guess=0.4)
    assert abs(jump.beta - 0.5) < 1e-6  # no root: the jump located


@pytest.mark.parametrize("regime", ["slider", "soft"])
@pytest.mark.parametrize("F_N", [0.1, 3.0])
def test_beta_by_continuation_equals_cold_bracketed_solve(regime, F_N):
    """A neighbour's beta as the start (as in a sweep) gives the beta of a cold solve,
    and both satisfy beta = L0/<tau_out>(beta) with the vectorised bracketed solver.

    Each is accepted at |G| <= BETA_GTOL tol on the quadrature's partition (the slope of
    G is >= 1 here), so the two agree to within twice that."""
    params = REGIMES[regime].replace(F_N=F_N)
    gtol = BETA_GTOL * 1e-3  # the default tol
    cold = uniform_array(params)
    neighbour = uniform_array(params.replace(k_r=params.k_r * 1.3))
    warm = uniform_array(params, beta_guess=(neighbour.beta, neighbour.stats["beta_slope"]))
    assert warm.beta_iterations < cold.beta_iterations or warm.beta == cold.beta
    assert abs(warm.beta - cold.beta) <= 2 * gtol
    assert warm.FTx_over_mu0FN == pytest.approx(cold.FTx_over_mu0FN, abs=2e-3)
    assert abs(warm.beta_residual) <= gtol and abs(cold.beta_residual) <= gtol
    # A cold bracketed solve (Brent on [BETA_MIN, 1]) of beta = L0/<tau_out>(beta),
    # each <tau_out> a fixed-beta uniform array at the same tolerances.
    bracketed = solve_beta_scalar(lambda b: params.L0 * uniform_array(params, beta=b).Nc_over_Nc0,
                                  params.L0, xtol=1e-7)
    assert bracketed.converged and not bracketed.capped
    assert abs(warm.beta - bracketed.beta) <= 2 * gtol


def test_uniform_array_from_a_close_guess_skips_the_coarse_solve():
    """Started at an extrapolated beta (``guess_is_close``), the quadrature begins there:
    fewer trajectories than from the same guess with it, and the beta of the cold solve to within twice the residual."""
    params = REGIMES["soft"].replace(F_N=3.0)
    cold = uniform_array(params)
    guess = (cold.beta * (1 + 1e-5), cold.stats["beta_slope"])
    close = uniform_array(params, beta_guess=guess, guess_is_close=True)
    warm = uniform_array(params, beta_guess=guess)
    assert abs(close.beta - cold.beta) <= 2 * BETA_GTOL * 1e-3
    assert close.stats["trajectories"] < warm.stats["trajectories"]
