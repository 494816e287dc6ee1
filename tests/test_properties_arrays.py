"""Property-based tests (hypothesis) of the array functions and the adaptive quadrature.

``fixed_orientation``, ``orientation_sweep`` and ``uniform_array`` over the paper's box:
finite results or a non-success that says why; their bad arguments raise ``ValueError``
(``TypeError`` for a non-``Params``) naming the argument. The quadrature's interval budget
never leaves part of [0, pi] out. Arrays are costlier than single contacts, so the example
counts are small and the tolerances coarse.
"""
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from model import Params, fixed_orientation, mu0, orientation_sweep, uniform_array
from model.arrays.quadrature import integrate

PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink)
ARRAYS = settings(max_examples=40, deadline=60_000, database=None, phases=PHASES,
                  suppress_health_check=[HealthCheck.too_slow])
FAST = settings(max_examples=150, deadline=None, database=None, phases=PHASES)


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e)


THETA0 = st.one_of(st.sampled_from([0.0, math.pi, math.pi - 1e-9, math.pi / 2]),
                   st.floats(-math.pi, math.pi))
BOX = st.builds(Params, k_r=log_uniform(0.01, 3.0), k_theta=log_uniform(0.01, 3.0),
                F_N=log_uniform(0.1, 10.0), theta0=THETA0)
BETA = st.one_of(st.just("self"), st.floats(0.05, 1.0))


def _strict_json(record: dict) -> str:
    return json.dumps(record, allow_nan=False, default=float)


# --------------------------------------------------------------------------- fixed arrays

@ARRAYS
@given(params=BOX, beta=BETA, rtol=log_uniform(1e-7, 1e-5))
def test_fixed_array_is_finite_or_says_why(params, beta, rtol):
    r = fixed_orientation(params, beta=beta, rtol=rtol)
    assert r.message
    assert 0 < r.beta <= 1 and r.params.beta == r.beta
    if beta != "self":
        assert r.beta == beta and r.beta_residual == 0.0
    if not r.success:
        assert r.message != "contact ended: the slab slid L0 over the support (Eq. 9)"
        return
    values = [r.FTx_over_mu0FN, r.FTy_over_mu0FN, r.Dy_over_Dx, r.Nc_over_Nc0, r.dtheta_rms,
              r.dr_rms, r.r_min, r.energy_residual, *r.work_split.values()]
    assert all(math.isfinite(v) for v in values), r
    assert r.Nc_over_Nc0 > 0 and r.Dy_over_Dx >= -1e-6
    # The work split closes to the energy residual (Eq. 12).
    assert sum(r.work_split.values()) == pytest.approx(1.0, abs=1e-3)
    # |F_f| <= mu_s f_N on every support, so the array force is bounded by mu_s/mu0 too.
    assert math.hypot(r.FTx_over_mu0FN, r.FTy_over_mu0FN) <= params.mu_s / mu0(params) + 1e-6
    if beta == "self" and "capped" not in r.message and "no root" not in r.message:
        # beta = N_c0/N_c = L0/tau_out(beta) (Sec. "Self-consistent load factor")
        assert r.beta * r.Nc_over_Nc0 == pytest.approx(1.0, abs=1e-5)
    if "capped" in r.message:
        assert r.beta == 1.0 and r.Nc_over_Nc0 <= 1.0 + 1e-9
    _strict_json(r.to_dict())


@settings(max_examples=12, deadline=60_000, database=None, phases=PHASES,
          suppress_health_check=[HealthCheck.too_slow])
@given(params=BOX, theta0=st.lists(THETA0, min_size=1, max_size=6),
       beta=st.floats(0.05, 1.0))
