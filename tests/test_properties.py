"""Property-based tests (hypothesis) of ``Params``, the solver options and ``simulate_support``.

Valid input anywhere in the documented parameter box never raises and round-trips; invalid
input (out of range, non-finite, wrong type) always raises ``ValueError`` naming the field;
every integration over the paper's box (k in [0.01, 3], F_N in [0.1, 10], theta0 in
[-pi, pi] with the axis and the pivot passage near pi) ends in a finite successful result or
in an unsuccessful one that says why, within its step budget. Physics: the mirror y -> -y
(theta0 -> -theta0) and the period 2 pi of theta0.
"""
import json
import math
import pickle

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st

from model import IntegrationError, Params, simulate_support
from model.contact.options import METHODS, SolverOptions
from model.contact.results import ACCURACY_FACTOR, SupportResult

# --------------------------------------------------------------------------- the spec

# Documented range of every field (the messages of ``Params`` quote them): (low, high,
# low end open). The upper end is closed everywhere.
RANGES = {
    "k_r": (0.0, 1e6, True), "k_theta": (0.0, 1e6, True), "F_N": (0.0, 1e3, True),
    "theta0": (-2 * math.pi, 2 * math.pi, False), "beta": (1e-3, 1.0, False),  # the solver's bracket
    "mu_s": (0.0, 100.0, True), "A": (0.0, 100.0, True), "B": (-1e4, 1e4, False),
    "zeta": (0.0, 1e6, True), "lam": (1e-4, 0.5, False), "L0": (0.0, 1e6, True),
}
FIELDS = list(RANGES)
# No "explain" phase: it reruns failing examples many times over and only adds comments.
PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink)
FAST = settings(max_examples=200, deadline=None, database=None, phases=PHASES)
# Integrations: budgets keep each example well under a second.
SOLVE = settings(max_examples=200, deadline=20_000, database=None, phases=PHASES,
                 suppress_health_check=[HealthCheck.too_slow])
MAX_STEPS = 200_000


def valid_value(name):
    lo, hi, lo_open = RANGES[name]
    return st.floats(lo, hi, exclude_min=lo_open, allow_nan=False)


def invalid_value(name):
    """Numbers outside the field's range, non-finite numbers and things that are not numbers."""
    lo, hi, lo_open = RANGES[name]
    return st.one_of(
        st.floats(max_value=lo, exclude_max=not lo_open),  # below (incl. -inf)
        st.floats(min_value=hi, exclude_min=True),  # above (incl. inf)
        st.just(math.nan),
        st.integers(min_value=2**1024),  # beyond the float range
        st.integers(max_value=-(2**1024)),
        st.sampled_from([None, True, False, np.True_, [1.0], (1.0,), {}, 1 + 0j, object(),
                         b"1.0", np.array([0.5, 0.5])]),
        st.text(max_size=12),  # strings, numeric ones included, are not numbers
    )


@st.composite
def params_kwargs(draw):
    """Keyword arguments of a valid ``Params``: the two stiffnesses and any other fields."""
    kwargs = {name: draw(valid_value(name)) for name in ("k_r", "k_theta")}
    for name in draw(st.sets(st.sampled_from(FIELDS[2:]))):
        kwargs[name] = draw(st.one_of(valid_value(name),
                                      valid_value(name).map(np.float64)))
    return kwargs


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e)


def near(x):
    """Values a hair off ``x``: x -+ 10^-u, u in [1, 15]."""
    return st.tuples(st.sampled_from([-1.0, 1.0]), st.floats(1.0, 15.0)).map(
        lambda su: x + su[0] * 10.0 ** -su[1])


# theta0 over [-pi, pi], with the axis (0, +-pi, exactly) and the pivot passage (near pi).
THETA0 = st.one_of(st.sampled_from([0.0, math.pi, -math.pi]), near(math.pi), near(0.0),
                   st.floats(-math.pi, math.pi))


@st.composite
def box(draw):
    """A support from the paper's parameter box (Figs. 5, 6): log-uniform springs and load."""
    return Params(k_r=draw(log_uniform(0.01, 3.0)), k_theta=draw(log_uniform(0.01, 3.0)),
                  F_N=draw(log_uniform(0.1, 10.0)), theta0=draw(THETA0))


# --------------------------------------------------------------------------- Params

@FAST
@given(params_kwargs())
def test_valid_params_never_raise_and_store_floats(kwargs):
    p = Params(**kwargs)
    for name, value in kwargs.items():
        stored = getattr(p, name)
        assert type(stored) is float and stored == float(value)
    assert p.f_N == p.beta * p.F_N


