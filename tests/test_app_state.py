"""The dashboard's state (app/state.py, app/urlstate.py), without a server.

Every control maps to the right ``model.Params`` (or array argument); the presets and
reset; the URL round trip; unusable URL values fall back to defaults with a notice and
never raise.
"""
import concurrent.futures as cf
import math

import numpy as np
import pytest

from app import worker
from app.state import PRESETS, ExplorerState, classify
from app.defaults import DEFAULTS, RTOLS
from app.urlstate import parse, serialize, to_search
from model import REGIMES, Params


def test_defaults_are_the_pendulum_of_fig_7a():
    s = ExplorerState()
    assert s.params == Params(k_r=3.0, k_theta=0.01, F_N=1.0, theta0=math.pi / 2, beta=1.0)
    assert s.array_beta == "self"
    assert s.regime == "pendulum"
    assert s.notice == ""


@pytest.mark.parametrize("name, value, field, expected", [
    ("k_r", 0.2, "k_r", 0.2),
    ("k_theta", 1.7, "k_theta", 1.7),
    ("F_N", 4.0, "F_N", 4.0),
    ("theta0", 135.0, "theta0", 3 * math.pi / 4),
    ("theta0", 0.0, "theta0", 0.0),
    ("theta0", 359.0, "theta0", math.radians(359.0)),
])
def test_each_physical_control_maps_to_its_field(name, value, field, expected):
    s = ExplorerState()
    before = s.params.as_dict()
    setattr(s, name, value)
    after = s.params.as_dict()
    assert after[field] == pytest.approx(expected, rel=1e-15, abs=1e-15)
    assert {k: v for k, v in after.items() if k != field} == \
        {k: v for k, v in before.items() if k != field}


def test_beta_modes():
    s = ExplorerState(beta=0.4)
    assert s.array_beta == "self"  # the solver finds beta
    s.beta_mode = "fixed"
    assert s.array_beta == 0.4
    s.beta = 1.0
    assert s.array_beta == 1.0


def test_the_load_factor_and_orientations_travel_as_arguments_not_inside_params():
    """``support`` is the support and its load, ``params`` adds the slider's theta0; the
    load factor is the array functions' argument in both modes, so no call has to reset a
    field of ``Params`` behind its caller's back."""
    from model import Params
    s = ExplorerState(k_r=0.5, k_theta=2.0, F_N=3.0, theta0=30.0, beta=0.4, beta_mode="fixed")
    assert s.support == Params(k_r=0.5, k_theta=2.0, F_N=3.0)
    assert s.params == s.support.replace(theta0=math.radians(30.0))
    assert s.params.beta == 1.0 and s.array_beta == 0.4
    # an orientation sweep covers its own theta0 values: given the one support's, it
    # refuses it with the fix instead of quietly replacing it
    with pytest.raises(ValueError, match="theta0=.*not used by orientation_sweep"):
        worker.compute_polar(s.params, s.array_beta)
    # the Array tab's input: the support alone for a uniform array, at theta0 otherwise
    s.orientation = "uniform"
    assert worker.array_params(s) == s.support
    s.orientation = "fixed"
    assert worker.array_params(s) == s.params


def test_solver_and_display_controls_do_not_change_params():
    s = ExplorerState()
    p = s.params
    s.param.update(rtol=1e-8, average="duration", map_quantity="5b", tab="polar",
                   projector=True)
    assert s.params == p
    assert s.rtol == 1e-8


def test_controls_are_bounded():
    s = ExplorerState()
    for name, bad in [("k_r", 0.001), ("k_theta", 5.0), ("F_N", 20.0), ("theta0", 360.0),
                      ("theta0", -1.0), ("beta", 0.0), ("rtol", 1e-3)]:
        with pytest.raises(ValueError):
            setattr(s, name, bad)


@pytest.mark.parametrize("name", list(REGIMES))
def test_presets_set_the_papers_regimes(name):
    s = ExplorerState(F_N=3.0, theta0=45.0)
    s.apply_preset(name)
    assert (s.k_r, s.k_theta) == (REGIMES[name].k_r, REGIMES[name].k_theta) == PRESETS[name]
    assert (s.F_N, s.theta0) == (3.0, 45.0)  # a preset changes only the springs
    assert s.regime == name
    assert s.params == REGIMES[name].replace(F_N=3.0, theta0=math.radians(45.0))


