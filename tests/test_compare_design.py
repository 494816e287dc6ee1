"""Comparing two states on the Design tab and in what a researcher exports.

A pinned state A keeps the Design tab's inputs and distribution and round-trips through
the URL with them (bounded; a garbled design part refuses the whole of A); A's design
results are computed only while pinned and only while the Design tab is on screen, with
B's request keys; the Design tab draws A's point, curve and distribution beside B's and
gives A, B and B − A of the array; the headline, the CSV downloads and the view-as-code
snippet carry A.

The design is the notes' LDPE pillars at a load and speed inside the paper's map (as in
tests/test_design_tab.py), so each array takes about a second.
"""
from __future__ import annotations

import math
import urllib.parse

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app import results as results_module
from app import slot, worker
from app.pinned_state import PINNED_ALL, complete
from app import histogram
from app.state import ExplorerState, distribution_of
from app.views.compare_tables import distribution_words
from app.defaults import (DEFAULTS, DESIGN_INPUTS, DIST_FAMILIES, KAPPA_BOUNDS, MIX_BOUNDS,
                          PSI_BOUNDS)
from app.urlstate import MAX_PINNED_CHARS, parse, parse_pinned
from fakes import InProcessPool
from model import csvfile

FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s"
#: B, edited after pinning A = FAST: other pillars' speed, another distribution, springs.
B_EDIT = dict(design_V0="80 m/s", dist_family="pair", dist_deg=30.0, k_r=0.5)


def _a_query(search: str) -> str:
    return urllib.parse.parse_qs(search[1:])["A"][0]


# ------------------------------------------------------------------------------ URL

@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(family=st.sampled_from(DIST_FAMILIES), family2=st.sampled_from(DIST_FAMILIES),
       deg=st.floats(0.0, 360.0, exclude_max=True), deg2=st.floats(0.0, 360.0, exclude_max=True),
       kappa=st.floats(*KAPPA_BOUNDS), kappa2=st.floats(*KAPPA_BOUNDS),
       psi=st.floats(*PSI_BOUNDS), mix=st.floats(*MIX_BOUNDS),
       D=st.sampled_from(["5 um", "7.5 µm", "0.01 mm", "5,0 um", "1e-5 m"]))
def test_a_pinned_design_round_trips_through_the_url(family, family2, deg, deg2, kappa,
                                                      kappa2, psi, mix, D):
    a = dict(dist_family=family, dist2_family=family2, dist_deg=deg, dist2_deg=deg2,
             dist_kappa=kappa, dist2_kappa=kappa2, dist_psi=psi, mix_weight=mix, design_D=D)
    state = ExplorerState(pinned={**ExplorerState().snapshot(), **a, "k_r": 0.5})
    search = state.to_search()
    back = ExplorerState()
    assert back.load_query(search) == []
    assert back.design_D == DEFAULTS["design_D"] and back.dist_family == DEFAULTS["dist_family"]
    assert set(back.pinned) == set(PINNED_ALL) and back.pinned["k_r"] == 0.5
    for name, value in a.items():
        got = back.pinned[name]
        if isinstance(value, str):
            assert got == value, name  # a comma in a quantity's text survives
        elif name.endswith("_deg"):  # 6 digits of an angle: 359.9999996 comes back as 0
            assert abs((got - value + 180.0) % 360.0 - 180.0) <= 1e-5 * 360.0, name
        else:
            assert got == pytest.approx(value, rel=1e-5, abs=1e-300), name


def test_only_what_differs_from_the_defaults_is_written():
    s = ExplorerState()
    s.pin()
    assert _a_query(s.to_search()) == "k_r:3,k_theta:0.01,F_N:1,theta0_deg:90"
    s.param.update(design_D="10 um", dist_family="pair", dist_deg=30.0, mix_weight=0.25)
    s.pin()
    assert _a_query(s.to_search()) == ("k_r:3,k_theta:0.01,F_N:1,theta0_deg:90,d_D:10 um,"
                                       "dist:pair,dist_deg:30,mix:0.25")


