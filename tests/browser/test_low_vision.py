"""Low vision (WCAG 2.1 AA): the page zoomed to 200 % on a 1280-px screen (a 640-px wide
window of CSS pixels at twice the device scale, as the browser's zoom makes it) shows
every tab without scrolling sideways (1.4.10 Reflow), and on a 1280 x 720 laptop every
control a pointer hits is at least 24 px both ways (2.5.8 Target size, of WCAG 2.2)."""
from __future__ import annotations

import re

import pytest

from app.views.page import TAB_TITLES

from . import page_tools as pt
from . import phone_tools as ph
from .serving import VIEWPORT

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

#: A 1280 x 720 screen at 200 % zoom.
ZOOMED = {"viewport": {"width": 640, "height": 360}, "device_scale_factor": 2}
MIN_TARGET = 24


def _each_tab(browser, url: str, options: dict, check) -> dict:
    """``check(page)`` on every tab in one page load: {tab: what it found} (empties left out)."""
    context = browser.new_context(**options)
    context.set_default_timeout(60_000)
    found = {}
    try:
        page = context.new_page()
        pt.wait_for_app(page, url, timeout_ms=90_000)
        for title in TAB_TITLES:
            pt.open_tab(page, "^" + re.escape(title))
            pt.settle(page, quiet_ms=500)
            page.wait_for_timeout(300)
            result = check(page)
            if result:
                found[title] = result
    finally:
        context.close()
    return found


def test_at_200_percent_zoom_no_tab_scrolls_sideways(browser, app_url):
    def wider(page):
        width = page.evaluate("() => document.scrollingElement.scrollWidth")
        return width if width > ZOOMED["viewport"]["width"] else None
    found = _each_tab(browser, app_url, ZOOMED, wider)
    assert not found, f"tabs wider than the zoomed window (640 px): {found}"


def test_every_target_is_at_least_24_px(browser, app_url):
    found = _each_tab(browser, app_url, {"viewport": VIEWPORT},
                      lambda page: ph.scan(page, min_text=0, min_target=MIN_TARGET)["tiny"])
    assert not found, f"controls smaller than {MIN_TARGET} px: {found}"