@FAST
@given(params_kwargs())
def test_params_round_trip(kwargs):
    p = Params(**kwargs)
    copies = [Params(**p.as_dict()), p.replace(), pickle.loads(pickle.dumps(p)),
              eval(repr(p), {"Params": Params})]  # noqa: S307 - our own repr
    for q in copies:
        assert q == p and hash(q) == hash(p)
    assert {p: 1}[copies[0]] == 1  # a usable cache key
    assert json.loads(json.dumps(p.as_dict())) == p.as_dict()


@FAST
@given(params_kwargs(), st.data())
def test_replace_changes_one_field(kwargs, data):
    p = Params(**kwargs)
    name = data.draw(st.sampled_from(FIELDS))
    value = data.draw(valid_value(name))
    q = p.replace(**{name: value})
    assert getattr(q, name) == value
    assert {k: v for k, v in q.as_dict().items() if k != name} == \
        {k: v for k, v in p.as_dict().items() if k != name}
    assert (q == p) == (value == getattr(p, name))


@FAST
@given(st.sampled_from(FIELDS), st.data())
def test_invalid_field_raises_value_error_naming_it(name, data):
    bad = data.draw(invalid_value(name))
    with pytest.raises(ValueError, match=rf"^{name}=") as info:
        Params(**{"k_r": 1.0, "k_theta": 1.0, name: bad})
    message = str(info.value)
    assert "is not a number" in message or "is invalid" in message
    # and replace() validates the same way
    with pytest.raises(ValueError, match=rf"^{name}="):
        Params(1.0, 1.0).replace(**{name: bad})


@FAST
@given(st.floats(-2 * math.pi, 2 * math.pi))
def test_rest_position_is_on_the_unit_circle_and_exact_on_the_axis(theta0):
    x, y = Params(1.0, 1.0, theta0=theta0).rest_position
    assert math.hypot(x, y) == pytest.approx(1.0, abs=1e-15)
    on_axis = any(theta0 == k * math.pi for k in (-2, -1, 0, 1, 2))
    if on_axis:
        assert y == 0.0 and abs(x) == 1.0


# --------------------------------------------------------------------------- solver options

# Documented ranges of the options (SolverOptions, simulate_support's samples).
BAD_OPTIONS = {
    "rtol": st.one_of(st.floats(max_value=1e-14, exclude_max=True), st.floats(min_value=1e-2,
                      exclude_min=True), st.just(math.nan), st.sampled_from([None, True, "1e-6"])),
    "atol": st.one_of(st.floats(max_value=1e-16, exclude_max=True), st.floats(min_value=1e-2,
                      exclude_min=True), st.just(math.nan), st.sampled_from([True, "1e-8", []])),
    "method": st.one_of(st.text(max_size=10).filter(lambda m: m not in METHODS),
                        st.sampled_from([None, 1, ("auto",), "AUTO", " auto"])),
    "max_steps": st.one_of(st.integers(max_value=9), st.integers(min_value=10**8 + 1),
                           st.floats(10.0, 1e8).filter(lambda x: not x.is_integer()),
                           st.sampled_from([math.nan, math.inf, None, True, "100", [100]])),
    "tau_max": st.one_of(st.floats(max_value=1.0, exclude_max=True), st.floats(min_value=1e8,
                         exclude_min=True), st.sampled_from([math.nan, None, True, "10"])),
    "samples": st.one_of(st.integers(max_value=-1), st.integers(min_value=10**6 + 1),
                         st.floats(0.0, 1e6).filter(lambda x: not x.is_integer()),
                         st.sampled_from([math.nan, math.inf, None, True, "5", [5]])),
}


@FAST
@given(st.sampled_from(sorted(BAD_OPTIONS)), st.data())
def test_invalid_solver_options_raise_value_error_naming_them(name, data):
    bad = data.draw(BAD_OPTIONS[name])
    with pytest.raises(ValueError, match=rf"^{name}="):
        simulate_support(Params(1.0, 1.0), **{name: bad})
    if name != "samples":
        with pytest.raises(ValueError, match=rf"^{name}="):
            SolverOptions(**{name: bad})


@FAST
@given(st.one_of(st.none(), st.dictionaries(st.text(max_size=5), st.floats()), st.floats(),
                 st.text(max_size=5)))
def test_params_must_be_a_params(bad):
    with pytest.raises(TypeError, match="must be a model.Params"):
        simulate_support(bad)


