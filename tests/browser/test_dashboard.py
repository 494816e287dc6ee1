"""The served dashboard in headless Chromium: what a person sees and does.

Widgets are found by the CSS classes the app gives them (``ctl-k_r``, ``preset-soft``,
``player``, ...; slider titles as a fallback) and plotted data by the names of the
ColumnDataSources (``orbit``, ``scene_mass``, ``regime_now``). Every test carries the
``browser`` marker (``-m "not browser"`` leaves them out) and a time limit.
"""
from __future__ import annotations

import json
import math
import re
from urllib.parse import parse_qs, urlsplit

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(180)]

# control -> (CSS class, slider title (regex) as a fallback, slider over log10 of the value)
CONTROLS = {
    "k_r": ("ctl-k_r", r"^k_r\b|k_\{r\}", True),
    "k_theta": ("ctl-k_theta", r"k_θ|k_theta|k_\{\\theta\}", True),
    "F_N": ("ctl-F_N", r"F_N|F_\{N\}", True),
    "theta0": ("ctl-theta0", r"θ₀|θ0|theta0|\\theta_0", False),
}
ORBIT = ["orbit"]  # the support's path during the contact
DEFAULTS = {"k_r": 3.0, "k_theta": 0.01, "F_N": 1.0, "theta0": 90.0}
PRESETS = {"soft": (0.03, 0.03), "pendulum": (3.0, 0.01), "slider": (0.01, 3.0),
           "stiff": (3.0, 3.0)}


def _open(page, url: str) -> float:
    seconds = pt.wait_for_app(page, url)
    pt.settle(page)
    return seconds


def _slider(page, control: str) -> pt.SliderInfo:
    css, title, _log = CONTROLS[control]
    info = pt.find_slider(page, css, title)
    assert info is not None, (f"no slider for {control} (class {css} or title like {title!r}); "
                              f"sliders: {[s.title for s in pt.sliders(page)]}")
    return info


def _handle(page, control: str):
    css, title, _log = CONTROLS[control]
    return pt.slider_handle(page, css, title)


def _value(page, control: str) -> float:
    """The control's value in its physical units (log sliders converted back)."""
    info = _slider(page, control)
    return 10 ** info.value if CONTROLS[control][2] else info.value


def _close(a: float, b: float, rel: float) -> bool:
    return math.isclose(a, b, rel_tol=rel, abs_tol=1e-9)


def _key_towards_middle(info: pt.SliderInfo) -> str:
    """ArrowRight unless the slider sits in the upper half of its range."""
    if info.start is None or info.end is None or info.value is None:
        return "ArrowRight"
    return "ArrowLeft" if info.value > (info.start + info.end) / 2 else "ArrowRight"


def _no_errors(page_log) -> None:
    assert page_log.errors == [], "JavaScript errors:\n" + "\n".join(page_log.errors)


# ---------------------------------------------------------------------------- the page

def test_page_loads_without_console_errors(page, page_log, app_url):
    seconds = _open(page, app_url)
    print(f"page rendered in {seconds:.2f} s")
    _no_errors(page_log)
    body = page.locator("body").inner_text()
    assert "Traceback" not in body
    assert page.title(), "the page has no title"


def test_default_page_screenshot(page, page_log, app_url, artifacts_dir):
    _open(page, app_url)
    shot = pt.screenshot(page, artifacts_dir / "dashboard.png", full_page=False)
    full = pt.screenshot(page, artifacts_dir / "dashboard-full.png", full_page=True)
    assert shot.stat().st_size > 10_000 and full.stat().st_size > 10_000
    _no_errors(page_log)


def test_the_four_controls_are_sliders(page, app_url):
    _open(page, app_url)
    for control, default in DEFAULTS.items():
        info = _slider(page, control)
        assert info.extra["visible"] and not info.extra["disabled"], info
        assert _handle(page, control).is_visible(), f"the {control} slider handle is hidden"
        assert _close(_value(page, control), default, 1e-6), (control, _value(page, control))
        css = CONTROLS[control][0]
        shown = page.locator(f".{css} .bk-slider-value").first.inner_text().strip()
        assert shown and not re.search(r"undefined|NaN", shown), \
            f"the {control} slider shows {shown!r} as its value"


# ---------------------------------------------------------------------------- controls

@pytest.mark.parametrize("control", list(CONTROLS))
def test_moving_a_slider_changes_the_plotted_data(page, page_log, app_url, control):
    _open(page, app_url)
    info = _slider(page, control)
    before = pt.data_sources(page, ORBIT)
    assert before, "the page has no 'orbit' ColumnDataSource"
    pt.move_slider(page, _handle(page, control), _key_towards_middle(info), presses=3)
    changed = pt.wait_for_data_change(page, before, ORBIT, timeout_s=30)
    assert _slider(page, control).value != info.value, "the slider did not move"
    assert changed, f"moving {control} did not change the plotted orbit"
    _no_errors(page_log)


