"""The dashboard for keyboard, screen-reader and low-vision users (WCAG 2.1 AA).

* axe-core's WCAG 2.1 A/AA rules find nothing on any tab: on a 1280 x 720 laptop, in
  projector mode and on a phone (one page load each, every tab visited in it);
* the One support tab's plots are described in words in a polite live region, which
  follows the controls and stays still while the animation plays;
* the keyboard reaches the tab bar, the sliders (each named after its title), the regime
  presets and the buttons, and every stop shows a focus ring; Enter opens a tab and Space
  presses a preset;
* a reader who asked for less motion gets no autoplay (the player starts on request).

axe-core comes from npm (``.ci/run`` installs it; see ``axe_tools``): without it these
tests skip on a developer's machine and fail in CI.
"""
from __future__ import annotations

import re

import pytest

from app.views.layout import UI_COLOURS
from app.views.page import TAB_TITLES

from . import axe_tools
from . import page_tools as pt
from . import phone_tools as ph
from .conftest import unavailable
from .serving import VIEWPORT

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

CONFIGS = {"laptop": ({"viewport": VIEWPORT}, ""),
           "projector": ({"viewport": VIEWPORT}, "?projector=1"),
           "phone": (ph.PHONE, "")}

# The element that has the keyboard focus (inside shadow roots) and its focus ring.
_FOCUSED_JS = """() => {
  let el = document.activeElement;
  while (el && el.shadowRoot && el.shadowRoot.activeElement) el = el.shadowRoot.activeElement;
  if (!el || el === document.body) return null;
  const s = getComputedStyle(el);
  return {tag: el.tagName, role: el.getAttribute("role"),
          name: (el.getAttribute("aria-label") || el.textContent || "").trim().slice(0, 60),
          outline: s.outlineStyle, width: parseFloat(s.outlineWidth), colour: s.outlineColor};
}"""


@pytest.fixture(scope="module")
def axe_js():
    if not axe_tools.AXE_JS.exists():
        unavailable(f"axe-core is not installed at {axe_tools.AXE_JS} "
                    f"({axe_tools.INSTALL_HINT})")
    return axe_tools.AXE_JS


def _open(browser, url: str, options: dict):
    context = browser.new_context(**options)
    context.set_default_timeout(60_000)
    page = context.new_page()
    pt.wait_for_app(page, url, timeout_ms=90_000)
    return context, page


@pytest.mark.parametrize("config", list(CONFIGS))
def test_axe_finds_no_wcag_violation_on_any_tab(browser, app_url, axe_js, config):
    options, query = CONFIGS[config]
    context, page = _open(browser, app_url + query, options)
    try:
        found = {}
        for title in TAB_TITLES:
            pt.open_tab(page, "^" + re.escape(title))
            if title == "Equations":  # typeset by MathJax once shown
                page.locator(".equations mjx-container").first.wait_for(state="attached")
            pt.settle(page, quiet_ms=500)
            page.wait_for_timeout(300)  # the page's accessibility pass runs after a change
            violations = axe_tools.violations(page)
            if violations:  # a result landing during the scan redraws part of it: at rest, again
                print(f"{config} [{title}]: scanned again at rest after:\n"
                      + axe_tools.describe(violations))
                pt.settle(page, quiet_ms=1_500)
                violations = axe_tools.violations(page)
            if violations:
                found[title] = axe_tools.describe(violations)
        assert not found, f"{config}: axe-core's WCAG 2.1 A/AA violations:\n" + "\n".join(
            f"[{tab}]\n{text}" for tab, text in found.items())
    finally:
        context.close()


def _description(page) -> str:
    return page.locator(".support-description [role=status]").first.text_content()