@FAST
@given(rtol=log_uniform(1e-14, 1e-2), atol=st.one_of(st.none(), log_uniform(1e-16, 1e-2)),
       method=st.sampled_from(METHODS), max_steps=st.integers(10, 10**8),
       tau_max=st.floats(1.0, 1e8))
def test_valid_solver_options_are_accepted(rtol, atol, method, max_steps, tau_max):
    o = SolverOptions(rtol=rtol, atol=atol, method=method, max_steps=max_steps, tau_max=tau_max)
    assert o.rtol == rtol and o.atol == (rtol / 100 if atol is None else atol)
    assert type(o.max_steps) is int and o.max_steps == max_steps
    assert o == SolverOptions(rtol=rtol, atol=o.atol, method=method, max_steps=float(max_steps),
                              tau_max=tau_max)


# --------------------------------------------------------------------------- integration

def _finite(*values) -> bool:
    return all(math.isfinite(float(v)) for v in values)


def check_result(res: SupportResult):
    """What every result promises, successful or not."""
    assert isinstance(res, SupportResult)
    assert res.success == (res.status == 0) and res.message
    if not res.success:
        assert res.status in (1, 2, 3, 4)
        cause = {1: "max_steps", 2: "tau_max", 3: "step size", 4: "non-finite"}[res.status]
        assert cause in res.message
        with pytest.raises(IntegrationError):
            res.check()
        return
    assert res.check() is res
    p = res.params
    assert _finite(res.t_out, res.W, res.D_x, res.D_y, res.U_el, res.K, res.energy_residual,
                   res.dtheta_rms, res.dr_rms, res.r_min, *res.F_mean, *res.state_out)
    assert res.t_out > 0
    scale = max(abs(res.W), 1.0)
    assert res.D_x >= -1e-6 * scale and res.D_y >= -1e-6 * scale  # dissipation
    # U_el is relative to the start at r = 1: the repulsion exp(-r/lam)/2 left there is
    # the most it can fall below zero.
    assert res.K >= 0 and res.U_el >= -0.5 * math.exp(-1 / p.lam) - 1e-6 * scale
    # The balance W = D_x + D_y + U_el + K (Eq. 12) and its reported residual
    balance = res.W - (res.D_x + res.D_y + res.U_el + res.K)
    assert balance == pytest.approx(res.energy_residual, rel=1e-9, abs=1e-12 * scale)
    assert res.accurate == (abs(res.energy_residual) / max(abs(res.W), 1e-300)
                            <= ACCURACY_FACTOR * max(res.options.rtol, 1e-9))
    if not res.accurate:
        assert "inaccurate" in res.message
    # |F_f| / f_N = mu(|v_R|) <= mu_s, so its time average is bounded too
    assert math.hypot(*res.F_mean) <= p.mu_s * (1 + 1e-6)
    assert res.F_mean[0] * p.f_N * res.t_out == pytest.approx(res.W, rel=1e-9, abs=1e-12)
    assert 0.0 <= res.r_min <= 1.0 + 1e-12
    assert res.pivot_approach == (res.r_min < res.pivot_radius)
    if res.pivot_approach:
        assert "pivot" in res.message
    assert res.dtheta_rms >= 0 and res.dr_rms >= 0
    json.dumps(res.to_dict(), allow_nan=False, default=float)  # strict JSON


@SOLVE
@given(params=box(), rtol=log_uniform(1e-6, 1e-4), method=st.sampled_from(["auto", "explicit",
                                                                           "implicit"]))
def test_integration_over_the_box_is_finite_or_says_why(params, rtol, method):
    res = simulate_support(params, rtol=rtol, method=method, max_steps=MAX_STEPS)
    check_result(res)
    if method == "auto":  # the default path must finish every case of the box
        assert res.success, res.message
    assert res.stats["n_steps"] + res.stats["n_rejected"] <= MAX_STEPS


@SOLVE
@given(params=box(), rtol=log_uniform(1e-6, 1e-4), samples=st.integers(2, 300))
def test_sampled_series_covers_the_contact(params, rtol, samples):
    res = simulate_support(params, rtol=rtol, samples=samples, max_steps=MAX_STEPS)
    assert res.success, res.message
    s = res.series
    if s is None:  # allowed only when the contact has no two distinct nodes
        return
    assert s.tau.size == samples and s.tau[0] == 0.0
    assert s.tau[-1] == pytest.approx(res.t_out, rel=1e-12)
    assert np.all(np.diff(s.tau) >= 0)
    for name, values in s.as_dict().items():
        assert np.all(np.isfinite(values)), name
    assert np.all(s.F_abs <= params.mu_s * (1 + 1e-9))


