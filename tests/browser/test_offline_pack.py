"""The offline explorer (``micropillar pack``) opened from file:// in headless Chromium with
every request that is not file: refused: it draws, computes in the page and keeps its
state in the URL fragment (docs/offline.md)."""
from __future__ import annotations

import math

import pytest

from app.offline.pack import write
from app.worker import UNIFORM_TOL, compute_support, compute_uniform
from model import Params
from model.contact.friction import mu0

from .offline_tools import (DEFAULTS, DRAWN, POLAR, UNIFORM, Offline,  # noqa: F401 (fixtures)
                            explorer_file, offline)
from .serving import VIEWPORT


def test_opens_from_file_with_no_request_and_no_error(offline):
    offline.open()
    orbit = offline.data("orbit")
    assert len(orbit["x0"]) > 100  # the orbit was computed in the page
    assert offline.page.evaluate("JSON.stringify(explorer.state)") == (
        '{"tab":"support","projector":false,"play":false,"beta_mode":"self","k_r":3,'
        '"k_theta":0.01,"F_N":1,"theta0_deg":90,"beta":1}')
    # The support is its fixed array's contact at the self-consistent beta, as the
    # dashboard's (app.worker.compute_support).
    want = compute_support(Params(k_r=3, k_theta=0.01))
    got = offline.page.evaluate("explorer.result")
    assert got["params"]["beta"] == pytest.approx(want.fixed.beta, rel=1e-6)
    assert got["F_mean_x"] == pytest.approx(want.result.F_mean[0], rel=1e-4)
    assert f"{want.fixed.FTx_over_mu0FN:.3f}" in offline.text("headline-number")
    assert f"β = {want.fixed.beta:.3f} (self-consistent)" in offline.text("headline-number")
    # The uniform array with its self-consistent beta, computed in the page: the
    # dashboard's readout and headline sentence, its numbers within the quadrature
    # tolerance of Python's (app.worker.compute_uniform).
    offline.page.wait_for_function(f"{UNIFORM} >= 1")
    uniform = offline.page.evaluate("explorer.uniform")
    row = compute_uniform(3.0, 0.01, 1.0)
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Nc_over_Nc0"):
        assert uniform[key] == pytest.approx(row[key], abs=UNIFORM_TOL), key
    assert uniform["beta"] == pytest.approx(row["beta"], rel=UNIFORM_TOL)
    readouts = pytest.importorskip("app.views.readouts")
    assert offline.text("headline") == readouts.headline_text(
        got["F_mean_x"] / mu0(), 90, uniform["FTx_over_mu0FN_duration"])
    assert "with supports of all orientations the slab feels" in offline.text("headline")
    assert f"{uniform['FTx_over_mu0FN']:.4g}" in offline.text("uniform-readout")
    assert offline.foreign_requests() == []
    assert offline.errors == []


def test_a_slider_key_press_changes_the_plotted_data(offline):
    offline.open()
    before = offline.data("orbit")
    drawn = offline.page.evaluate(DRAWN)
    handle = offline.page.locator(".noUi-handle").nth(3)  # theta0, the fourth slider
    handle.focus()
    for _ in range(5):
        handle.press("ArrowLeft")
    offline.page.wait_for_function(f"{DRAWN} > {drawn} && explorer.state.theta0_deg === 85"
                                   " && !explorer.pending()")
    after = offline.data("orbit")
    assert after["x1"] != before["x1"]
    assert "theta0_deg=85" in offline.page.evaluate("location.hash")
    # What is drawn is the kernel's orbit for the new state.
    want = offline.page.evaluate(
        "Array.from(explorer.simulate({k_r: 3, k_theta: 0.01, F_N: 1, theta0: 85 * Math.PI / 180,"
        " beta: explorer.result.params.beta, samples: 400}).series.x)")
    assert after["x1"] == pytest.approx(want[1:], abs=1e-12)
    assert offline.errors == []


#: At a key press's first animation frame (registered as the key goes down, so it runs
#: before the figures' paint in that frame): the state's theta0 and the support's data then.
AT_THE_KEYS_FRAME = """() => { window.atKeysFrame = null;
  window.addEventListener("keydown", () => requestAnimationFrame(() => {
    const source = (name) => [...Bokeh.documents[0].all_models].find((m) => m.name === name
        && m.data !== undefined && m.selected !== undefined);
    window.atKeysFrame = {theta0: explorer.result.params.theta0,
      x1: Array.from(source("orbit").data.x1), F_x: Array.from(source("forces").data.F_x)};
  }), {capture: true, once: true}); }"""


