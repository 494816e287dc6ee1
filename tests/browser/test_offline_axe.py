"""The offline explorer (``micropillar pack``), opened from file:// in headless Chromium,
passes axe-core's WCAG 2.1 A/AA rules on every tab: on a 1280 x 720 laptop, in projector
mode and on a phone."""
from __future__ import annotations

import pytest

from app.offline.pack import OFFLINE_TABS, write

from . import axe_tools
from . import phone_tools as ph
from .conftest import unavailable
from .serving import VIEWPORT

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

CONFIGS = {"laptop": ({"viewport": VIEWPORT}, ""),
           "projector": ({"viewport": VIEWPORT}, "&projector=1"),
           "phone": (ph.PHONE, "")}
DRAWN = "Number(document.documentElement.getAttribute('data-drawn') || 0)"


@pytest.fixture(scope="module")
def explorer_file(tmp_path_factory):
    if not axe_tools.AXE_JS.exists():
        unavailable(f"axe-core is not installed at {axe_tools.AXE_JS} "
                    f"({axe_tools.INSTALL_HINT})")
    path = tmp_path_factory.mktemp("offline") / "explorer.html"
    write(path)
    return path


@pytest.mark.parametrize("config", list(CONFIGS))
def test_the_offline_explorer_has_no_wcag_violation_on_any_tab(browser, explorer_file, config):
    options, extra = CONFIGS[config]
    context = browser.new_context(**options)
    context.set_default_timeout(60_000)
    found = {}
    try:
        page = context.new_page()
        for tab in OFFLINE_TABS:
            page.goto(f"{explorer_file.as_uri()}#tab={tab}{extra}")
            page.reload()  # a new fragment alone does not reload the page
            page.wait_for_function(f"{DRAWN} >= 1", timeout=120_000)
            page.wait_for_timeout(500)
            violations = axe_tools.violations(page)
            if violations:
                found[tab] = axe_tools.describe(violations)
    finally:
        context.close()
    assert not found, f"axe-core's WCAG 2.1 A/AA violations ({config}):\n" + "\n".join(
        f"[{tab}]\n{text}" for tab, text in found.items())


def _figures_drawn(page, tab: str, fragment: str) -> dict:
    page.goto(f"{fragment}&tab={tab}")
    page.reload()
    page.wait_for_function(f"{DRAWN} >= 1", timeout=120_000)
    if tab == "polar":
        page.wait_for_function("Number(document.documentElement.getAttribute('data-polar') "
                               "|| 0) >= 1", timeout=120_000)
    page.wait_for_timeout(500)  # the page names its figures 100 ms after a change
    return axe_tools.ax_figures(page)


def test_the_offline_figures_are_named_and_described_by_the_state(browser, explorer_file):
    context = browser.new_context(viewport=VIEWPORT)
    context.set_default_timeout(60_000)
    try:
        page = context.new_page()
        for tab, count in (("support", 4), ("polar", 3), ("map", 1)):
            pendulum = _figures_drawn(page, tab, f"{explorer_file.as_uri()}#regime=pendulum")
            soft = _figures_drawn(page, tab, f"{explorer_file.as_uri()}#regime=soft")
            assert len(pendulum) >= count and set(soft) == set(pendulum), (tab, pendulum, soft)
            assert all(name and words for name, words in soft.items()), (tab, soft)
            assert all(soft[name] != pendulum[name] for name in soft), (tab, pendulum, soft)
            assert all("k_r = 0.03, k_θ = 0.03" in words for words in soft.values()), soft
    finally:
        context.close()


def test_the_offline_sliders_announce_the_values_they_show(browser, explorer_file):
    """A screen reader hears k_r = 3, not the log slider's position 0.48 (WCAG 4.1.2)."""
    context = browser.new_context(viewport=VIEWPORT)
    context.set_default_timeout(60_000)
    try:
        page = context.new_page()
        page.goto(f"{explorer_file.as_uri()}#regime=pendulum")
        page.wait_for_function(f"{DRAWN} >= 1", timeout=120_000)
        page.wait_for_timeout(500)  # the page names its handles 100 ms after a change
        spoken = {h.get_attribute("aria-label").split(":")[0]: h.get_attribute("aria-valuetext")
                  for h in page.get_by_role("slider").all()}
        assert {k: spoken.get(k) for k in ("k_r", "k_θ", "F_N", "θ₀")} == {
            "k_r": "3", "k_θ": "0.01", "F_N": "1", "θ₀": "90"}, spoken
        handle = page.get_by_role("slider", name="k_r: radial stiffness (Eq. 5)")
        handle.focus()
        for _ in range(4):
            page.keyboard.press("ArrowLeft")
        # The handle's value text follows the slider's model (log10 k_r), now below 3.
        page.wait_for_function("""(handle) => {
          const k_r = 10 ** Bokeh.documents[0].get_model_by_name("slider-k_r").value;
          const spoken = Number(handle.getAttribute("aria-valuetext"));
          return k_r < 3 && Math.abs(spoken - k_r) <= 0.01 * k_r;
        }""", arg=handle.element_handle(), timeout=10_000)
    finally:
        context.close()
