"""The page's width: opened from a link, no tab scrolls sideways, on a phone (its own
layout stacks) or at 1280 x 720; the Design tab is measured again while its array is
computed, with the banner that says so."""
from __future__ import annotations

import os
import time

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]

LAPTOP = {"width": 1280, "height": 720}
PHONE = {"width": 390, "height": 844}


def _new_page(browser, viewport):
    context = browser.new_context(viewport=viewport)
    context.set_default_timeout(30_000)
    return context, context.new_page()


def _open(page, url: str) -> None:
    pt.wait_for_app(page, url)
    pt.settle(page)


@pytest.mark.parametrize("tab, viewport", [("array", PHONE), ("equations", PHONE),
                                           ("design", PHONE), ("design", LAPTOP)])
def test_no_tab_scrolls_sideways(browser, app_url, tab, viewport):
    """Opened from a link, a tab fits the screen's width: on a phone its own layout stacks
    (the Design tab's inputs, figures and readouts; long equations scroll within their
    line, with a shadow at the edge that shows it) and the hidden tabs do not widen the
    page; at 1280 x 720 the Design tab's figures take the width its inputs and readouts
    leave. The Design tab is measured again while its array is computed: the banner
    saying so stays within its pane."""
    context, page = _new_page(browser, viewport)
    try:
        _open(page, f"{app_url}?tab={tab}")
        if tab == "design":
            _banner_fits(page, viewport)
        if tab == "equations":
            _long_equations_show_they_scroll(page)
        width = page.evaluate("() => document.scrollingElement.scrollWidth")
        assert width <= viewport["width"], f"the {tab} tab scrolls sideways ({width} px wide)"
    finally:
        context.close()


def _long_equations_show_they_scroll(page) -> None:
    """An equation wider than the phone scrolls within its line and shows a shadow at its
    edge (a gradient drawn with the line's scroll); one that fits has none."""
    page.locator(".equations mjx-container").first.wait_for(state="visible")
    pt.settle(page)
    lines = page.evaluate("""() => {
      const out = [];
      const walk = (root) => {
        for (const e of root.querySelectorAll(".scroll-x")) {
          const cs = getComputedStyle(e);
          out.push({over: e.scrollWidth > e.clientWidth + 1, image: cs.backgroundImage,
                    attach: cs.backgroundAttachment});
        }
        for (const e of root.querySelectorAll("*")) if (e.shadowRoot) walk(e.shadowRoot);
      };
      walk(document);
      return out;
    }""")
    assert any(line["over"] for line in lines), "no equation is wider than the phone"
    for line in lines:
        hinted = "gradient" in line["image"] and "local" in line["attach"]
        assert hinted == line["over"], line


def _banner_fits(page, viewport) -> None:
    """Type a sliding speed no other test asks for, and measure the Design tab at the first
    frame its "Computing" banner shows (one script, so the banner cannot vanish between
    seeing it and measuring it)."""
    speed = f"{1 + (os.getpid() % 997 + time.time_ns() % 10_007) / 1e5:.5f} m/s"
    host = page.locator(".design-updating").element_handle()
    box = page.locator(".ctl-design_V0 input").first
    box.fill(speed)
    box.press("Enter")
    seen = page.wait_for_function("""(host) => {
        const edges = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.right]; };
        if (host.getBoundingClientRect().width === 0) return false;
        const content = [...host.shadowRoot.children].find((e) => e.tagName === "DIV");
        return {host: edges(host), content: edges(content),
                width: document.scrollingElement.scrollWidth};
    }""", arg=host, polling="raf", timeout=30_000).json_value()
    (host_left, host_right), (left, right) = seen["host"], seen["content"]
    assert host_left - 0.5 <= left and right <= host_right + 0.5, (
        f"the banner's box {left:.0f}-{right:.0f} px leaves its pane's "
        f"{host_left:.0f}-{host_right:.0f} px")
    assert seen["width"] <= viewport["width"], \
        f"with the banner shown the design tab scrolls sideways ({seen['width']} px wide)"
