"""The offline explorer's state after fast input: keys held down end with every view in
the last state, and a link to a tab not drawn yet draws it in the link's state
(docs/offline.md, "Speed")."""
from __future__ import annotations

import math

import pytest

from app.views.readouts import headline_text
from app.worker import compute_support
from model import Params
from model.contact.friction import mu0

from .offline_tools import POLAR, UNIFORM, explorer_file, offline  # noqa: F401 (fixtures)

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]


def test_rapid_key_presses_end_with_every_view_in_the_final_state(offline):
    """Keys held down: the support is redrawn first and the texts, the polar marker, the
    uniform array and the link follow after the paint; once the presses settle every view
    shows the last state's numbers (none left at an earlier press's). Soft springs at
    F_N = 3: each contact takes long enough for the next presses to arrive meanwhile."""
    offline.open("#k_r=0.03&k_theta=0.03&F_N=3&theta0_deg=90")
    offline.page.wait_for_function(f"{POLAR} >= 1 && {UNIFORM} >= 1", timeout=120_000)
    k_r = offline.page.locator(".noUi-handle").nth(0)
    k_r.focus()
    for _ in range(3):  # new springs: the polar sweep and the uniform array again
        k_r.press("ArrowLeft")
    theta0 = offline.page.locator(".noUi-handle").nth(3)
    theta0.focus()
    for _ in range(12):  # pressed with no wait: each starts before the last is drawn
        theta0.press("ArrowRight")
    state = offline.page.evaluate("explorer.state")
    assert state["theta0_deg"] == 102 and state["k_r"] < 0.03
    p = Params(k_r=state["k_r"], k_theta=0.03, F_N=3, theta0=math.radians(102))
    want = compute_support(p)
    ftx = f"{want.fixed.FTx_over_mu0FN:.3f}"
    offline.page.wait_for_function(
        "!explorer.pending() && explorer.uniform.key.startsWith(explorer.state.k_r + ',')"
        " && explorer.polar.key.startsWith(explorer.state.k_r + ',')", timeout=120_000)
    offline.page.wait_for_timeout(300)
    assert offline.page.evaluate("explorer.pending()") is False
    result = offline.page.evaluate("explorer.result")
    assert result["params"]["theta0"] == pytest.approx(math.radians(102), rel=1e-12)
    assert result["F_mean_x"] == pytest.approx(want.result.F_mean[0], rel=1e-4)
    # The support's figures, the headline, the status line and the player's readout.
    orbit = offline.data("orbit")
    kernel = offline.page.evaluate(
        "Array.from(explorer.simulate(Object.assign({}, explorer.result.params, "
        "{samples: 400})).series.x)")
    assert orbit["x1"] == pytest.approx(kernel[1:], abs=1e-12)
    assert ftx in offline.text("headline-number")
    assert f"{result['t_out']:.4g}" in offline.text("status")
    frames = offline.data("support_frames")
    assert frames["tau"][-1] == pytest.approx(result["t_out"], rel=1e-12)
    assert offline.model("support_player_readout", "html").endswith(f"τ = {frames['tau'][0]:.2f}")
    # The polar diagrams, drawn when their tab is first shown: the final sweep, and the
    # marker this contact's, at theta0 = 102 degrees.
    offline.page.locator(".bk-tab", has_text="Polar").click()
    offline.page.wait_for_function(
        "[...Bokeh.documents[0].all_models].some((m) => m.name === 'polar-status'"
        " && m.text.includes('orientations computed'))")
    sweep = offline.page.evaluate("explorer.polar")
    assert offline.data("polar_FTx")["value"][0] == pytest.approx(sweep["F_mean_x"][0] / mu0(),
                                                                  rel=1e-12)
    now = offline.data("polar_FTx_now")
    assert math.degrees(math.atan2(now["y"][0], now["x"][0])) == pytest.approx(102, abs=1e-9)
    assert now["value"][0] == pytest.approx(result["F_mean_x"] / mu0(), rel=1e-12)
    # The sweep and the uniform array are the final springs' (and so is the headline).
    assert offline.page.evaluate(
        "explorer.polar.key === [explorer.state.k_r, 0.03, 3, 'self'].join(',')")
    uniform = offline.page.evaluate("explorer.uniform")
    assert f"{uniform['FTx_over_mu0FN']:.4g}" in offline.text("uniform-readout")
    assert offline.text("headline") == headline_text(
        result["F_mean_x"] / mu0(), 102, uniform["FTx_over_mu0FN_duration"])
    assert "theta0_deg=102" in offline.page.evaluate("location.hash")
    # The page timed its key presses (the benchmark's in-page figure).
    assert offline.page.evaluate("explorer.keyToSupportMs.length") >= 1
    assert offline.errors == []


