"""The page as a teacher projects it, a student holds it and a researcher reads it.

Sizes are measured in the page (bounding boxes of the Bokeh figures, of buttons and slider
handles); the history is driven with the browser's own Back/Forward. Screenshots of every
tab on a 390x844 phone are saved to ``$MICROPILLAR_SCREENSHOTS`` (default: a temporary
folder) for a person to look at; those at 1280x720 and 1920x1080, normal and projected,
are taken by ``test_projector`` as its pages go from tab to tab.
"""
from __future__ import annotations

import math
import re
from urllib.parse import parse_qs, urlsplit

import pytest

from . import page_tools as pt
from . import still

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]

LAPTOP = {"width": 1280, "height": 720}
FULL_HD = {"width": 1920, "height": 1080}
PHONE = {"width": 390, "height": 844}
#: tab key -> (tab-bar label, the figures the tab shows)
TABS = {"support": ("One support", ("scene", "forces", "friction_law", "energy_live")),
        "polar": ("Orientation", ("polar_FTx", "polar_DyDx", "polar_FTy")),
        "map": ("Regime map", ("regime_map",)),
        "load": ("Load", ("load",))}

PROJECTED_ABOVE_FOLD = {"support": ("scene", "forces")}

# Bounding boxes (CSS px) of the visible Bokeh figures called ``names``.
_FIGURE_BOXES_JS = """(names) => {
  const out = {};
  for (const m of Bokeh.documents[0].all_models) {
    if (!names.includes(m.name) || /DataSource$/.test(m.type) || !("x_range" in m)) continue;
    const view = Bokeh.index.find_one(m);
    if (!view) continue;
    const r = view.el.getBoundingClientRect();
    if (r.width > 0 && r.height > 0) out[m.name] = [r.left, r.top, r.width, r.height];
  }
  return out;
}"""

# Bounding boxes of the elements matching ``selector`` anywhere in the page, shadow roots
# included (Bokeh and Panel draw widgets inside shadow DOM).
_BOXES_JS = """(selector) => {
  const out = [];
  const walk = (root) => {
    for (const el of root.querySelectorAll(selector)) {
      const r = el.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) out.push([r.left, r.top, r.width, r.height]);
    }
    for (const el of root.querySelectorAll("*")) if (el.shadowRoot) walk(el.shadowRoot);
  };
  walk(document);
  return out;
}"""


#: The browser-side player's buttons, by their tooltips (app/figures/player.py).
PLAYER_TIPS = ("Play or pause (Space)", "One frame back (←)", "One frame forward (→)",
               "Back to the first frame (Home)", "Start again at the end (L)")


def _open(page, url: str) -> None:
    pt.wait_for_app(page, url)
    pt.settle(page)


def _new_page(browser, viewport):
    context = browser.new_context(viewport=viewport)
    context.set_default_timeout(30_000)
    return context, context.new_page()


def _figures(page, names) -> dict:
    return page.evaluate(_FIGURE_BOXES_JS, list(names))


def _layout_at_rest(page, names, quiet_ms: int = 300, timeout_ms: int = 15_000) -> None:
    """Wait until the figures ``names`` and the controls have not moved for ``quiet_ms``:
    the page has laid itself out again after the controls opened or folded, or the window
    changed size."""
    read = ("() => JSON.stringify([(" + _FIGURE_BOXES_JS + f")({list(names)!r}), ("
            + _BOXES_JS + ')(".sidebar")])')
    still.wait_until_still(page, read, quiet_ms, timeout_ms)


def _visible_area(box, viewport) -> float:
    left, top, width, height = box
    w = max(0.0, min(left + width, viewport["width"]) - max(left, 0.0))
    h = max(0.0, min(top + height, viewport["height"]) - max(top, 0.0))
    return w * h


def _query(page) -> dict:
    return {k: v[-1] for k, v in parse_qs(urlsplit(page.url).query).items()}


