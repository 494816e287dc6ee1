"""The dashboard on a real phone's emulation (Playwright ``is_mobile``, touch, device scale
factor 3, 390 x 844): the page declares its viewport (without it a phone lays the page out
980 px wide and shrinks it to ~0.4), never scrolls sideways, draws no text under 12 px
and no tap target under 44 px, on every tab; the Design tab's figures cover no input.
One phone page goes from tab to tab with its tab bar, as a student does."""
from __future__ import annotations

import re

import pytest

from app.defaults import TABS
from app.views.page import TAB_TITLES

from . import page_tools as pt
from . import phone_tools as ph

pytestmark = [pytest.mark.browser, pytest.mark.timeout(300)]


@pytest.fixture(scope="module")
def phone(browser):
    """The module's phone page (``tab``: the tab it shows at rest, None until opened)."""
    context = browser.new_context(**ph.PHONE)
    context.set_default_timeout(30_000)
    shared = {"page": context.new_page(), "tab": None}
    yield shared
    context.close()


def _on_tab(phone: dict, app_url: str, tab: str):
    """The phone page on ``tab`` at rest: opened on it the first time (or after a test
    failed on it), else reached with the tab bar."""
    page, shown = phone["page"], phone["tab"]
    phone["tab"] = None  # until the test using it passes
    if shown is None:
        pt.wait_for_app(page, f"{app_url}?tab={tab}", timeout_ms=90_000)
    elif shown != tab:
        pt.open_tab(page, "^" + re.escape(TAB_TITLES[TABS.index(tab)]), tab)
    pt.settle(page)
    page.wait_for_timeout(500)
    return page


def _check(found: dict, canvas: list, where: str) -> None:
    assert found["meta"] == "width=device-width, initial-scale=1", where
    assert found["scroll_width"] <= found["width"], \
        f"{where}: the page scrolls sideways ({found['scroll_width']} px)"
    assert found["small"] == [], f"{where}: text under {ph.MIN_TEXT_PX} px: {found['small'][:5]}"
    assert found["tiny"] == [], f"{where}: targets under {ph.MIN_TARGET_PX} px: {found['tiny'][:5]}"
    small = [c for c in canvas if c["size"] < ph.MIN_TEXT_PX]
    assert small == [], f"{where}: figure text under {ph.MIN_TEXT_PX} px: {small[:5]}"


@pytest.mark.parametrize("tab", TABS)
def test_every_tab_fits_a_phone(phone, app_url, tab):
    page = _on_tab(phone, app_url, tab)
    assert page.evaluate("() => window.innerWidth") == ph.PHONE["viewport"]["width"], \
        "the phone did not lay the page out at its own width"
    _check(ph.scan(page), ph.canvas_text_sizes(page), f"{tab} tab")
    assert ph.cut_titles(page) == [], f"{tab} tab: titles cut off: {ph.cut_titles(page)}"
    if tab == "support":  # the controls, opened (and folded again for the next tab)
        controls = page.locator(".sidebar").get_by_text("Controls", exact=True).first
        controls.click()
        pt.wait_for(page, lambda: page.locator(".ctl-k_r .noUi-handle").is_visible(),
                    what="the controls to open")
        page.wait_for_timeout(500)
        _check(ph.scan(page), [], "the opened controls")
        controls.click()
        pt.wait_for(page, lambda: not page.locator(".ctl-k_r .noUi-handle").is_visible(),
                    what="the controls to fold")
    phone["tab"] = tab


def test_the_design_figures_cover_no_input_on_a_phone(phone, app_url):
    page = _on_tab(phone, app_url, "design")
    pt.wait_for_plot(page, "design_map")
    boxes = page.evaluate("""() => {
      const out = {};
      for (const m of Bokeh.documents[0].all_models) {
        if (m.name !== "design_map" || !("x_range" in m)) continue;
        const v = Bokeh.index.find_one(m);
        if (!v || v.el.getBoundingClientRect().width === 0) continue;
        const r = v.el.getBoundingClientRect();
        out.map = [r.left, r.top, r.width, r.height];
      }
      return out;
    }""")
    top = boxes["map"][1]
    for name in ("design_V0", "design_V_s", "design_F_N"):
        box = page.locator(f".ctl-{name} input").first.bounding_box()
        assert box is not None, name
        assert box["y"] + box["height"] <= top + 1, (name, box, boxes)
    phone["tab"] = "design"