def test_a_theta0_key_press_is_drawn_in_the_keys_own_frame(offline):
    """A theta0 step at the same springs and load (a few contacts from the last beta) is
    computed on the page's thread as the key goes down: the frame that shows the slider's
    new place paints the support's figures with the new contact's data (the scene's path,
    Fig. 7's forces), with no frame of the old data between (docs/offline.md)."""
    offline.open()
    offline.page.wait_for_function(f"{POLAR} >= 1 && {UNIFORM} >= 1", timeout=120_000)
    offline.page.wait_for_timeout(200)  # the kernel compiled on the page (jobs.js warmHere)
    handle = offline.page.locator(".noUi-handle").nth(3)
    handle.focus()
    for step, key in enumerate(("ArrowRight", "ArrowRight", "ArrowLeft"), start=1):
        offline.page.evaluate(AT_THE_KEYS_FRAME)
        handle.press(key)
        offline.page.wait_for_function("window.atKeysFrame !== null && !explorer.pending()")
        seen = offline.page.evaluate("window.atKeysFrame")
        deg = 90 + (1 if step != 2 else 2)
        assert seen["theta0"] == pytest.approx(math.radians(deg), rel=1e-12)
        want = offline.page.evaluate(
            f"(() => {{ const r = explorer.simulate({{k_r: 3, k_theta: 0.01, F_N: 1, theta0: "
            f"{deg} * Math.PI / 180, beta: explorer.result.params.beta, samples: 400}}); return "
            "{x: Array.from(r.series.x), F_x: Array.from(r.series.F_x)}; })()")
        assert seen["x1"] == pytest.approx(want["x"][1:], abs=1e-12)
        assert seen["F_x"] == pytest.approx(want["F_x"], abs=1e-12)
    assert offline.page.evaluate("explorer.keyToSupportMs.length") == 3
    assert offline.errors == []


def test_a_link_opens_in_its_state(offline):
    offline.open("#k_r=0.03&k_theta=0.03&F_N=3&theta0_deg=120")
    state = offline.page.evaluate("explorer.state")
    assert state == {"tab": "support", "k_r": 0.03, "k_theta": 0.03, "F_N": 3, "theta0_deg": 120,
                     "projector": False, "play": False, "beta_mode": "self", "beta": 1}
    sliders = offline.page.evaluate(
        "['k_r', 'k_theta', 'F_N', 'theta0_deg'].map(k => "
        "Bokeh.documents[0].get_model_by_name('slider-' + k).value)")
    assert sliders == pytest.approx([math.log10(0.03), math.log10(0.03), math.log10(3), 120])
    want = compute_support(Params(k_r=0.03, k_theta=0.03, F_N=3, theta0=math.radians(120)))
    assert offline.page.evaluate("explorer.result.F_mean_x") == pytest.approx(
        want.result.F_mean[0], rel=1e-3)
    assert offline.text("notice") == ""
    # A new fragment in the same page moves it too.
    drawn = offline.page.evaluate(DRAWN)
    offline.page.evaluate("location.hash = '#regime=slider&F_N=1&theta0_deg=90'")
    offline.page.wait_for_function(f"{DRAWN} > {drawn}")
    assert offline.page.evaluate("[explorer.state.k_r, explorer.state.k_theta]") == [0.01, 3]
    assert offline.errors == []


def test_a_bad_link_gets_a_notice_and_the_defaults(offline):
    offline.open("#k_r=banana&F_N=1e9&theta0_deg=45&tab=array&colour=red")
    state = offline.page.evaluate("explorer.state")
    assert state["k_r"] == DEFAULTS["k_r"] and state["F_N"] == DEFAULTS["F_N"]
    assert state["theta0_deg"] == 45  # the good value is kept
    notice = offline.text("notice")
    for part in ("k_r=banana", "F_N=1e9", "the array tab is not in the offline explorer",
                 "colour is not a setting"):
        assert part in notice, (part, notice)
    assert len(offline.data("orbit")["x0"]) > 100  # never a blank page
    assert offline.errors == []