def test_unknown_preset_raises():
    with pytest.raises(ValueError, match="unknown"):
        ExplorerState().apply_preset("wobbly")


def test_classify_quadrants():
    assert classify(3, 0.01) == "pendulum" and classify(0.01, 3) == "slider"
    assert classify(3, 3) == "stiff" and classify(0.03, 0.03) == "soft"


def test_reset_restores_every_control_but_the_view():
    s = ExplorerState()
    s.param.update(k_r=0.05, k_theta=2.0, F_N=7.0, theta0=200.0, rtol=1e-8, beta_mode="fixed",
                   beta=0.3, average="duration", map_quantity="5b", projector=True,
                   tab="map", notice="x")
    s.reset()
    assert s.values() == {**DEFAULTS, "tab": "map", "projector": True}
    assert s.notice == ""


def test_restore_query_sets_exactly_the_state_of_an_address():
    s = ExplorerState()
    s.param.update(k_r=0.05, F_N=7.0, projector=True, tab="map", average="duration")
    notices = s.restore_query("?k_r=0.5&k_theta=0.2&F_N=2&theta0_deg=45&tab=polar")
    assert notices == [] and s.notice == ""
    assert s.values() == {**DEFAULTS, "k_r": 0.5, "k_theta": 0.2, "F_N": 2.0, "theta0": 45.0,
                          "tab": "polar"}
    assert s.restore_query("?k_r=banana") and "k_r" in s.notice
    assert s.values() == DEFAULTS


def test_the_preset_of_the_current_springs_is_found():
    s = ExplorerState()
    assert s.matching_preset() == "pendulum"
    for name, (k_r, k_theta) in PRESETS.items():
        s.apply_preset(name)
        assert s.matching_preset() == name
    s.k_r = 0.5
    assert s.matching_preset() is None


def test_set_theta0_wraps_and_rounds():
    s = ExplorerState()
    s.set_theta0(-90.2)
    assert s.theta0 == 270.0
    s.set_theta0(359.6)
    assert s.theta0 == 0.0


def test_set_stiffness_clamps():
    s = ExplorerState()
    s.set_stiffness(1e-4, 50.0)
    assert (s.k_r, s.k_theta) == (0.01, 3.0)


# ---------------------------------------------------------------------- URL

def test_url_of_the_default_state():
    assert ExplorerState().to_query() == {"k_r": "3", "k_theta": "0.01", "F_N": "1",
                                          "theta0_deg": "90"}


def test_url_round_trip_of_every_control():
    s = ExplorerState()
    s.param.update(k_r=10 ** -0.52, k_theta=0.0234, F_N=10 ** 0.37, theta0=212.0, rtol=1e-7,
                   beta_mode="fixed", beta=0.55, average="duration", map_quantity="5b",
                   tab="load", projector=True)
    query = s.to_query()
    t = ExplorerState()
    assert t.load_query(query) == []
    for name, value in s.values().items():
        if isinstance(value, float):
            assert getattr(t, name) == pytest.approx(value, rel=1e-5), name
        else:
            assert getattr(t, name) == value, name
    assert t.to_query() == query  # stable after one trip
    assert t.params.k_r == pytest.approx(s.params.k_r, rel=1e-5)


def test_url_round_trip_through_a_search_string_and_session_args():
    s = ExplorerState(k_r=0.03, k_theta=0.03, F_N=2.5, theta0=30.0)
    t = ExplorerState()
    t.load_query(s.to_search())
    assert t.values() == s.values()
    # pn.state.session_args gives lists of bytes
    u = ExplorerState()
    u.load_query({k: [v.encode()] for k, v in s.to_query().items()})
    assert u.values() == s.values()