def _slider(page, css: str) -> pt.SliderInfo:
    info = pt.find_slider(page, css)
    assert info is not None, f"no slider .{css}"
    return info


def _controls_width(page) -> float:
    boxes = page.evaluate(_BOXES_JS, ".sidebar")
    return boxes[0][2] if boxes else 0.0


# ---------------------------------------------------------------------------- projector

@pytest.fixture(scope="class")
def projected_1920(browser, app_url):
    """One projector-mode page at 1920x1080 for the tabs' tests, which go from tab to tab
    with its tab bar as a class does (``opened``: False until the page shows the app).
    Closed once they ran: a page left open on a tab that computes (the Load tab's curves)
    would keep the server's workers busy for the tests after them."""
    context, page = _new_page(browser, FULL_HD)
    shared = {"page": page, "opened": False}
    yield shared
    context.close()


class TestProjectorAt1920:
    """The tabs projected at 1920x1080, one page going from tab to tab."""

    @pytest.mark.parametrize("tab", list(TABS))
    def test_projector_mode_at_1920_fills_the_screen_with_figures(self, projected_1920, app_url,
                                                                    tab):
        """The figures cover most of the area beside the controls (they used to fill half the
        screen at 1920x1080) and, with the controls folded away, most of the screen; they lie
        inside it and grow with the window."""
        label, names = TABS[tab]
        # Projected, the support's Fig. 3 and energy split go below the fold (the top view and
        # Fig. 7 take the screen).
        names = PROJECTED_ABOVE_FOLD.get(tab, names)
        page = projected_1920["page"]
        screen = FULL_HD["width"] * FULL_HD["height"]

        def covered():
            for name in names:
                pt.wait_for_plot(page, name)
            boxes = _figures(page, names)
            assert set(boxes) == set(names), f"figures shown: {sorted(boxes)}"
            for name, (left, top, width, height) in boxes.items():
                assert left >= 0 and left + width <= FULL_HD["width"] + 1, (name, boxes[name])
                assert top + height <= FULL_HD["height"] + 1, f"{name} runs off the screen"
            return boxes, sum(_visible_area(b, FULL_HD) for b in boxes.values())

        opened, projected_1920["opened"] = projected_1920["opened"], False  # until it passes
        if opened:  # the last tab's test left it folded, at 1280x720
            page.set_viewport_size(FULL_HD)
            pt.open_tab(page, label, tab)
            for name in names:
                pt.wait_for_plot(page, name)
            _layout_at_rest(page, names)
        else:
            _open(page, f"{app_url}?tab={tab}&projector=1")
        # Projected, the controls start folded away.
        assert _controls_width(page) < 200, "the controls are open in projector mode"
        boxes, folded = covered()
        page.locator(".sidebar").get_by_text("Controls", exact=True).first.click()
        pt.wait_for(page, lambda: _controls_width(page) > 200, what="the controls to open")
        _layout_at_rest(page, names)
        _, area = covered()
        # The room left to figures: beside the controls and the "why" column (which stays
        # beside the plots on a screen this wide).
        side = page.evaluate(_BOXES_JS, ".side-column")
        beside = (FULL_HD["width"] - _controls_width(page) - (side[0][2] if side else 0)) \
            * FULL_HD["height"]
        print(f"{tab}: figures cover {area / beside:.0%} of the area beside the controls; "
              f"controls folded: {folded / screen:.0%} of the screen")
        assert area / beside > 0.70, (tab, area / beside, boxes)
        assert folded / (screen - (side[0][2] if side else 0) * FULL_HD["height"]) > 0.70, \
            (tab, folded / screen)
        page.locator(".sidebar").get_by_text("Controls", exact=True).first.click()
        pt.wait_for(page, lambda: _controls_width(page) < 200, what="the controls to fold")
        page.set_viewport_size({"width": 1280, "height": 720})
        _layout_at_rest(page, names)
        small = _figures(page, names)
        for name in names:
            assert boxes[name][2] * boxes[name][3] > 1.5 * small[name][2] * small[name][3], \
                f"{name} does not grow with the window: {small[name]} -> {boxes[name]}"
        projected_1920["opened"] = True