def test_friction_histories_and_energy_bars_are_the_kernels(offline):
    offline.open("#k_r=0.03&k_theta=0.03&F_N=1&theta0_deg=90")
    series = offline.page.evaluate(
        "(() => { const s = explorer.simulate({k_r: 0.03, k_theta: 0.03, F_N: 1,"
        " theta0: Math.PI / 2, beta: explorer.result.params.beta, samples: 400}).series;"
        " return Object.fromEntries(['tau', 'F_x', 'F_y', 'W', 'D_x'].map((k) => [k, Array.from(s[k])])); })()")
    forces = offline.data("forces")  # Fig. 7
    assert forces["F_x"] == pytest.approx(series["F_x"], abs=1e-12)
    assert forces["F_y"] == pytest.approx(series["F_y"], abs=1e-12)
    # mu0's label stands at the right end of the new contact's time axis.
    label_x, end = offline.page.evaluate(
        "(() => { const all = [...Bokeh.documents[0].all_models];"
        " const fig = all.find((m) => m.name === 'forces' && 'x_range' in m);"
        " return [all.find((m) => m.name === 'forces_mu0_label').x, fig.x_range.end]; })()")
    assert label_x == pytest.approx(end)
    assert end == pytest.approx(1.02 * series["tau"][-1], rel=1e-3)
    # The energy bars follow the player: step to the last frame, the bars are W and its
    # split at tau_out (Eq. 12: W = D_x + D_y + U_el + K).
    offline.page.locator("button", has_text="Step ▶").click()
    offline.page.keyboard.press("Home")
    for _ in range(3):
        offline.page.keyboard.press("ArrowLeft")  # from frame 0 back: stays at the start
    offline.page.evaluate("[...Bokeh.documents[0].all_models].find((m) => m.name ==="
                          " 'support_player_slider').value = 299")
    offline.page.wait_for_function("[...Bokeh.documents[0].all_models].find((m) => m.name ==="
                                   " 'support_player_frame').value === 299")
    bars = offline.data("energy_live_bars")
    result = offline.page.evaluate("explorer.result")
    assert bars["top"][0] == pytest.approx(result["W"], rel=1e-9)  # W so far, at tau_out
    assert bars["top"][-1] == pytest.approx(result["W"] - result["energy_residual"], rel=1e-6)
    assert "τ = " in offline.model("energy_live_readout", "html")
    assert offline.errors == []


def test_the_player_plays_steps_and_answers_keys(offline):
    offline.open()
    frame = ("[...Bokeh.documents[0].all_models].find((m) => m.name === 'support_player_frame')"
             ".value")
    mass = offline.data("scene_mass")["x"]
    offline.page.locator("button", has_text="Step ▶").click()
    offline.page.wait_for_function(f"{frame} === 1")
    assert offline.data("scene_mass")["x"] != mass  # the support moved along its orbit
    offline.page.locator("body").click(position={"x": 5, "y": 5})
    offline.page.keyboard.press("ArrowRight")
    offline.page.wait_for_function(f"{frame} === 2")
    offline.page.keyboard.press(" ")  # play
    offline.page.wait_for_function(f"{frame} > 10")
    offline.page.keyboard.press(" ")  # pause
    stopped = offline.page.evaluate(frame)
    offline.page.wait_for_timeout(300)
    assert offline.page.evaluate(frame) == stopped
    assert offline.errors == []


@pytest.mark.parametrize("motion", ["reduce", "no-preference"])
def test_play_in_a_link_respects_reduced_motion(browser, explorer_file, motion):
    context = browser.new_context(viewport=VIEWPORT, reduced_motion=motion)
    try:
        page = context.new_page()
        page.goto(explorer_file.as_uri() + "#play=1")
        page.wait_for_function(f"{DRAWN} >= 1")
        playing = page.evaluate("[...Bokeh.documents[0].all_models].find((m) => m.name ==="
                                " 'support_player_play').active")
        assert playing is (motion == "no-preference")
    finally:
        context.close()


def test_polar_diagrams_are_computed_in_the_page(offline):
    offline.open("#k_r=0.03&k_theta=0.3&F_N=1&theta0_deg=90&tab=polar")
    offline.page.wait_for_function(f"{POLAR} >= 1")
    assert offline.model("tabs", "active") == 1
    curve = offline.data("polar_FTx")
    assert len(curve["value"]) == 2 * 72 + 1
    # Orientations of the sweep against Python's fixed arrays there, each at its
    # self-consistent beta (the dashboard's default).
    from model.arrays.fixed import orientation_sweep
    from app.worker import POLAR_THETA0
    p = Params(k_r=0.03, k_theta=0.3, F_N=1)
    sweep = orientation_sweep(p, POLAR_THETA0[[0, 40]], beta="self")
    betas = offline.page.evaluate("[explorer.polar.beta[0], explorer.polar.beta[40]]")
    assert betas == pytest.approx(list(sweep.beta), rel=1e-5)
    assert curve["value"][0] == pytest.approx(sweep.FTx_over_mu0FN[0], rel=1e-4)
    assert curve["value"][40] == pytest.approx(sweep.FTx_over_mu0FN[1], rel=1e-4)
    assert offline.data("polar_DyDx")["value"][40] == pytest.approx(sweep.Dy_over_Dx[1], rel=1e-3)
    assert "72 orientations computed" in offline.text("polar-status")
    # A click on a diagram sets theta0 to its angle.
    offline.page.evaluate("explorer._polarTap(0, -1)")
    assert offline.page.evaluate("explorer.state.theta0_deg") == 270
    assert offline.errors == []


