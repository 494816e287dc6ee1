"""The compiled kernel: coefficients, Jacobian, friction law, convergence orders."""
import importlib
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.integrate._ivp.rk import RK45

from model import REGIMES, mu_over_s
from model import _kernel
from model.contact.reference import reference_rhs

dopri5 = importlib.import_module("model._kernel.dopri5")
rodas4 = importlib.import_module("model._kernel.rodas4")
dop853 = importlib.import_module("model._kernel.dop853")


def test_dopri5_coefficients_match_scipy():
    np.testing.assert_allclose(dopri5.A, RK45.A, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dopri5.B, RK45.B, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dopri5.E, RK45.E, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dopri5.P_DENSE, RK45.P, rtol=0, atol=1e-14)


def _states():
    rng = np.random.default_rng(1)
    out = [np.array([0.3, 0.8, 0.2, -0.4, 1.3]),      # generic
           np.array([-0.9, 0.1, 1.0, 1e-7, 3.0]),     # v_R ~ 0 (series branch)
           np.array([0.02, -0.01, 0.5, 0.3, 2.0])]    # near the pivot
    out += [np.concatenate([rng.uniform(-2, 2, 2), rng.uniform(-1, 2, 2), rng.uniform(-3, 3, 1)])
            for _ in range(5)]
    return out


@pytest.mark.parametrize("state", _states())
@pytest.mark.parametrize("regime", ["pendulum", "slider", "soft"])
def test_jacobian_matches_finite_differences(state, regime):
    P = _kernel.pack(REGIMES[regime].replace(F_N=3.0))
    u = np.zeros(_kernel.N_STATE)
    u[:5] = state
    J = np.zeros((_kernel.N_STATE, _kernel.N_MOTION))
    f0 = np.empty(_kernel.N_STATE)
    _kernel.rhs(u, P, f0)
    _kernel.jacobian(u, P, f0, J)
    fp, fm = np.empty(_kernel.N_STATE), np.empty(_kernel.N_STATE)
    for j in range(_kernel.N_MOTION):
        h = 1e-6 * max(1.0, abs(u[j]))
        up, um = u.copy(), u.copy()
        up[j] += h
        um[j] -= h
        _kernel.rhs(up, P, fp)
        _kernel.rhs(um, P, fm)
        fd = (fp - fm) / (2 * h)
        np.testing.assert_allclose(J[:, j], fd, rtol=1e-5, atol=1e-5 * (1 + np.abs(fd).max()))


def test_kernel_rhs_matches_reference_rhs():
    params = REGIMES["slider"].replace(theta0=2.0, F_N=2.0)
    P = _kernel.pack(params)
    ref = reference_rhs(params)
    out = np.empty(_kernel.N_STATE)
    for state in _states():
        u = np.zeros(_kernel.N_STATE)
        u[:5] = state
        _kernel.rhs(u, P, out)
        # The kernel's derivatives are w(r) d/dtau (Sundman); out[11] = w.
        np.testing.assert_allclose(out[:11] / out[11], ref(0.0, u[:11]), rtol=1e-12, atol=1e-12)
        r = np.hypot(*state[:2])
        assert 0 < out[11] <= 1 and 1 - out[11] <= 1.01 * (1e-6 / r) ** 2  # w = 1 - (R_S/r)^2


@pytest.mark.parametrize("s", [0.0, 1e-12, 1e-6, 9.99e-5, 1.0001e-4, 1e-3, 0.05, 1.0, 30.0])
def test_kernel_friction_matches_numpy(s):
    P = _kernel.pack(REGIMES["pendulum"])
    assert math.isclose(_kernel.mu_over_s(s, P), float(mu_over_s(s)), rel_tol=1e-12)