def test_a_link_to_a_hidden_tab_draws_it_in_the_links_state(offline):
    """The support tab is the one drawn first; a link to the polar or map tab opens that
    tab, drawn for the link's state."""
    offline.open("#k_r=0.1&k_theta=0.3&F_N=3&theta0_deg=60&tab=map")
    assert offline.model("tabs", "active") == 2
    offline.page.wait_for_function("document.documentElement.getAttribute('data-map') === '3/5a'")
    assert offline.data("regime_now") == {"k_r": [0.1], "k_theta": [0.3]}
    shown = [f.bounding_box() for f in offline.page.locator(".bk-Figure").all()
             if f.is_visible()]
    assert len(shown) == 1 and shown[0]["width"] >= 300  # the map alone, laid out
    offline.page.locator(".bk-tab", has_text="Polar").click()
    offline.page.wait_for_function(f"{POLAR} >= 1")
    assert offline.page.evaluate("explorer.polar.key") == "0.1,0.3,3,self"
    assert "72 orientations computed" in offline.text("polar-status")
    shown = [f.bounding_box() for f in offline.page.locator(".bk-Figure").all()
             if f.is_visible()]
    assert len(shown) == 3 and min(b["width"] for b in shown) >= 250  # Fig. 11's three
    assert len(offline.data("polar_FTx")["value"]) == 2 * 72 + 1
    assert "tab=polar" in offline.page.evaluate("location.hash")
    assert offline.errors == []


def test_the_polar_and_map_tabs_are_added_when_first_shown_in_the_current_look(offline):
    """The page opens with the support tab's models alone; the polar and map tabs' models
    are added when their tab is first shown, drawn in the current state and look
    (projector mode on before they existed)."""
    offline.open("#k_r=0.1&k_theta=0.3&F_N=3&theta0_deg=60&projector=1")
    offline.page.wait_for_function(f"{POLAR} >= 1")
    names = ("[...Bokeh.documents[0].all_models].filter((m) => ['polar_FTx', 'regime_map',"
             " 'polar-status', 'map-note'].includes(m.name)).length")
    assert offline.page.evaluate(names) == 0
    offline.page.locator(".bk-tab", has_text="Polar").click()
    offline.page.wait_for_function("[...Bokeh.documents[0].all_models].some((m) => m.name === "
                                   "'polar-status' && m.text.includes('orientations computed'))")
    assert len(offline.data("polar_FTx")["value"]) == 2 * 72 + 1
    now = offline.data("polar_FTx_now")
    assert math.degrees(math.atan2(now["y"][0], now["x"][0])) == pytest.approx(60, abs=1e-9)
    from app.figures.common import MIN_TEXT_PX, PROJECTOR_SCALE
    size = ("[...Bokeh.documents[0].all_models].find((m) => m.name === '{}'"
            " && m.renderers !== undefined).title.text_font_size")
    projected = f"{round((MIN_TEXT_PX + 1) * PROJECTOR_SCALE)}px"
    assert offline.page.evaluate(size.format("polar_FTx")) == projected
    offline.page.locator(".bk-tab", has_text="Regime map").click()
    offline.page.wait_for_function("document.documentElement.getAttribute('data-map') === '3/5a'")
    assert offline.data("regime_now") == {"k_r": [0.1], "k_theta": [0.3]}
    assert offline.page.evaluate(size.format("regime_map")) == projected
    shown = [f for f in offline.page.locator(".bk-Figure").all() if f.is_visible()]
    assert len(shown) == 1 and shown[0].bounding_box()["width"] >= 300
    assert offline.page.evaluate(names) == 6  # polar_FTx and regime_map: a figure, a source
    assert offline.errors == []