def test_projector_mode_has_large_controls_and_labels(browser, app_url):
    context, page = _new_page(browser, FULL_HD)
    try:
        _open(page, f"{app_url}?projector=1")
        page.locator(".sidebar").get_by_text("Controls", exact=True).first.click()  # folded
        pt.wait_for(page, lambda: page.locator(".ctl-k_r .noUi-handle").is_visible(),
                    what="the controls to open")
        buttons = page.evaluate(_BOXES_JS, ", ".join(f'[title="{t}"]' for t in PLAYER_TIPS))
        assert len(buttons) >= 5, buttons
        assert min(b[3] for b in buttons) >= 44 and min(b[2] for b in buttons) >= 44, buttons
        handles = page.evaluate(_BOXES_JS, ".noUi-handle")
        assert handles and min(min(b[2], b[3]) for b in handles) >= 28, handles
        sizes = page.evaluate("""() => {
          const out = {};
          for (const m of Bokeh.documents[0].all_models) {
            if (m.type === "ColorBar") out.colorbar = m.major_label_text_font_size;
            if (m.type === "Label" && m.name === "scene_time") out.time = m.text_font_size;
          }
          return out;
        }""")
        assert int(sizes["colorbar"].rstrip("px")) >= 16, sizes
        # The time label stays inside the scene's frame (it used to be cut off).
        label = page.evaluate("""() => {
          const fig = [...Bokeh.documents[0].all_models].find((m) => m.name === "scene");
          const label = fig.center.find((m) => m.name === "scene_time");
          const ctx = document.createElement("canvas").getContext("2d");
          ctx.font = `${label.text_font_size} ${label.text_font}`;
          const view = Bokeh.index.find_one(fig);
          return {width: ctx.measureText(label.text).width, frame: view.frame.bbox.width,
                  size: label.text_font_size};
        }""")
        assert label["width"] + 12 <= label["frame"], label
    finally:
        context.close()


# ---------------------------------------------------------------------------- state

def test_reset_keeps_projector_mode_and_the_tab(page, app_url):
    _open(page, f"{app_url}?tab=polar&projector=1&k_r=0.5")
    page.locator(".sidebar").get_by_text("Controls", exact=True).first.click()  # folded
    pt.click_button(page, r"^Reset$")
    pt.wait_for(page, lambda: math.isclose(10 ** _slider(page, "ctl-k_r").value, 3.0, rel_tol=1e-6),
              what="k_r back to its default")
    assert pt.model_value(page, "Toggle$", "active", "ctl-projector") is True
    pt.wait_for(page, lambda: _query(page).get("k_r") == "3", what=f"k_r=3 in {page.url}")
    assert _query(page).get("projector") == "1" and _query(page).get("tab") == "polar"


def test_back_and_forward_restore_the_state(page, app_url):
    _open(page, f"{app_url}?theta0_deg=60")
    start = page.evaluate("() => history.length")
    pt.move_slider(page, pt.slider_handle(page, "ctl-theta0"), "ArrowRight", presses=2)
    pt.wait_for(page, lambda: _query(page).get("theta0_deg") == "62", what="theta0_deg=62")
    page.locator(".preset-soft button").first.click()
    pt.wait_for(page, lambda: _query(page).get("k_r") == "0.03", what="the soft preset's URL")
    assert page.evaluate("() => history.length") == start + 2
    page.go_back()
    pt.wait_for(page, lambda: math.isclose(10 ** _slider(page, "ctl-k_r").value, 3.0,
                                         rel_tol=1e-6), what="k_r back to 3 after Back")
    assert _slider(page, "ctl-theta0").value == 62
    page.go_back()
    pt.wait_for(page, lambda: _slider(page, "ctl-theta0").value == 60, what="theta0 back to 60")
    page.go_forward()
    pt.wait_for(page, lambda: _slider(page, "ctl-theta0").value == 62, what="theta0 62 again")
    page.wait_for_timeout(URL_SETTLE_MS)
    # Restoring writes no new entry, so Forward still leads to the soft preset.
    assert page.evaluate("() => history.length") == start + 2
    page.go_forward()
    pt.wait_for(page, lambda: math.isclose(10 ** _slider(page, "ctl-k_r").value, 0.03,
                                         rel_tol=1e-6), what="k_r 0.03 after Forward")