def test_the_regime_map_is_the_shipped_one_and_sets_the_springs(offline):
    offline.open("#F_N=3&tab=map")
    from model.runs.shipped_map import load_regime_map
    m = load_regime_map(F_N=3)
    cells = offline.data("regime_map")
    assert cells["value"][:24] == pytest.approx(list(m.FTx_over_mu0FN[0]), rel=1e-5)
    assert "F_N = 3" in offline.page.evaluate(
        "[...Bokeh.documents[0].all_models].find((m) => m.name === 'regime_map'"
        " && m.renderers !== undefined).title.text")
    # A click on the map sets both springs; the marker follows.
    drawn = offline.page.evaluate(DRAWN)
    offline.page.evaluate("explorer._mapTap(0.1, 1.0)")
    offline.page.wait_for_function(f"{DRAWN} > {drawn}")
    assert offline.page.evaluate("[explorer.state.k_r, explorer.state.k_theta]") == [0.1, 1]
    assert offline.data("regime_now") == {"k_r": [0.1], "k_theta": [1]}
    # The keyboard does the same, one cell of the 24 x 24 grid per key.
    offline.page.locator("body").click(position={"x": 5, "y": 5})
    offline.page.keyboard.press("ArrowRight")
    offline.page.keyboard.press("ArrowDown")
    step = (3 / 0.01) ** (1 / 23)
    k_r, k_theta = offline.page.evaluate("[explorer.state.k_r, explorer.state.k_theta]")
    assert k_r == pytest.approx(0.1 * step, rel=1e-2) and k_theta == pytest.approx(1 / step, rel=1e-2)
    assert "k_r=" in offline.page.evaluate("location.hash")
    assert offline.errors == []


def test_projector_mode_from_the_link_and_the_toggle(offline):
    offline.open("#projector=1")
    size = ("[...Bokeh.documents[0].all_models].find((m) => m.name === 'forces'"
            " && m.renderers !== undefined).title.text_font_size")
    from app.figures.common import MIN_TEXT_PX, PROJECTOR_SCALE
    # app.figures.common.style(fig, True): the title's projector size
    assert offline.page.evaluate(size) == f"{round((MIN_TEXT_PX + 1) * PROJECTOR_SCALE)}px"
    assert offline.model("projector", "active") is True
    offline.page.locator("button", has_text="Projector mode").click()
    offline.page.wait_for_function(f"{size} === '{MIN_TEXT_PX + 1}px'")
    assert "projector" not in offline.page.evaluate("location.hash")
    assert offline.errors == []


def test_a_phone_gets_the_page_without_horizontal_scroll(browser, explorer_file):
    context = browser.new_context(viewport={"width": 390, "height": 844}, is_mobile=True,
                                  has_touch=True, device_scale_factor=3)
    try:
        page = context.new_page()
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(explorer_file.as_uri())
        page.wait_for_function(f"{DRAWN} >= 1")
        assert page.evaluate("document.documentElement.scrollWidth") <= 390
        # The figures are stacked, each within the screen.
        shown = [f.bounding_box() for f in page.locator(".bk-Figure").all() if f.is_visible()]
        assert len(shown) >= 4, shown  # the support tab's figures (in Bokeh's shadow roots)
        assert max(b["x"] + b["width"] for b in shown) <= 390 + 0.5, shown
        assert errors == []
    finally:
        context.close()


def test_a_packed_state_opens_without_a_fragment(browser, tmp_path):
    """The dashboard's download: the file packed with a state opens in it (fixed beta)."""
    path = tmp_path / "explorer.html"
    write(path, "#k_r=0.5&k_theta=0.2&F_N=3&theta0_deg=120&beta=0.4&tab=polar&projector=1")
    offline = Offline(browser, path)
    try:
        offline.open()
        state = offline.page.evaluate("explorer.state")
        assert state == {"tab": "polar", "k_r": 0.5, "k_theta": 0.2, "F_N": 3, "theta0_deg": 120,
                         "projector": True, "play": False, "beta_mode": "fixed", "beta": 0.4}
        assert offline.model("beta-mode", "value") == "fixed"
        assert offline.page.evaluate("explorer.result.params.beta") == 0.4
        offline.page.wait_for_function(f"{POLAR} >= 1 && {UNIFORM} >= 1")
        assert set(offline.page.evaluate("explorer.polar.beta")) == {0.4}
        assert offline.page.evaluate("explorer.uniform.beta") == 0.4
        assert "β = 0.400 (fixed)" in offline.text("uniform-readout")
        assert offline.text("notice") == "" and offline.errors == []
    finally:
        offline.context.close()