def test_a_slider_move_shows_or_hides_nothing(page, page_log, app_url):
    """A move changes data, ranges and texts; no view's visibility goes back and forth
    between server and page (a folded card's pane, sent ``visible`` each move, was shown,
    hidden again by the card and the whole page laid out twice: ~0.4 s per move)."""
    sent, received = [], []
    page.on("websocket", lambda ws: (
        ws.on("framesent", lambda p: sent.append(p) if isinstance(p, str) else None),
        ws.on("framereceived", lambda p: received.append(p) if isinstance(p, str) else None)))
    _open(page, app_url)
    # The support's spinner (a Panel LoadingSpinner: an HTML model of class "loader") is
    # meant to show for a move whose work takes over 0.3 s (a busy machine's): its
    # visibility is not the round trip looked for here.
    spinners = set(page.evaluate("""() => Array.from(Bokeh.documents[0].all_models)
        .filter((m) => (m.css_classes || []).includes("loader")).map((m) => m.id)"""))
    assert spinners, "the page has no spinner"
    before = pt.data_sources(page, ORBIT)
    n_sent, n_received = len(sent), len(received)
    pt.move_slider(page, _handle(page, "theta0"), "ArrowRight", presses=2)
    assert pt.wait_for_data_change(page, before, ORBIT, timeout_s=30), "the orbit did not change"
    pt.settle(page, quiet_ms=500)
    # The frames are read: the move's new data is among what they brought.
    assert any(event.get("kind") == "ColumnDataChanged" for frame in received[n_received:]
               for event in _events(frame)), "no data change read from the page's frames"
    toggled = [event for frame in sent[n_sent:] + received[n_received:]
               for event in _events(frame) if event.get("attr") == "visible"
               and (event.get("model") or {}).get("id") not in spinners]
    assert toggled == [], f"visibility sent back and forth on a move: {toggled}"
    _no_errors(page_log)


def _events(frame: str) -> list[dict]:
    """The document events of a Bokeh protocol frame (its content part), else none."""
    try:
        content = json.loads(frame)
    except ValueError:
        return []
    return content.get("events", []) if isinstance(content, dict) else []


@pytest.mark.parametrize("preset", ["soft", "slider"])
def test_a_preset_button_changes_the_orbit(page, page_log, app_url, preset):
    _open(page, app_url)
    before = pt.data_sources(page, ORBIT)
    page.locator(f".preset-{preset} button").first.click()
    changed = pt.wait_for_data_change(page, before, ORBIT, timeout_s=30)
    assert changed, f"the {preset} preset did not change the orbit"
    k_r, k_theta = PRESETS[preset]
    pt.wait_for(page, lambda: _close(_value(page, "k_r"), k_r, 1e-6)
              and _close(_value(page, "k_theta"), k_theta, 1e-6), timeout_s=10,
              what="the preset's springs")
    _no_errors(page_log)


def test_clicking_the_regime_map_sets_the_springs(page, page_log, app_url):
    _open(page, app_url)
    pt.open_tab(page, r"Regime map")
    page.wait_for_timeout(300)
    before = pt.data_sources(page, ["regime_now"])
    target = (0.1, 0.5)
    pt.click_plot(page, "regime_map", *target)
    pt.wait_for(page, lambda: _close(_value(page, "k_r"), target[0], 0.05)
              and _close(_value(page, "k_theta"), target[1], 0.05), timeout_s=10,
              what=f"k_r, k_theta near {target}")
    assert pt.wait_for_data_change(page, before, ["regime_now"], timeout_s=10), \
        "the current-springs marker on the map did not move"
    _no_errors(page_log)


def test_url_parameters_restore_the_controls(page, page_log, app_url):
    wanted = {"k_r": 0.5, "k_theta": 0.2, "F_N": 2.0, "theta0": 45.0}
    _open(page, f"{app_url}?k_r=0.5&k_theta=0.2&F_N=2&theta0_deg=45")
    for control, value in wanted.items():
        assert _close(_value(page, control), value, 1e-6), (control, _value(page, control))
    assert not page.locator(".page-notice").is_visible(), page.locator(".page-notice").inner_text()
    # The address bar follows the controls, so a reload shows the same view.
    pt.move_slider(page, _handle(page, "theta0"), "ArrowRight", presses=2)
    pt.wait_for(page, lambda: parse_qs(urlsplit(page.url).query).get("theta0_deg") == ["47"],
              what=f"theta0_deg=47 in the URL (now {page.url})")
    page.reload()
    pt.wait_for_app(page, page.url)
    assert _close(_value(page, "theta0"), 47.0, 1e-6)
    assert _close(_value(page, "k_r"), 0.5, 1e-6)
    _no_errors(page_log)


def test_bad_url_values_fall_back_with_a_notice(page, page_log, app_url):
    _open(page, f"{app_url}?k_r=banana&F_N=1e9&theta0_deg=45")
    notice = page.locator(".page-notice")
    assert notice.is_visible(), "no notice about the unusable URL values"
    text = pt.model_value(page, r"\bHTML$|Markdown$|Alert$", "text", "page-notice") or ""
    assert "k_r" in text and "F_N" in text, text
    assert _close(_value(page, "k_r"), DEFAULTS["k_r"], 1e-6)
    assert _close(_value(page, "F_N"), DEFAULTS["F_N"], 1e-6)
    assert _close(_value(page, "theta0"), 45.0, 1e-6)
    assert "Traceback" not in page.locator("body").inner_text()
    _no_errors(page_log)


