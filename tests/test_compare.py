"""Comparing two states (app/compare.py, the ``A=`` URL key, the A overlays and readouts).

The pinned state A round-trips through the URL; a garbled ``A=`` gives a notice and pins
nothing; pin, swap and clear; ``SessionResults`` computes A's results only while something
is pinned and only those of the visible tab, with B's request keys (so the shared cache
serves A where it equals a state computed before); the overlays' data and the readouts'
differences are A's and B's.
"""
from __future__ import annotations

import math
import urllib.parse

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app import results as results_module
from app.state import ExplorerState
from app.defaults import BETA_BOUNDS, F_N_BOUNDS, K_BOUNDS, RTOLS
from app.pinned_state import PINNED_ALL, PINNED_KEYS
from app.urlstate import MAX_PINNED_CHARS, parse, parse_pinned, pinned_text, serialize, to_search

PINNED = dict(k_r=0.5, k_theta=0.2, F_N=1.0, theta0=60.0, rtol=1e-6, beta_mode="self",
              beta=1.0)


# ------------------------------------------------------------------------------ URL

@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(k_r=st.floats(*K_BOUNDS), k_theta=st.floats(*K_BOUNDS), F_N=st.floats(*F_N_BOUNDS),
       theta0=st.floats(0.0, 360.0, exclude_max=True), rtol=st.sampled_from(RTOLS),
       beta=st.one_of(st.none(), st.floats(*BETA_BOUNDS)))
def test_a_pinned_state_round_trips_through_the_url(k_r, k_theta, F_N, theta0, rtol, beta):
    pinned = dict(k_r=k_r, k_theta=k_theta, F_N=F_N, theta0=theta0, rtol=rtol,
                  beta_mode="self" if beta is None else "fixed",
                  beta=1.0 if beta is None else beta)
    state = ExplorerState(k_r=1.0, pinned=pinned)
    search = state.to_search()
    assert len(urllib.parse.parse_qs(search[1:])["A"][0]) <= 100  # MAX_VALUE_CHARS
    back = ExplorerState()
    assert back.load_query(search) == []
    assert back.k_r == 1.0 and set(back.pinned) == set(PINNED_ALL)
    for name, value in pinned.items():
        got = back.pinned[name]
        if name == "theta0":  # an angle: 359.9999996 deg comes back as 0
            assert abs((got - value + 180.0) % 360.0 - 180.0) <= 1e-5 * 360.0
        elif isinstance(value, float) and name != "rtol" and not (name == "beta" and beta is None):
            assert got == pytest.approx(value, rel=1e-5), name
        elif name != "beta" or beta is not None:
            assert got == value, name


def test_the_pinned_text_is_short_and_readable_in_the_address():
    text = pinned_text(PINNED)
    assert text == "k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:60"
    assert "A=k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:60" in to_search(
        {**ExplorerState().values(), "pinned": PINNED})
    fixed = pinned_text({**PINNED, "rtol": 1e-8, "beta_mode": "fixed", "beta": 0.5})
    assert fixed.endswith(",rtol:1e-08,beta:0.5")
    assert parse_pinned(fixed) == {**ExplorerState().snapshot(), **PINNED, "rtol": 1e-8,
                                   "beta_mode": "fixed", "beta": 0.5}
    assert set(PINNED_KEYS) < set(PINNED_ALL)
    assert "A" not in serialize(ExplorerState().values())  # nothing pinned: no A=


def test_a_pinned_state_names_what_it_omits_by_its_defaults():
    assert parse_pinned("k_r:0.5") == {**ExplorerState().snapshot(), "k_r": 0.5}


@pytest.mark.parametrize("junk", [
    "zzz", "k_r", "k_r:", "k_r:abc", "k_r:50", "k_r:nan", "tab:polar", "k_r:0.5,foo:1",
    "k_r:0.5;k_theta:0.2", "theta0_deg:360", "beta:0", ":", ",,,", "rtol:0.5",
])
def test_a_garbled_pinned_state_gives_a_notice_and_pins_nothing(junk):
    values, notices = parse({"A": junk, "k_r": "0.5"})
    assert "pinned" not in values and values["k_r"] == 0.5  # the rest of the URL counts
    assert len(notices) == 1 and notices[0].startswith("URL parameter A=")
    assert "k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:90" in notices[0]  # says how to write it
    state = ExplorerState()
    state.load_query(urllib.parse.urlencode({"A": junk}))
    assert state.pinned is None and state.notice