def test_the_plots_are_described_and_the_words_follow_the_controls(page, app_url):
    pt.wait_for_app(page, app_url)
    region = page.locator(".support-description [role=status]").first
    assert region.get_attribute("aria-live") == "polite"
    pt.wait_for(page, lambda: "regime" in _description(page), what="the plots' description")
    before = _description(page)
    assert "pendulum regime" in before and "Friction on the slab" in before, before
    assert not region.is_visible() or region.bounding_box()["width"] <= 1, \
        "the description is for screen readers and should be out of sight"

    # Still while the animation plays: nothing is announced per frame.
    pt.click_button(page, "Play")
    seen = set()
    for _ in range(10):
        page.wait_for_timeout(100)
        seen.add(_description(page))
    assert seen == {before}, f"the description changed while playing: {seen}"
    pt.click_button(page, "Pause")

    # A screen reader hears the k_r the slider shows (its model holds log10 k_r); the
    # description may pass through the slider's intermediate values and settles on its last.
    handle = page.get_by_role("slider", name="k_r radial stiffness (log)")
    pt.move_slider(page, handle, "ArrowLeft", presses=30)

    def near(text, value) -> bool:
        return text is not None and abs(float(text) - value) <= 0.01 * value

    def k_r() -> float:
        return 10 ** pt.model_value(page, "Slider$", "value", "ctl-k_r")

    pt.wait_for(page, lambda: k_r() < 1 and near(handle.get_attribute("aria-valuetext"), k_r()),
                what=lambda: f"the k_r handle to announce {k_r():.3g}, not "
                             f"{handle.get_attribute('aria-valuetext')!r}")

    def described() -> str | None:
        found = re.search(r"k_r = ([0-9.]+),", _description(page))
        return found and found.group(1)

    pt.wait_for(page, lambda: near(described(), k_r()),
                what=lambda: f"the description to follow the k_r slider to {k_r():.3g} "
                             f"(it says {described()})")


def test_the_keyboard_reaches_every_control_with_a_visible_focus_ring(page, app_url):
    pt.wait_for_app(page, app_url)
    pt.settle(page)
    page.locator(".tab-bar button").first.focus()
    stops = []
    for _ in range(16):
        stops.append(page.evaluate(_FOCUSED_JS))
        page.keyboard.press("Tab")
    names = [s and s["name"] for s in stops]
    for title in TAB_TITLES:
        assert title in names, f"the tab bar's {title!r} is not a keyboard stop: {names}"
    assert {"Pendulum", "Slider", "Stiff", "Soft", "Reset"} <= set(names), names
    sliders = [s for s in stops if s and s["role"] == "slider"]
    assert [s["name"] for s in sliders][:4] == [
        "k_r radial stiffness (log)", "k_θ torsional stiffness (log)",
        "F_N normal load (log)", "θ₀ rest orientation [°]"], sliders
    rgb = tuple(int(UI_COLOURS["focus"][i:i + 2], 16) for i in (1, 3, 5))
    faint = [s for s in stops if s is None or s["outline"] == "none" or s["width"] < 2
             or s["colour"] != f"rgb({rgb[0]}, {rgb[1]}, {rgb[2]})"]
    assert not faint, f"keyboard stops without a visible focus ring: {faint}"

    # Enter on a tab opens it; Space on a preset presses it.
    page.locator(".tab-bar button").filter(has_text="Regime map").first.focus()
    page.keyboard.press("Enter")
    pt.wait_for(page, lambda: "tab=map" in page.url, what="Enter to open the Regime map tab")
    before = pt.find_slider(page, "ctl-k_r").value
    page.get_by_role("button", name="Soft", exact=True).focus()
    page.keyboard.press("Space")
    pt.wait_for(page, lambda: pt.find_slider(page, "ctl-k_r").value != before,
                what="Space on the Soft preset to set the springs")


def _player(page) -> dict:
    """The support player's play button state and current frame."""
    return page.evaluate("""() => {
      const named = (n) => [...Bokeh.documents[0].all_models].find((m) => m.name === n);
      return {playing: named("support_player_play").active,
              frame: named("support_player_frame").value};
    }""")


def test_no_autoplay_for_a_reader_who_asked_for_less_motion(browser, app_url):
    context, page = _open(browser, f"{app_url}?play=1",
                          {"viewport": VIEWPORT, "reduced_motion": "reduce"})
    try:
        pt.settle(page, names=["support_frames"])
        page.wait_for_timeout(1500)  # the player is made ready after the page is up
        assert _player(page) == {"playing": False, "frame": 0}, "the animation started by itself"
        pt.click_button(page, "Play")
        pt.wait_for(page, lambda: _player(page)["frame"] > 0, what="the player to run on request")
    finally:
        context.close()