URL_SETTLE_MS = 1000  # longer than the page's URL debounce


def test_a_run_of_key_presses_makes_one_history_entry(page, app_url):
    """The server writes the address with each answer; the page makes a history entry
    once the address and the keys have settled: Back after a run goes to its start."""
    _open(page, f"{app_url}?theta0_deg=60")
    start = page.evaluate("() => history.length")
    handle = pt.slider_handle(page, "ctl-theta0")
    for _ in range(8):  # a run of presses, answered as the server manages
        handle.press("ArrowRight")
        page.wait_for_timeout(100)
    pt.wait_for(page, lambda: _query(page).get("theta0_deg") == "68", what="theta0_deg=68")
    page.wait_for_timeout(URL_SETTLE_MS)
    entries = page.evaluate("() => history.length") - start
    # Two when a busy server answered a step at once, then took over 400 ms for the last.
    assert 1 <= entries <= 2, entries
    for _ in range(entries):
        page.go_back()
    pt.wait_for(page, lambda: _slider(page, "ctl-theta0").value == 60, what="theta0 back to 60")


@pytest.mark.parametrize("css, log", [("ctl-theta0", False), ("ctl-k_r", True)])
def test_page_keys_move_a_slider_by_a_tenth_of_its_range(page, app_url, css, log):
    _open(page, app_url)
    before = _slider(page, css)
    span = before.end - before.start
    handle = pt.slider_handle(page, css)
    key = "PageDown" if before.value > (before.start + before.end) / 2 else "PageUp"
    pt.move_slider(page, handle, key, presses=1)
    pt.wait_for(page, lambda: _slider(page, css).value != before.value, what=f"{css} to move")
    moved = abs(_slider(page, css).value - before.value)
    assert abs(moved - span / 10) <= before.step / 2 + 1e-9, (moved, span / 10, before.step)
    if log:  # arrows: 0.05 decade, about 50 presses across the range
        assert before.step == pytest.approx(0.05)
        value = _slider(page, css).value
        pt.move_slider(page, handle, "ArrowRight", presses=1)
        pt.wait_for(page, lambda: _slider(page, css).value != value, what="an arrow step")
        assert abs(_slider(page, css).value - value) == pytest.approx(0.05, abs=1e-6)


def _background(page, preset: str) -> str:
    return page.locator(f".preset-{preset} button").first.evaluate(
        "(b) => getComputedStyle(b).backgroundColor")


def test_the_preset_of_the_current_springs_is_marked(page, app_url):
    _open(page, app_url)  # the default springs are the pendulum's
    clear = _background(page, "soft")
    assert _background(page, "pendulum") != clear
    page.locator(".preset-soft button").first.click()
    pt.wait_for(page, lambda: _background(page, "soft") != clear, what="soft to be marked")
    assert _background(page, "pendulum") == clear
    pt.move_slider(page, pt.slider_handle(page, "ctl-k_r"), "ArrowRight", presses=1)
    pt.wait_for(page, lambda: _background(page, "soft") == clear,
              what="no preset marked off the presets")


