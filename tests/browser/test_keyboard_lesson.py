"""The lesson of docs/teaching.md taught from the keyboard alone (WCAG 2.1.1): from the
default page, with Tab, Shift+Tab, Enter, Space and the arrow keys only (no mouse, no
programmatic focus), the page reaches each question's state (Q1-Q7: the regime presets,
theta0 = 150°, the Array tab, F_N = 10 on the Load tab), and the player and the
figures' "click to set" (the regime map's and the polar diagrams' buttons) work too.
Each state is checked where a reader finds it: the page's address (a shared link) and
the plots' descriptions for screen readers.
"""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(900)]

# The focused element's accessible name and role (inside shadow roots).
_FOCUSED = """() => {
  let el = document.activeElement;
  while (el && el.shadowRoot && el.shadowRoot.activeElement) el = el.shadowRoot.activeElement;
  if (!el || el === document.body) return null;
  return {role: el.getAttribute("role") || el.tagName.toLowerCase(),
          name: (el.getAttribute("aria-label") || el.textContent || "").trim()};
}"""
MAX_STOPS = 150


def _tab_to(page, name: str, role: str = "button", backwards: bool = False) -> None:
    """Press Tab (or Shift+Tab) until the focus is on the control named ``name``."""
    for _ in range(MAX_STOPS):
        focused = page.evaluate(_FOCUSED)
        if focused and focused["name"] == name and focused["role"] == role:
            return
        page.keyboard.press("Shift+Tab" if backwards else "Tab")
    pytest.fail(f"Tab never reached the {role} {name!r}", pytrace=False)


def _press(page, name: str, key: str = "Space", role: str = "button") -> None:
    _tab_to(page, name, role)
    page.keyboard.press(key)


def _description(page, css: str) -> str:
    region = page.locator(f".{css} [role=status]").first
    return (region.text_content() or "") if region.count() else ""


def _wait_words(page, css: str, *phrases: str) -> None:
    pt.wait_for(page, lambda: all(p in _description(page, css) for p in phrases),
                timeout_s=180, what=lambda: f"{phrases} in {_description(page, css)!r}")


def _wait_url(page, **keys) -> None:
    pt.wait_for(page, lambda: all(re.search(rf"[?&]{k}={re.escape(v)}(&|$)", page.url)
                                  for k, v in keys.items()),
                timeout_s=60, what=lambda: f"{keys} in the address {page.url}")


def _springs(page) -> float:
    found = re.search(r"The current springs, k_r = ([0-9.]+)",
                      _description(page, "map-description"))
    return float(found[1]) if found else float("nan")


def _slider_keys(page, name: str, key: str, presses: int) -> None:
    """Press ``key`` ``presses`` times on the slider ``name`` (one step each; PageUp a
    tenth of the range, stopping at the end)."""
    _tab_to(page, name, "slider")
    for _ in range(presses):
        page.keyboard.press(key)


def test_the_lesson_can_be_taught_from_the_keyboard_alone(page, page_log, app_url):
    pt.wait_for_app(page, app_url)
    pt.settle(page)
    page.keyboard.press("Tab")  # into the page
    words = "support-description"
    # Q1-Q3, Q5: the presets, with Space.
    for preset, regime, springs in (("Stiff", "stiff", "k_r = 3, k_θ = 3"),
                                    ("Pendulum", "pendulum", "k_r = 3, k_θ = 0.01"),
                                    ("Slider", "slider", "k_r = 0.01, k_θ = 3")):
        _press(page, preset)
        _wait_words(page, words, f"{regime} regime ({springs}", "turned from 90°")
        if preset == "Pendulum":  # the player: Enter plays and pauses
            _tab_to(page, "▶ Play")
            page.keyboard.press("Enter")
            _tab_to(page, "‖ Pause")
            page.keyboard.press("Enter")
            _tab_to(page, "▶ Play")
    # Q4: theta0 = 150° with the arrow keys.
    _slider_keys(page, "θ₀ rest orientation [°]", "ArrowRight", 60)  # 1° a step
    _wait_words(page, words, "turned from 150°")
    _wait_url(page, theta0_deg="150")
    _slider_keys(page, "θ₀ rest orientation [°]", "ArrowLeft", 60)
    _wait_words(page, words, "turned from 90°")
    _press(page, "Soft")
    _wait_words(page, words, "soft regime (k_r = 0.03, k_θ = 0.03", "turned from 90°")
    # Q6: the Array tab (Enter on the tab bar), slider regime.
    _press(page, "Slider")
    _tab_to(page, "Array", backwards=True)
    page.keyboard.press("Enter")
    _wait_url(page, tab="array")
    _wait_words(page, "array-description", "k_r = 0.01, k_θ = 3", "Once settled")
    # Q7: soft regime, F_N = 10, the Load tab.
    _tab_to(page, "Load", backwards=True)
    page.keyboard.press("Enter")
    _wait_url(page, tab="load")
    _press(page, "Soft")
    _slider_keys(page, "F_N normal load (log)", "PageUp", 15)  # to the end, F_N = 10
    _wait_words(page, "load-description", "At the current F_N = 10:")
    _wait_url(page, F_N="10", k_r="0.03")
    # The figures' "click to set": the map's and the polar diagrams' buttons.
    _tab_to(page, "Regime map", backwards=True)
    page.keyboard.press("Enter")
    _wait_words(page, "map-description", "The current springs, k_r = 0.03, k_θ = 0.03")
    _press(page, "k_r +", "Enter")  # one cell of the map to the right
    pt.wait_for(page, lambda: 0.035 < _springs(page) < 0.045, timeout_s=60,
                what=lambda: f"k_r + to move the springs: {_description(page, 'map-description')}")
    _tab_to(page, "Orientation (polar)", backwards=True)
    page.keyboard.press("Enter")
    _wait_words(page, "polar-description", "At the current θ₀ = 90°")
    _press(page, "θ₀ +15°", "Enter")
    _wait_words(page, "polar-description", "At the current θ₀ = 105°")
    _wait_url(page, theta0_deg="105")
    assert page_log.errors == [], page_log.errors