def test_orientation_sweep_rows_match_single_arrays(params, theta0, beta):
    """A batch of orientations gives each orientation's own fixed array (fixed beta)."""
    s = orientation_sweep(params.replace(theta0=math.pi / 2), theta0, beta=beta, rtol=1e-6)
    assert s.theta0.shape == s.FTx_over_mu0FN.shape == s.success.shape == (len(theta0),)
    for i, t in enumerate(theta0):
        one = fixed_orientation(params.replace(theta0=t), beta=beta, rtol=1e-6)
        assert bool(s.success[i]) == one.success
        if one.success:
            assert s.FTx_over_mu0FN[i] == pytest.approx(one.FTx_over_mu0FN, rel=1e-12)
            assert s.Nc_over_Nc0[i] == pytest.approx(one.Nc_over_Nc0, rel=1e-12)


# --------------------------------------------------------------------------- uniform arrays

@settings(max_examples=10, deadline=120_000, database=None, phases=PHASES,
          suppress_health_check=[HealthCheck.too_slow])
@given(params=BOX, beta=BETA, tol=log_uniform(1e-2, 0.2))
def test_uniform_array_is_finite_or_says_why(params, beta, tol):
    r = uniform_array(params.replace(theta0=math.pi / 2), beta=beta, tol=tol)
    assert r.message and r.n_members >= 60 and r.n_members % 15 == 0
    assert r.n_failed == len(r.failed_theta0) and 0 <= r.n_pivot <= r.n_members
    assert r.FTy_over_mu0FN == 0.0  # mirror symmetry
    assert r.success == (r.n_failed == 0 and "not met" not in r.message)
    assert 0 < r.beta <= 1
    for name, value in [("FTx_over_mu0FN", r.FTx_over_mu0FN), ("Nc_over_Nc0", r.Nc_over_Nc0),
                        ("Dy_over_Dx", r.Dy_over_Dx), ("duration", r.FTx_over_mu0FN_duration),
                        *r.work_split.items(), *r.quadrature_error.items()]:
        assert math.isfinite(value), name
    assert all(e >= 0 for e in r.quadrature_error.values())
    if r.success:
        assert r.quadrature_error["FTx_over_mu0FN"] <= tol
        assert r.quadrature_error["Nc_over_Nc0"] <= tol
    _strict_json(r.to_dict())


@pytest.mark.slow
@settings(max_examples=6, deadline=None, database=None, phases=PHASES,
          suppress_health_check=[HealthCheck.too_slow])
@given(params=BOX, max_intervals=st.integers(1, 12))
def test_interval_budget_keeps_the_error_estimate_honest(params, max_intervals):
    """Out of intervals, the average is still over all of [0, pi]: it stays within a
    small multiple of its (coarse) error estimate of the converged value."""
    params = params.replace(theta0=math.pi / 2)  # a uniform array covers every theta0
    full = uniform_array(params, beta=1.0, tol=1e-4)
    cut = uniform_array(params, beta=1.0, tol=1e-4, max_intervals=max_intervals)
    assert cut.stats["intervals"] <= max(4, max_intervals)
    for name in ("FTx_over_mu0FN", "Nc_over_Nc0"):
        error = cut.quadrature_error[name] + full.quadrature_error[name]
        assert abs(getattr(cut, name) - getattr(full, name)) <= 30 * error + 2e-4, name


@FAST
@given(max_intervals=st.integers(1, 40), rounds=st.integers(1, 30),
       edge=st.floats(0.1, 3.0), a=st.floats(-2.0, 1.0), width=st.floats(0.5, 4.0))
def test_quadrature_partition_always_covers_the_interval(max_intervals, rounds, edge, a, width):
    """A rough component drives the refinement into the interval budget; a constant one
    must still integrate to the length of [a, b] (no interval may be dropped)."""
    b = a + width
    step = a + edge * width / 3.1

    def f(x):
        return np.c_[np.ones_like(x), np.where(x < step, 1.0, 0.0), np.abs(np.sin(7 * x))]

    res = integrate(f, a, b, 1e-12, control=[1, 2], max_intervals=max_intervals,
                    max_rounds=rounds)
    assert res.edges[0] == a and res.edges[-1] == pytest.approx(b, rel=1e-15, abs=1e-15)
    assert np.all(np.diff(res.edges) > 0)
    assert res.edges.size - 1 <= max(4, max_intervals)
    assert res.integral[0] == pytest.approx(b - a, rel=1e-12)
    assert res.nodes.size == 15 * (res.edges.size - 1)