def test_the_headline_states_the_result_in_words(page, app_url):
    _open(page, app_url)
    headline = page.locator(".headline span").first
    pt.wait_for(page, lambda: "being computed" not in headline.inner_text(), timeout_s=90,
              what="both results in the headline")
    text = headline.inner_text()
    print(text)
    assert re.search(r"^Friction is \d+\.\d % (below|above) a rigid surface \(every support "
                     r"at θ₀ = 90°\); ", text), text
    # The force the slab feels with supports of all orientations (the uniform array's
    # duration-weighted average, in words), or the reason it is missing (a notice).
    felt = re.search(r"; with supports of all orientations the slab feels \d+\.\d % "
                     r"(below|above) a rigid surface \(each support counted for as long as "
                     r"it touches the slab\)\.$", text)
    assert felt or (text.endswith("what the slab feels with supports of all orientations: "
                                  "not computed (see the notice).")
                    and page.locator(".page-notice").is_visible()), text
    details = page.locator(".readout-details")
    assert not page.get_by_text("energy residual").first.is_visible()
    details.get_by_text("Numbers and diagnostics").click()
    pt.wait_for(page, lambda: page.get_by_text("energy residual").first.is_visible(),
              what="the diagnostics")


# ---------------------------------------------------------------------------- phone

def test_the_phone_layout(browser, app_url):
    context, page = _new_page(browser, PHONE)
    try:
        _open(page, app_url)
        width = page.evaluate("() => document.scrollingElement.scrollWidth")
        assert width <= PHONE["width"], f"the page scrolls sideways ({width} px wide)"
        names = TABS["support"][1]
        boxes = page.evaluate(_FIGURE_BOXES_JS, list(names))
        assert set(boxes) == set(names)
        ordered = sorted(boxes.values(), key=lambda b: b[1])
        for upper, lower in zip(ordered, ordered[1:]):
            assert upper[1] + upper[3] <= lower[1] + 1, "two plots share a row"
        assert all(b[2] >= 0.9 * PHONE["width"] for b in ordered), ordered
        # The controls start folded above the plots; opened, they are touch-sized.
        assert not page.locator(".ctl-k_r .noUi-handle").is_visible()
        page.locator(".sidebar").get_by_text("Controls", exact=True).first.click()
        pt.wait_for(page, lambda: page.locator(".ctl-k_r .noUi-handle").is_visible(),
                  what="the controls to open")
        handle = page.locator(".ctl-k_r .noUi-handle").bounding_box()
        assert min(handle["width"], handle["height"]) >= 32, handle
        for preset in ("pendulum", "soft"):
            box = page.locator(f".preset-{preset} button").bounding_box()
            assert box["height"] >= 44, (preset, box)
        assert page.locator(".sidebar").bounding_box()["y"] < ordered[0][1], \
            "the controls are not above the plots"
        width = page.evaluate("() => document.scrollingElement.scrollWidth")
        assert width <= PHONE["width"], f"with the controls open: {width} px wide"
    finally:
        context.close()


# ---------------------------------------------------------------------------- screenshots

@pytest.mark.timeout(600)
def test_screenshots_of_every_tab_on_a_phone(browser, app_url):
    """PNGs of each tab on a 390x844 screen, for a person to look at (at 1280x720 and
    1920x1080, normal and projected: ``test_projector``)."""
    folder = still.shots_dir()
    saved = []
    context, page = _new_page(browser, PHONE)
    try:
        _open(page, app_url)
        for tab, (label, names) in [*TABS.items(), ("equations", ("Equations", ()))]:
            pt.open_tab(page, label)
            for name in names:
                pt.wait_for_plot(page, name)
            if tab == "equations":  # typeset by MathJax once shown
                page.locator(".equations mjx-container").first.wait_for(state="visible")
            pt.settle(page)
            saved.append(still.shoot(page, folder / f"{tab}_normal_390x844.png"))
    finally:
        context.close()
    print(f"{len(saved)} screenshots in {folder}")
    assert len(saved) == 5 and all(p.stat().st_size > 10_000 for p in saved)