def test_url_regime_key_and_override():
    s = ExplorerState()
    assert s.load_query("?regime=slider&F_N=2") == []
    assert (s.k_r, s.k_theta, s.F_N) == (0.01, 3.0, 2.0)
    s = ExplorerState()
    s.load_query("?regime=soft&k_r=0.5")
    assert (s.k_r, s.k_theta) == (0.5, 0.03)


def test_url_beta():
    s = ExplorerState()
    s.load_query("?beta=0.25")
    assert (s.beta_mode, s.beta) == ("fixed", 0.25)
    s.load_query("?beta=self")
    assert s.beta_mode == "self"


@pytest.mark.parametrize("key, text", [
    ("k_r", "nan"), ("k_r", "-1"), ("k_r", "abc"), ("k_r", "1e308"), ("k_r", "inf"),
    ("k_r", ""), ("k_theta", "0"), ("k_theta", "NaN"), ("F_N", "-1"), ("F_N", "1e999"),
    ("F_N", "10.5"), ("theta0_deg", "360"), ("theta0_deg", "-1"), ("theta0_deg", "nan"),
    ("theta0_deg", "ninety"), ("rtol", "0.5"), ("rtol", "abc"), ("beta", "0"),
    ("beta", "1.5"), ("beta", "nan"), ("avg", "median"), ("map", "5c"), ("tab", "x"),
    ("projector", "maybe"), ("regime", "wobbly"), ("k_r", "3" * 400),
])
def test_bad_url_values_fall_back_to_defaults_with_a_notice(key, text):
    s = ExplorerState()
    good_key, good, name = ("F_N", "2", "F_N") if key != "F_N" else ("theta0_deg", "45", "theta0")
    notices = s.load_query({key: text, good_key: good})
    assert len(notices) == 1 and key in notices[0] and "default" in notices[0]
    assert s.notice == notices[0]
    assert s.values() == {**DEFAULTS, name: float(good)}  # the good value is still used
    assert isinstance(s.params, Params)
    assert len(s.notice) < 300  # long junk is shortened in the message


def test_unknown_url_keys_are_reported_and_bokeh_keys_ignored():
    s = ExplorerState()
    notices = s.load_query("?kr=0.5&bokeh-session-id=abc")
    assert notices == ["Unknown URL parameter 'kr' ignored."]
    assert s.values() == DEFAULTS


def test_parse_never_raises_on_junk():
    for junk in ["", "?", "?&&&", "?k_r", "?k_r=&k_r=0.5", "%zz", "?theta0_deg=%00",
                 "?k_r=0x10", "?=1"]:
        values, notices = parse(junk)
        assert isinstance(values, dict) and isinstance(notices, list)
    values, _ = parse("?k_r=&k_r=0.5")  # repeated keys: the last one counts
    assert values == {"k_r": 0.5}


def test_serialize_only_writes_what_differs_for_optional_controls():
    values = dict(DEFAULTS)
    assert set(serialize(values)) == {"k_r", "k_theta", "F_N", "theta0_deg"}
    values.update(rtol=1e-4, beta_mode="fixed", beta=0.5, projector=True)
    q = serialize(values)
    assert (q["rtol"], q["beta"], q["projector"]) == ("0.0001", "0.5", "1")
    assert parse(to_search(values))[0]["rtol"] in RTOLS


# ---------------------------------------------------------------------- the page, no server

@pytest.fixture(scope="module")
def dashboard():
    """One dashboard without a server: jobs run synchronously (in the worker processes)."""
    from app.views import Dashboard

    return Dashboard(ExplorerState())


def _orbit(page):
    return np.asarray(page.support._sources["orbit"].data["x1"]).copy()


def _error(page, name="support"):
    return page.results.errors.get(name, "")


def test_the_page_builds_with_data(dashboard):
    assert dashboard.results.support.result is not None and _error(dashboard) == ""
    assert len(_orbit(dashboard)) == 399
    assert dashboard.results.uniform["FTx_over_mu0FN"] == pytest.approx(0.945, abs=0.01)
    assert dashboard.messages == []


@pytest.mark.parametrize("change", [dict(k_r=0.5), dict(k_theta=0.5), dict(F_N=3.0),
                                    dict(theta0=30.0), dict(rtol=1e-8),
                                    dict(beta_mode="fixed", beta=0.5)])