# --------------------------------------------------------------------------- bad arguments

NOT_A_BETA = st.one_of(st.floats(max_value=0.0), st.floats(min_value=1.0, exclude_min=True),
                       st.just(math.nan), st.sampled_from([None, [0.5], "Self", "", True]),
                       st.text(max_size=6).filter(lambda t: t != "self"))
NOT_A_TOL = st.one_of(st.floats(max_value=1e-8, exclude_max=True),
                      st.floats(min_value=0.5, exclude_min=True), st.just(math.nan),
                      st.sampled_from([None, "1e-3", True, [1e-3]]))
NOT_AN_RTOL = st.one_of(st.floats(max_value=1e-14, exclude_max=True),
                        st.floats(min_value=1e-2, exclude_min=True),
                        st.sampled_from([math.nan, "1e-6", True]))
NOT_THETA0S = st.one_of(
    st.just([]), st.lists(st.floats(allow_nan=False).filter(lambda t: abs(t) > 2 * math.pi),
                          min_size=1, max_size=3),
    st.sampled_from([[math.nan], [0.1, math.inf], [[0.1, 0.2], [0.3, 0.4]], ["a"], None,
                     [None], np.zeros((2, 2))]))
NOT_PARAMS = st.one_of(st.none(), st.floats(), st.text(max_size=5),
                       st.fixed_dictionaries({"k_r": st.floats(), "k_theta": st.floats()}))


@FAST
@given(bad=NOT_A_BETA)
def test_bad_beta_is_rejected_by_every_array_function(bad):
    params = Params(3.0, 3.0)
    for call in (lambda: fixed_orientation(params, beta=bad),
                 lambda: orientation_sweep(params, [1.0], beta=bad),
                 lambda: uniform_array(params, beta=bad, tol=0.1)):
        with pytest.raises(ValueError, match=r"^beta="):
            call()


@FAST
@given(bad=NOT_A_TOL)
def test_bad_quadrature_tolerance(bad):
    with pytest.raises(ValueError, match=r"^tol="):
        uniform_array(Params(3.0, 3.0), tol=bad)


@FAST
@given(bad=NOT_AN_RTOL, method=st.sampled_from(["auto", "nope"]))
def test_bad_solver_options_of_arrays(bad, method):
    params = Params(3.0, 3.0)
    for call in (lambda: fixed_orientation(params, rtol=bad, method=method),
                 lambda: uniform_array(params, rtol=bad, method=method, tol=0.1)):
        with pytest.raises(ValueError, match=r"^(rtol|method)="):
            call()


@FAST
@given(bad=st.one_of(st.integers(max_value=0), st.sampled_from([None, 2.5, "8", True])))
def test_bad_interval_budget(bad):
    with pytest.raises(ValueError, match=r"^max_intervals="):
        uniform_array(Params(3.0, 3.0), max_intervals=bad)


@FAST
@given(bad=NOT_THETA0S)
def test_bad_orientations(bad):
    with pytest.raises(ValueError, match=r"^theta0="):
        orientation_sweep(Params(3.0, 3.0), bad)


@FAST
@given(bad=st.one_of(st.floats(max_value=0.0), st.floats(min_value=0.1, exclude_min=True),
                     st.sampled_from([math.nan, None, "1e-8", True])))
def test_bad_beta_tolerance(bad):
    with pytest.raises(ValueError, match=r"^beta_xtol="):
        orientation_sweep(Params(3.0, 3.0), [1.0], beta_xtol=bad)


@FAST
@given(bad=NOT_PARAMS)
def test_arrays_need_params(bad):
    for call in (lambda: fixed_orientation(bad), lambda: orientation_sweep(bad, [1.0]),
                 lambda: uniform_array(bad)):
        with pytest.raises(TypeError, match="must be a model.Params"):
            call()