def _frame(page, name: str = "support_player_frame"):
    return page.evaluate("(n) => { const m = Bokeh.documents[0].get_model_by_name(n); "
                         "return m ? m.value : null; }", name)


def test_the_player_advances_in_the_browser(page, page_log, app_url):
    """The animation runs in the page: frames advance and the mass moves with no message
    to the server per frame."""
    sent = []
    page.on("websocket", lambda ws: ws.on("framesent", lambda payload: sent.append(payload)))
    _open(page, app_url)
    assert _frame(page) == 0, "no browser-side player in the page"
    before = pt.data_sources(page, ["scene_mass"])
    page.get_by_role("button", name="▶ Play").first.click()
    pt.wait_for(page, lambda: (_frame(page) or 0) > 10, timeout_s=10,
              what="the player to advance")
    count = len(sent)
    page.wait_for_timeout(1500)  # ~45 frames at 1x
    assert (_frame(page) or 0) > 30
    assert len(sent) - count <= 2, f"{len(sent) - count} messages to the server while playing"
    assert pt.wait_for_data_change(page, before, ["scene_mass"], timeout_s=10), \
        "the animated mass did not move"
    page.keyboard.press("Space")  # pause
    page.wait_for_timeout(300)
    paused = _frame(page)
    page.wait_for_timeout(500)
    assert _frame(page) == paused, "Space did not pause the animation"
    page.keyboard.press("ArrowRight")
    pt.wait_for(page, lambda: _frame(page) == paused + 1, timeout_s=5, what="one step forward")
    _no_errors(page_log)


_SCENE_AT_FRAME = """() => {
    const d = Bokeh.documents[0], get = (n) => d.get_model_by_name(n);
    const src = (n) => [...d.all_models].find((m) => m.name === n && m.type === "ColumnDataSource");
    const i = get("support_player_frame").value, f = src("support_frames").data;
    const m = src("scene_mass").data, s = src("scene_slab").data;
    const p = src("support_frame_params").data;
    return {frame: i, mass: [m.x[0], m.y[0], m.tau[0]], at: [f.x[i], f.y[i], f.tau[i]],
            right: s.right[0], slab: p.x_start[0] + f.tau[i]};
}"""


def test_a_new_contact_is_drawn_at_the_frame_on_show(page, page_log, app_url):
    """The server sends a new contact's frames, not its scene at a frame: the page draws the
    mass, springs, slab and arrows of the new contact at the paused frame itself."""
    _open(page, app_url)
    forward = page.get_by_role("button", name="Step ▶", exact=True).first
    for _ in range(5):
        forward.click()
    pt.wait_for(page, lambda: _frame(page) == 5, timeout_s=5, what="five steps forward")
    before = page.evaluate(_SCENE_AT_FRAME)
    assert before["mass"] == before["at"]
    orbit = pt.data_sources(page, ["orbit", "support_frames"])
    handle = _handle(page, "theta0")
    handle.press("ArrowRight")
    assert pt.wait_for_data_change(page, orbit, ["orbit", "support_frames"], timeout_s=15), \
        "a move of theta0 brought no new contact"
    pt.settle(page, quiet_ms=300)
    after = page.evaluate(_SCENE_AT_FRAME)
    assert after["frame"] == 5
    assert after["at"] != before["at"], "the frames did not change with theta0"
    assert after["mass"] == after["at"], "the mass is not the new contact's at the frame on show"
    assert after["right"] == pytest.approx(after["slab"]), "the slab is not at the frame's tau"
    _no_errors(page_log)


# ---------------------------------------------------------------------------- latency

def test_slider_latency_in_the_browser(page, app_url):
    """Key press on a slider to the redrawn orbit, over 10 moves (reported, not bounded)."""
    _open(page, app_url)
    handle = _handle(page, "theta0")
    change, paint = [], []
    for i in range(10):
        sample = pt.measure_slider_latency(page, handle, "ArrowRight" if i % 2 == 0 else "ArrowLeft",
                                           names=ORBIT)
        change.append(sample["change_ms"])
        paint.append(sample["paint_ms"])
        if not math.isfinite(sample["paint_ms"]):
            break
        pt.settle(page, quiet_ms=300)
    summary = pt.latency_summary(paint)
    print(f"slider key press -> redrawn orbit: p50 {summary['p50']:.0f} ms, "
          f"p95 {summary['p95']:.0f} ms, max {summary['max']:.0f} ms "
          f"(data in the page: p50 {pt.latency_summary(change)['p50']:.0f} ms; n={summary['n']})")
    assert all(math.isfinite(x) for x in paint), f"some moves never redrew: {paint}"