def test_every_control_changes_the_plotted_support(dashboard, change):
    state = dashboard.state
    state.reset()
    before = _orbit(dashboard)
    state.param.update(**change)
    data = dashboard.results.support
    assert data.params.k_r == state.k_r and data.params.theta0 == state.params.theta0
    after = _orbit(dashboard)
    assert before.shape != after.shape or not np.array_equal(before, after)
    state.reset()


def test_a_preset_changes_the_orbit_and_the_regime_text(dashboard):
    dashboard.state.reset()
    before = _orbit(dashboard)
    dashboard.state.apply_preset("soft")
    assert not np.allclose(before, _orbit(dashboard))
    assert "Soft" in dashboard.readouts.regime.html
    dashboard.state.reset()


def test_a_model_error_is_shown_and_the_page_recovers(dashboard, monkeypatch):

    from app import slot

    class Broken:
        def submit(self, lane, key, fn, *args, **options):
            future = cf.Future()
            future.set_exception(RuntimeError("solver exploded"))
            return future

    dashboard.state.reset()
    before = _orbit(dashboard)
    monkeypatch.setattr(slot, "work_pool", Broken)
    dashboard.state.F_N = 2.0
    assert "solver exploded" in dashboard.alert.object and dashboard.alert.visible
    assert np.allclose(before, _orbit(dashboard))  # the last good plot stays
    monkeypatch.undo()
    dashboard.state.F_N = 3.0
    assert _error(dashboard) == "" and not dashboard.alert.visible
    dashboard.state.reset()


def test_polar_and_load_compute_only_when_visible(dashboard):
    state = dashboard.state
    state.reset()
    state.tab = "support"
    state.k_r = 0.7  # no polar sweep for hidden tabs
    assert dashboard.results.polar is None or dashboard.results.polar.settings["k_r"] != 0.7
    state.tab = "polar"
    sweep = dashboard.results.polar
    assert sweep.settings["k_r"] == 0.7 and len(sweep.columns["theta0"]) == 72
    x = np.asarray(dashboard.polar._sources["polar_FTy"].data["value"])
    assert x.size == 145 and np.allclose(x[:72], -x[72:144][::-1])  # F_T,y is odd
    state.tab = "load"
    assert len(dashboard.load.points) == 7
    state.tab = "support"
    state.reset()


def test_clicks_set_theta0_and_stiffness(dashboard):
    from types import SimpleNamespace

    state = dashboard.state
    state.tab = "map"  # builds the view
    state.tab = "polar"
    dashboard.polar._on_tap(SimpleNamespace(x=0.0, y=-0.5))
    assert state.theta0 == 270.0
    dashboard.regime_map._on_tap(SimpleNamespace(x=0.05, y=1.5))
    assert (state.k_r, state.k_theta) == (0.05, 1.5)
    assert dashboard.regime_map._sources["regime_now"].data["k_r"] == [0.05]
    state.tab = "support"
    state.reset()


def test_csv_downloads(dashboard):
    import csv
    import io

    text = dashboard._trajectory_csv().getvalue()
    rows = [r for r in csv.reader(io.StringIO(text)) if r and not r[0].startswith("#")]
    assert rows[0][:3] == ["tau", "x", "y"] and len(rows) == 401
    assert "k_r: 3.0" in text
    polar = dashboard._polar_csv().getvalue()
    assert "FTx_over_mu0FN" in polar


def test_the_page_builds_without_sizing_warnings(caplog):
    """Every container of every tab says how it stretches: Panel overrides none of them
    (each override logs a warning at every page build of a served class)."""
    import logging

    import panel as pn
    from bokeh.document import Document

    from app.defaults import TABS
    from app.views import Dashboard

    page = Dashboard(ExplorerState())
    for tab in TABS:
        page._build(tab)  # the view, without computing its results
    with caplog.at_level(logging.WARNING):
        pn.panel(page).get_root(Document())
    assert "overridden" not in caplog.text, caplog.text