def test_the_longest_pinned_state_fits_the_bound():
    """Every design input at the longest text the URL reads (40 characters), every
    distribution value written: within MAX_PINNED_CHARS, and read back."""
    def padded(text: str) -> str:  # the same quantity in 40 characters: 5 um -> 5.000... um
        number, _, unit = text.partition(" ")
        number += "" if "." in number else "."
        return number + "0" * (40 - len(number) - len(unit) - (1 if unit else 0)) + \
            (" " + unit if unit else "")
    longest = {name: padded(DEFAULTS[name] or "0.36 GPa") for name in DESIGN_INPUTS}
    assert all(len(text) == 40 for text in longest.values())
    pinned = {**ExplorerState().snapshot(), **longest, "k_r": 0.0123457, "k_theta": 0.0123457,
              "F_N": 1.23457, "theta0": 123.457, "rtol": 1e-8, "beta_mode": "fixed",
              "beta": 0.123457, "dist_family": "vonmises", "dist_deg": 123.457,
              "dist_kappa": 1234.57, "dist_psi": -123.457, "mix_weight": 0.123457,
              "dist2_family": "vonmises", "dist2_deg": 123.457, "dist2_kappa": 1234.57,
              "dist_hist": _longest_histogram()}
    text = _a_query(ExplorerState(pinned=pinned).to_search())
    assert "hist:" in text and len(text) <= MAX_PINNED_CHARS
    assert parse_pinned(text) == complete(pinned)


def _longest_histogram() -> dict:
    """The histogram with the longest link text: 40 bins, long edges, two-character levels."""
    code = "".join(histogram._ALPHABET[63] + histogram._ALPHABET[63 - i] for i in range(40))
    hist = histogram.from_link(f"-4.56789:8.98765:{code}")
    assert hist is not None and len(hist["weights"]) == histogram.LINK_MAX_BINS
    return hist


def test_a_pinned_histogram_round_trips_and_is_compared_as_a_histogram():
    hist = histogram.from_link("-5:10:" + "__" + "AC" * 35)
    pinned = {**ExplorerState().snapshot(), "dist_family": "histogram", "dist_hist": hist}
    state = ExplorerState(pinned=pinned)
    text = _a_query(state.to_search())
    assert "hist:-5:10:" in text
    back = parse_pinned(text)
    assert back["dist_hist"] == hist and back["dist_family"] == "histogram"
    assert distribution_of(back) == {"family": "histogram", **hist}
    assert distribution_words(distribution_of(back)).startswith("histogram of 36 bins")


@pytest.mark.parametrize("junk", [
    "k_r:0.5,d_D:5 apples", "k_r:0.5,d_D:" + "1" * 41, "k_r:0.5,dist:gaussian",
    "k_r:0.5,kappa:-1", "k_r:0.5,mix:2", "k_r:0.5,psi_deg:270", "k_r:0.5,dist_deg:nan",
    "k_r:0.5,opt:min-FTx", "k_r:0.5,objective:min-FTx",
])
def test_a_garbled_design_part_refuses_the_whole_of_a(junk):
    values, notices = parse({"A": junk, "dist": "pair"})
    assert "pinned" not in values and values["dist_family"] == "pair"
    assert len(notices) == 1 and notices[0].startswith("URL parameter A=")


def test_a_state_pinned_with_the_support_only_has_the_default_design():
    s = ExplorerState(dist_family="pair", pinned={"k_r": 0.5, "k_theta": 0.2, "F_N": 1.0,
                                                  "theta0": 60.0, "rtol": 1e-6,
                                                  "beta_mode": "self", "beta": 1.0})
    s.swap_pin()
    assert s.dist_family == DEFAULTS["dist_family"] and s.pinned["dist_family"] == "pair"


# ------------------------------------------------------------------------------ results

DESIGN_CALLS = ("compute_design_point", "compute_design_array")


def test_a_s_design_is_computed_only_while_pinned_and_on_the_design_tab(pool, monkeypatch):
    def compute_design_array(design, distribution, psi_deg, beta):  # a stand-in: no model
        return {"dist": distribution}
    monkeypatch.setattr(worker, "compute_design_array", compute_design_array)
    state = ExplorerState()
    state.load_query(FAST)
    r = results_module.SessionResults(state)
    r.show(("support", "design_point", "design_array"))
    r.start()
    assert [pool.calls.count(c) for c in DESIGN_CALLS] == [1, 1]  # B's only
    state.pin()
    # Pinned at B: A asks by B's keys (the shared cache serves it at no cost).
    for name in ("design_point", "design_array"):
        assert r.A.slots[name].applied_key == r.slots[name].applied_key, name
    state.dist_family = "pair"
    assert r.design_array["dist"]["family"] == "pair"
    assert r.design_array_A["dist"]["family"] == "vonmises"
    pool.calls.clear()
    r.show(("support", "uniform"))  # another tab: nothing of the design, A's or B's
    state.param.update(dist_family="fixed", pinned={**state.pinned, "dist_kappa": 9.0})
    assert not any(c in pool.calls for c in DESIGN_CALLS)
    r.show(("support", "design_point", "design_array"))
    assert pool.calls.count("compute_design_array") == 2
    assert r.design_array_A["dist"] == {"family": "vonmises", "mean_deg": 90.0, "kappa": 9.0}
    state.clear_pin()
    assert r.design_array_A is r.design_point_A is r.design_polar_A is None
    pool.calls.clear()
    state.dist_family = "pair"
    assert pool.calls.count("compute_design_array") == 1