@settings(max_examples=150, deadline=20_000, database=None, phases=PHASES)
@given(params=box(), theta0=st.one_of(near(math.pi).filter(lambda t: 0 < t < math.pi),
                                      st.floats(1e-12, math.pi, exclude_max=True)),
       rtol=log_uniform(1e-6, 1e-4), method=st.sampled_from(["auto", "explicit", "implicit"]))
def test_mirror_symmetry(params, theta0, rtol, method):
    """theta0 -> -theta0 mirrors the motion (y -> -y): x, v_x, t_out, the energies stay,
    y, v_y, theta - theta0 and F_y change sign. The pivot passage near pi amplifies any
    asymmetry of the arithmetic to order one, so this holds there only if every solver
    path is exactly mirror symmetric."""
    up = simulate_support(params.replace(theta0=theta0), rtol=rtol, method=method,
                          max_steps=MAX_STEPS)
    down = simulate_support(params.replace(theta0=-theta0), rtol=rtol, method=method,
                            max_steps=MAX_STEPS)
    assert (up.status, up.stats["n_steps"]) == (down.status, down.stats["n_steps"])
    close = dict(rel=1e-12, abs=1e-12)
    assert down.t_out == pytest.approx(up.t_out, **close)
    for i, sign in enumerate([1, -1, 1, -1]):
        assert down.state_out[i] == pytest.approx(sign * up.state_out[i], **close), i
    assert down.state_out[4] + theta0 == pytest.approx(-(up.state_out[4] - theta0), **close)
    assert down.F_mean[0] == pytest.approx(up.F_mean[0], **close)
    assert down.F_mean[1] == pytest.approx(-up.F_mean[1], **close)
    for name in ("W", "D_x", "D_y", "U_el", "K", "r_min"):
        assert getattr(down, name) == pytest.approx(getattr(up, name), **close), name


@settings(max_examples=40, deadline=20_000, database=None, phases=PHASES)
@given(params=box(), theta0=st.sampled_from([0.0, math.pi, -math.pi, 2 * math.pi,
                                             -2 * math.pi]),
       method=st.sampled_from(["auto", "explicit", "implicit"]))
def test_start_on_the_axis_stays_on_it(params, theta0, method):
    res = simulate_support(params.replace(theta0=theta0), rtol=1e-5, method=method,
                           max_steps=MAX_STEPS)
    check_result(res)
    if res.success:
        assert res.state_out[1] == 0.0 and res.state_out[3] == 0.0
        assert res.F_mean[1] == 0.0 and res.D_y == 0.0


@settings(max_examples=40, deadline=20_000, database=None, phases=PHASES)
@given(params=box(), theta0=st.floats(0.05, math.pi - 0.05))
def test_theta0_is_periodic(params, theta0):
    """theta0 and theta0 - 2 pi (both in the documented range) are the same support; away
    from the pivot (where the motion is ill-conditioned) they agree to the tolerance."""
    a = simulate_support(params.replace(theta0=theta0), rtol=1e-8)
    b = simulate_support(params.replace(theta0=theta0 - 2 * math.pi), rtol=1e-8)
    assert a.success and b.success, (a.message, b.message)
    assume(not (a.pivot_approach or b.pivot_approach))
    assert b.t_out == pytest.approx(a.t_out, rel=1e-6)
    np.testing.assert_allclose(b.F_mean, a.F_mean, atol=1e-6)
    assert b.D_y == pytest.approx(a.D_y, rel=1e-5, abs=1e-8)


@pytest.mark.slow
@settings(max_examples=200, deadline=60_000, database=None, phases=PHASES,
          suppress_health_check=[HealthCheck.too_slow])
@given(params=st.builds(Params, k_r=log_uniform(1e-3, 1e3), k_theta=log_uniform(1e-3, 1e3),
                        F_N=log_uniform(0.01, 30.0), theta0=THETA0,
                        beta=st.floats(0.01, 1.0), lam=st.floats(1e-3, 0.2)),
       rtol=log_uniform(1e-9, 1e-3), method=st.sampled_from(METHODS[:3]),
       max_steps=st.integers(10, 50_000), tau_max=st.floats(1.0, 1e4))
def test_integration_beyond_the_box_with_tight_budgets(params, rtol, method, max_steps,
                                                       tau_max):
    res = simulate_support(params, rtol=rtol, method=method, max_steps=max_steps,
                           tau_max=tau_max)
    check_result(res)
    assert res.stats["n_steps"] + res.stats["n_rejected"] <= max_steps
    if res.status == 2:  # the time budget is checked before each step
        assert res.t_out >= tau_max