def _fixed_step_error(step_fn, n_steps, params, T=2.0):
    """Max error at tau = T after n fixed steps, against a tight DOP853 solution."""
    P = _kernel.pack(params)
    y = _kernel.initial_state(params)
    exact = solve_ivp(reference_rhs(params), (0, 1.1 * T), y[:11], method="DOP853", rtol=1e-13,
                      atol=1e-14, dense_output=True).sol
    h = T / n_steps
    f = np.empty(_kernel.N_STATE)
    for _ in range(n_steps):
        _kernel.rhs(y, P, f)
        y = step_fn(y, f, h, P)
    return np.max(np.abs(y[:5] - exact(y[_kernel.TAU])[:5]))  # at the kernel's tau


def _dp5(y, f, h, P):
    K, ynew, err, ys = np.zeros((7, y.size)), np.empty(y.size), np.empty(y.size), np.empty(y.size)
    dopri5.step(y, f, h, P, K, ynew, err, ys)
    return ynew


def _dop853(y, f, h, P):
    K, ynew, ys = np.zeros((dop853.N_ROWS, y.size)), np.empty(y.size), np.empty(y.size)
    dop853.step(y, f, h, P, K, ynew, ys)
    return ynew


def _rodas(y, f, h, P):
    n = y.size
    J = np.zeros((n, _kernel.N_MOTION))
    _kernel.jacobian(y, P, f, J)
    M, piv = np.empty((5, 5)), np.zeros(5, np.int64)
    Kr, ynew, err, ys, b = np.zeros((6, n)), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    assert rodas4.step(y, f, h, P, J, M, piv, Kr, ynew, err, ys, b)
    return ynew


@pytest.mark.parametrize("step_fn, order, steps", [(_dp5, 5, (20, 40, 80, 160)),
                                                   (_dop853, 8, (8, 12, 18)),  # 40 steps: rounding
                                                   (_rodas, 4, (40, 80, 160, 320))])
def test_empirical_convergence_order(step_fn, order, steps):
    # Smooth on [0, 2]: |v_R| stays away from the steep part of mu near 0.
    params = REGIMES["stiff"]
    errors = [_fixed_step_error(step_fn, n, params) for n in steps]
    slopes = -np.diff(np.log(errors)) / np.diff(np.log(steps))
    assert np.all(np.abs(slopes - order) < 0.3), (errors, slopes)


def test_kernel_exit_quantities_match_numpy():
    from model.arrays.contacts import exit_quantities, run_contacts
    from model.contact.options import SolverOptions

    params = REGIMES["soft"].replace(F_N=2.0, beta=0.6)
    theta0 = np.array([0.3, 1.7, 2.9])
    options = SolverOptions(rtol=1e-7)
    k, _ = run_contacts(params, theta0, options)
    n = exit_quantities(params, options, theta0, k.status,
                        k.t_out, np.column_stack([k.state_out, k.W, k.F_y * k.t_out * params.f_N,
                                                  k.D_x, k.D_y, k.dtheta_rms**2 * k.t_out,
                                                  k.dr_rms**2 * k.t_out]),
                        k.stats, k.r_min)
    for name in ("F_x", "F_y", "U_el", "K", "energy_residual", "dtheta_rms", "dr_rms"):
        np.testing.assert_allclose(getattr(k, name), getattr(n, name), rtol=1e-12, atol=1e-14)


def test_cold_start_is_announced(monkeypatch, capsys):
    import io

    from model.cli import main

    stream = io.StringIO()
    _kernel.integrate_batch(_kernel.initial_state(REGIMES["stiff"])[None],
                            _kernel.pack(REGIMES["stiff"])[None], 1e-3, 1e-5, 0, 100, 1e5, False)
    assert not _kernel.cache_is_cold()  # loaded in this process
    monkeypatch.setattr(_kernel, "cache_is_cold", lambda: True)
    assert _kernel.announce_cold_start(stream)
    assert stream.getvalue().startswith("preparing the solver (first start, ~")
    assert main(["support", "--regime", "stiff"]) == 0
    assert "preparing the solver (first start" in capsys.readouterr().err
    monkeypatch.setattr(_kernel, "cache_is_cold", lambda: False)
    assert not _kernel.announce_cold_start(stream)
    main(["support", "--regime", "stiff"])
    assert "preparing" not in capsys.readouterr().err