@pytest.fixture(scope="module")
def page():
    """The Design tab with A = FAST pinned and B edited (``B_EDIT``), computed here."""
    mp = pytest.MonkeyPatch()
    pool = InProcessPool()
    mp.setattr(slot, "work_pool", lambda: pool)
    mp.setattr(results_module, "work_pool", lambda: pool)
    from app.views import Dashboard
    state = ExplorerState()
    assert state.load_query(FAST) == []
    state.pin()
    state.param.update(**B_EDIT)
    yield Dashboard(state)
    mp.undo()


def test_the_design_readouts_give_a_b_and_their_difference(page):
    from app.views.compare_tables import DESIGN_COMPARED, design_values, difference

    r = page.results
    a, b = r.design_array_A, r.design_array
    assert a["design"]["V0"] / b["design"]["V0"] == pytest.approx(100.0 / 80.0)  # A, B
    text = page.design.compare.object
    assert page.design.compare.visible
    av, bv = design_values(a), design_values(b)
    assert av[0] == a["array"]["FTx_over_mu0FN"] and bv[6] == b["FTx_N"]
    for (label, _, _), x, y in zip(DESIGN_COMPARED, av, bv):
        diff, rel = difference(x, y)
        assert f"| {label} |" in text and f"| {diff}<br>{rel} |" in text, label
        if x != 0 and y != x:
            assert float(diff) == pytest.approx(y - x, rel=2e-3, abs=1e-12), label
    assert av[0] != bv[0]  # two designs, two frictions
    assert "von Mises about 90°, κ = 4" in text and "pair ±30°" in text


def test_the_design_overlays_carry_both_data_sets(page):
    r, view = page.results, page.design
    src = {**view._map_sources, **view._polar_sources}
    a, b = r.design_point_A["point"], r.design_point["point"]
    assert list(src["design_point_A"].data["k_r"]) == [a["k_r"]]
    assert list(src["design_point"].data["k_r"]) == [b["k_r"]] != [a["k_r"]]
    # The map's axes hold both points.
    for key, fig_range in (("k_r", view.map_figure.x_range), ("k_theta", view.map_figure.y_range)):
        assert fig_range.start < min(a[key], b[key]) and max(a[key], b[key]) < fig_range.end
    # Fig. 11a: A's curve as many points as B's, A's density (von Mises) and B's atoms (pair).
    curve_A, curve_B = src["design_curve_A"].data, src["polar_FTx"].data
    assert len(curve_A["x"]) == len(curve_B["x"]) > 10
    assert list(curve_A["value"]) != list(curve_B["value"])
    assert len(src["design_density_A"].data["x"]) > 10 and len(src["design_atoms"].data["xs"]) == 2
    assert len(src["design_density"].data["x"]) == 0 and len(src["design_atoms_A"].data["xs"]) == 0
    assert all(x.visible for renderers in view._pinned.values() for x in renderers)
    assert "A (pinned)" in view.point_text.object


def test_the_headline_names_a_and_b_minus_a(page):
    from app.views.readouts import pinned_clause

    r = page.results
    html = page.headline.text
    a_fixed, b_fixed = r.support_A.fixed.FTx_over_mu0FN, r.support.fixed.FTx_over_mu0FN
    assert "A (pinned)" in html and f"B − A = {b_fixed - a_fixed:+.3g}" in html
    assert pinned_clause(0.9, 60.0, None, 0.95, None) == (
        "A (pinned): 10.0 % below at θ₀ = 60°, all orientations: being computed; "
        "B − A = +0.05, – (F_T,x/μ₀F_N)")


def test_the_snippet_card_computes_a_and_b_on_the_design_tab(page):
    page.code.card.collapsed = False
    text = page.code.code.object
    assert "design_A = PillarDesign(" in text and "V0='100 m/s'" in text
    assert "design = PillarDesign(" in text and "V0='80 m/s'" in text
    assert "'family': 'pair'" in text and "B - A: design array" in text


def test_clearing_a_hides_the_design_overlays(page):
    view = page.design
    pinned = page.state.pinned
    page.state.clear_pin()
    try:
        assert not view.compare.visible
        assert len(view._map_sources["design_point_A"].data["k_r"]) == 0
        assert len(view._polar_sources["design_curve_A"].data["x"]) == 0
        assert not any(x.visible for renderers in view._pinned.values() for x in renderers)
        assert "A (pinned)" not in page.headline.text
    finally:
        page.state.pinned = pinned


# ------------------------------------------------------------------------------ exports