def test_an_over_long_pinned_state_is_refused_unread():
    values, notices = parse({"A": "k_r:0.5," * (MAX_PINNED_CHARS // 8 + 1)})  # one too many
    assert "pinned" not in values and "too long" in notices[0]


# ------------------------------------------------------------------------------ state

def test_pin_swap_and_clear():
    s = ExplorerState()
    s.pin()
    assert s.pinned == s.snapshot()
    s.param.update(k_r=0.5, theta0=30.0)
    s.dist_family = "pair"  # the Design tab's values are exchanged too
    a, b = dict(s.pinned), s.snapshot()
    s.swap_pin()
    assert s.snapshot() == a and s.pinned == b
    assert s.dist_family == "vonmises" and s.pinned["dist_family"] == "pair"
    s.reset()  # Reset is about the physics: the comparison stays
    assert s.pinned == b and s.k_r == 3.0
    s.clear_pin()
    assert s.pinned is None
    s.swap_pin()  # nothing to swap with: nothing happens
    assert s.pinned is None and s.k_r == 3.0


def test_an_address_without_a_clears_the_pin_on_back_and_forward():
    s = ExplorerState(pinned=PINNED)
    s.restore_query("?k_r=1")
    assert s.pinned is None


# ------------------------------------------------------------------------------ results

def _started(state, tab_results):
    r = results_module.SessionResults(state)
    r.show(tab_results)
    r.start()
    return r


def test_nothing_of_a_is_computed_while_nothing_is_pinned(pool):
    r = _started(ExplorerState(), ("support", "uniform", "polar", "load"))
    calls = list(pool.calls)
    assert calls.count("compute_support") == 1 and calls.count("compute_polar") == 1
    assert r.support_A is None and r.polar_A is None and r.uniform_A is None
    assert r.A is None  # not even A's results object
    pool.calls.clear()
    r.state.k_r = 0.5
    assert pool.calls.count("compute_support") == 1  # B's only


def test_a_is_computed_while_pinned_for_the_visible_tab_only(pool):
    state = ExplorerState(pinned=PINNED)
    r = _started(state, ("support", "uniform"))
    assert pool.calls.count("compute_support") == 2 and "compute_polar" not in pool.calls
    a = r.support_A
    assert a.params.k_r == 0.5 and a.params.theta0 == pytest.approx(math.radians(60.0))
    assert r.support.params.k_r == 3.0 and r.uniform_A["FTx_over_mu0FN"] != \
        r.uniform["FTx_over_mu0FN"]
    pool.calls.clear()
    state.k_r = 1.0  # B moves; A stays
    assert pool.calls.count("compute_support") == 1 and r.support_A is a
    pool.calls.clear()
    r.show(("support", "polar"))
    assert pool.calls.count("compute_polar") == 2
    assert r.polar_A.settings["k_r"] == 0.5 and r.polar.settings["k_r"] == 1.0
    state.clear_pin()
    assert r.support_A is r.polar_A is r.uniform_A is r.load_A is None
    pool.calls.clear()
    state.pin()
    assert r.support_A.params.k_r == 1.0


def test_a_pinned_at_b_asks_for_b_s_results_by_the_same_keys(pool):
    """The shared cache then serves A at no cost: pinning repeats no computation."""
    state = ExplorerState(k_r=0.7, theta0=45.0)
    r = _started(state, ("support", "uniform", "polar", "load"))
    state.pin()
    for name in ("support", "uniform", "polar", "load"):
        assert r.A.slots[name].applied_key == r.slots[name].applied_key, name


def test_a_s_errors_are_shown_as_a_s(pool, monkeypatch):
    from app import worker

    state = ExplorerState()
    r = _started(state, ("support", "uniform"))
    real = worker.compute_uniform

    def fails_for_a(k_r, *args):
        if k_r == 0.5:
            raise FloatingPointError("simulated")
        return real(k_r, *args)
    monkeypatch.setattr(worker, "compute_uniform", fails_for_a)
    state.pinned = PINNED
    assert any(m.startswith("A (pinned): Uniform array failed") for m in r.error_messages)
    state.clear_pin()
    assert not r.error_messages


# ------------------------------------------------------------------------------ views

def test_the_readouts_give_a_b_and_their_difference(pool):
    from app.views.readouts import COMPARED, compare_markdown, compared_values, difference

    state = ExplorerState(pinned=PINNED)
    r = _started(state, ("support", "uniform"))
    text = compare_markdown(r.support_A, r.support, r.uniform_A, r.uniform, "paper")
    a = compared_values(r.support_A, r.uniform_A, "paper")
    b = compared_values(r.support, r.uniform, "paper")
    assert a[0] == r.support_A.fixed.FTx_over_mu0FN and b[-1] == r.uniform["FTx_over_mu0FN"]
    for (label, _), x, y in zip(COMPARED, a, b):
        diff, rel = difference(x, y)
        assert float(diff) == pytest.approx(y - x, rel=2e-3, abs=1e-12)
        assert float(rel.rstrip(" %")) == pytest.approx(100 * (y - x) / abs(x), abs=0.051)
        assert f"| {label} |" in text and diff in text
    assert "k_r = 0.5" in text and "k_r = 3" in text
    assert difference(None, 1.0) == ("–", "–") and difference(0.0, 1.0) == ("+1", "–")


def test_the_overlays_carry_both_data_sets_and_hide_without_a(pool):
    from app.views import Dashboard

    state = ExplorerState(pinned=PINNED)
    page = Dashboard(state)
    src = page.support._sources
    a, b = page.results.support_A.series, page.results.support.series
    assert list(src["orbit_A"].data["x"]) == list(a.x) and len(src["orbit"].data["x0"]) == \
        len(b.x) - 1
    assert list(src["forces_A"].data["F_x"]) == list(a.F_x)
    assert all(r.visible for r in page.support._pinned[page.support.scene])
    assert page.readouts.compare_pane.visible
    state.tab = "polar"
    polar = page.polar
    for key, fig in polar.figures.items():
        a_curve = polar._sources[f"polar_{key}_A"].data
        assert len(a_curve["x"]) == len(polar._sources[f"polar_{key}"].data["x"]) > 0
        r_lo, r_hi, _ = polar._axes[key]
        # The radial axis covers both curves: A is not drawn past the rim.
        assert max(a_curve["value"]) <= r_hi + 1e-12 and min(a_curve["value"]) >= r_lo - 1e-12
    state.clear_pin()
    # The One-support tab's overlays follow once that tab is shown (not while hidden).
    assert len(src["orbit_A"].data["x"]) > 0
    state.tab = "support"
    assert len(src["orbit_A"].data["x"]) == 0
    assert not any(r.visible for r in page.support._pinned[page.support.scene])
    assert not page.readouts.compare_pane.visible
    assert "A=" not in page.state.to_search()
