"""The recorded histories of one contact (``samples``): nodes inside the 8th-order steps,
their accuracy against a tight scipy DOP853 solution, and runs that record taking the same
steps as runs that do not (model/_kernel/record.py)."""
import importlib
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from model import REGIMES, _kernel, simulate_support
from model.contact.options import SolverOptions
from model.contact.reference import integrate_reference, reference_rhs

dop853 = importlib.import_module("model._kernel.dop853")
record = importlib.import_module("model._kernel.record")
S = _kernel.slots
SERIES = {"pendulum": REGIMES["pendulum"],
          "pendulum theta0=300deg": REGIMES["pendulum"].replace(theta0=math.radians(300)),
          "stiff": REGIMES["stiff"], "soft beta=0.25": REGIMES["soft"].replace(beta=0.25)}
#: The tolerance the series were held to with the Dormand-Prince 5(4) steps
#: (test_support.test_samples_cover_the_contact, test_array_motion); at rtol 1e-6 the
#: cubic Hermite sampling between the ends of the 8th-order steps alone misses it by up to
#: ten times (1.1e-3 in v_x on the pendulum).
SERIES_ATOL = 1e-4


def _run(params, rtol, method, record_):
    return _kernel.integrate_batch(_kernel.initial_state(params)[None], _kernel.pack(params)[None],
                                   rtol, rtol / 100, _kernel.METHOD_CODES[method], 1_000_000,
                                   1e5, record_)


@pytest.mark.parametrize("name", SERIES)
def test_sampled_series_match_a_tight_reference(name):
    """Every sampled history of a recording run (default rtol 1e-6) within SERIES_ATOL of
    scipy's DOP853 at rtol 1e-12, sampled at the same tau (docs/model.md, "Solvers")."""
    params = SERIES[name]
    res = simulate_support(params, samples=3000)
    status, t_ref, _, _, _, _, sol = integrate_reference(
        params, SolverOptions(rtol=1e-12, atol=1e-14, method="reference",
                              max_steps=2_000_000), dense=True)
    assert res.success and status == S.OK
    s = res.series
    inside = s.tau <= min(t_ref, res.t_out)
    ref = sol(s.tau[inside])
    scale = max(1.0, res.W)
    for k, key in enumerate(("x", "y", "v_x", "v_y", "theta", "W", "I_y", "D_x", "D_y")):
        if key == "I_y":
            continue
        atol = SERIES_ATOL * (scale if k >= 5 else 1.0)
        np.testing.assert_allclose(getattr(s, key)[inside], ref[k], rtol=0, atol=atol,
                                   err_msg=f"{name}: {key}")


@pytest.mark.parametrize("name", ["pendulum", "slider"])
def test_recording_takes_the_same_steps(name):
    """A recording run has the exit state of the same run without recording, bit for bit."""
    plain = _run(REGIMES[name], 1e-6, "auto", False)
    rec = _run(REGIMES[name], 1e-6, "auto", True)
    np.testing.assert_array_equal(rec[1], plain[1])
    np.testing.assert_array_equal(rec[2], plain[2])
    np.testing.assert_array_equal(rec[4][:, S.ST_ACC], plain[4][:, S.ST_ACC])
    np.testing.assert_array_equal(rec[4][:, S.ST_REJ], plain[4][:, S.ST_REJ])


def test_explicit_steps_carry_inner_nodes():
    """Explicit run: the start, then N_SUB nodes per accepted step (its inside and end), with
    tau increasing and the nodes on the motion (cubic Hermite reproduces them)."""
    out = _run(REGIMES["pendulum"], 1e-6, "explicit", True)
    nodes, n = out[7], out[8]
    steps = int(out[4][0, S.ST_ACC])
    assert n == record.N_SUB * steps + 1
    tau = nodes[:n, 0]
    assert np.all(np.diff(tau) > 0)
    ends = nodes[:n:record.N_SUB, 0]
    inner = np.delete(tau, np.arange(0, n, record.N_SUB))
    assert inner.size == (record.N_SUB - 1) * steps
    # Inner nodes sit strictly inside their step.
    assert np.all(inner > np.repeat(ends[:-1], record.N_SUB - 1))
    assert np.all(inner < np.repeat(ends[1:], record.N_SUB - 1))


def test_inner_node_derivatives_are_tau_derivatives():
    """The derivative columns of every node are d/dtau of the state (the right-hand side)."""
    params = REGIMES["stiff"]
    out = _run(params, 1e-6, "explicit", True)
    nodes = out[7][:out[8]]
    fun = reference_rhs(params)
    cols = [0, 1, 2, 3, 4, 5, 7, 8]  # REC_SLOTS in the reference's 11-state order
    for row in nodes[1::record.N_SUB][:20]:
        u = np.zeros(11)
        u[:5] = row[1:6]
        f = fun(row[0], u)[cols]
        np.testing.assert_allclose(row[1 + record.N_REC:], f, rtol=0, atol=1e-6)


@pytest.mark.parametrize("theta", [1 / 3, 2 / 3])
def test_continuous_extension_order(theta):
    """DOP853's continuous extension (the inner nodes): local error O(h^8) in the value and
    O(h^7) in its derivative, from one step at h = 0.4, 0.2, 0.1."""
    params = REGIMES["stiff"]
    P = _kernel.pack(params)
    y = _kernel.initial_state(params)
    f = np.empty(S.N_STATE)
    _kernel.rhs(y, P, f)
    fun = reference_rhs(params)
    sol = solve_ivp(fun, (0, 1.0), y[:11], method="DOP853", rtol=1e-13, atol=1e-15,
                    dense_output=True).sol
    hs = np.array([0.4, 0.2, 0.1])
    err_v, err_d = [], []
    for h in hs:
        K = np.zeros((dop853.N_ROWS, S.N_STATE))
        ynew, ys = np.empty(S.N_STATE), np.empty(S.N_STATE)
        dop853.step(y, f, h, P, K, ynew, ys)
        dop853.dense_stages(y, h, P, K, ys)
        F = np.empty(dop853.N_POLY)
        v, d = np.empty(5), np.empty(5)
        for i in range(5):
            dop853.poly(y, ynew, K, h, i, F)
            v[i], slope = dop853.poly_with_slope(y[i], F, theta)
            d[i] = slope / h
        exact = sol(theta * h)
        err_v.append(np.max(np.abs(v - exact[:5])))
        err_d.append(np.max(np.abs(d - fun(theta * h, exact)[:5])))
    order_v = np.diff(np.log(err_v)) / np.diff(np.log(hs))
    order_d = np.diff(np.log(err_d)) / np.diff(np.log(hs))
    assert np.all(np.abs(order_v - 8) < 0.6), (err_v, order_v)
    assert np.all(np.abs(order_d - 7) < 0.6), (err_d, order_d)