def _csv(tmp_path, text: str):
    path = tmp_path / "x.csv"
    path.write_text(text)
    return csvfile.read(path)


def test_the_csv_downloads_carry_a(pool, tmp_path):
    from app.views import Dashboard

    state = ExplorerState(k_r=0.5, theta0=60.0)
    state.pin()
    state.param.update(k_r=3.0, theta0=30.0)
    page = Dashboard(state)
    r = page.results
    header, cols = _csv(tmp_path, page._trajectory_csv().getvalue())
    assert header["k_r"] == 3.0 and header["pinned k_r"] == 0.5
    assert header["pinned theta0_deg"] == pytest.approx(60.0) and header["A"] == 1.44  # law's A
    assert "pinned state A" in header["compare"]
    assert list(cols["F_x_A"]) == list(r.support_A.series.F_x)
    assert list(cols["F_x"]) == list(r.support.series.F_x)
    assert header["pinned t_out"] == r.support_A.result.t_out != header["t_out"]
    header, cols = _csv(tmp_path, page._polar_csv().getvalue())  # computes both sweeps
    assert header["pinned k_r"] == 0.5 and header["k_r"] == 3.0
    assert list(cols["theta0_A"]) == list(cols["theta0"])
    assert list(cols["FTx_over_mu0FN_A"]) == list(r.polar_A.columns["FTx_over_mu0FN"])
    assert list(cols["FTx_over_mu0FN_A"]) != list(cols["FTx_over_mu0FN"])
    state.clear_pin()
    header, cols = _csv(tmp_path, page._trajectory_csv().getvalue())
    assert "compare" not in header and not any(k.endswith("_A") for k in cols)


def test_a_csv_with_a_not_yet_computed_says_so():
    from app.export import sweep_csv
    from model import REGIMES

    text = sweep_csv(worker.compute_polar(REGIMES["stiff"]), None, comparing=True)
    assert "# compare: pinned, but its sweep is not computed yet" in text
    assert "_A" not in text.splitlines()[-1]


def test_the_snippet_with_a_reproduces_both_states():
    from app.snippet import view_as_python
    from test_snippet import as_json, execute, same

    state = ExplorerState(k_r=0.5, k_theta=0.2, theta0=30.0, average="duration")
    state.pin()
    state.param.update(k_r=3.0, k_theta=0.01, F_N=2.0, theta0=135.0)
    code = view_as_python(state)
    records, printed = execute(code, names=("support", "support_A", "uniform", "uniform_A",
                                            "fixed", "fixed_A"))
    for tag, s in (("", state), ("_A", ExplorerState(**state.pinned))):
        shown = worker.compute_support(s.params, s.array_beta, s.rtol)
        expected = dict(shown.result.to_dict(), series_x=list(shown.series.x))
        assert same(records[f"support{tag}"], as_json(expected)), tag
        assert same(records[f"fixed{tag}"], as_json(shown.fixed.to_dict())), tag
        row = worker.compute_uniform(s.k_r, s.k_theta, s.F_N, s.array_beta)
        value = row["FTx_over_mu0FN_duration"]
        assert records[f"uniform{tag}"]["FTx_over_mu0FN_duration"] == pytest.approx(
            value, rel=1e-12)
        who = "A " if tag else "B "
        assert f"{who}uniform array: F_T,x/(mu0 F_N) = {value!r} " in printed
    b, a = records["fixed"]["FTx_over_mu0FN"], records["fixed_A"]["FTx_over_mu0FN"]
    assert f"B - A: fixed array F_T,x/(mu0 F_N) {b - a:+.6g}" in printed


def test_the_design_snippet_with_a_reproduces_both_arrays():
    from app.snippet import view_as_python
    from test_snippet import execute

    state = ExplorerState()
    state.load_query(FAST)
    state.mix_weight = 0.3  # A: a mixture (lists of components in the snippet)
    state.pin()
    state.param.update(**B_EDIT, mix_weight=0.0)
    code = view_as_python(state)
    assert "'family': 'mixture'" in code
    records, printed = execute(code, names=())
    for tag, s in (("B", state), ("A", ExplorerState(**state.pinned))):
        design = worker.design_of(s.design_inputs)
        row = worker.compute_design_array(design, s.distribution, s.dist_psi, s.array_beta)
        value = row["array"]["FTx_over_mu0FN"]
        assert f"{tag} design array: F_T,x/(mu0 F_N) = {float(value)!r}," in printed, tag
        assert math.isfinite(value)
    assert "B - A: design array F_T,x/(mu0 F_N)" in printed
    assert np.isfinite(float(printed.split("B - A: design array F_T,x/(mu0 F_N) ")[1].split()[0]))
