"""In the served page: the headline settles on every tab (it said "being computed" for
good on the Array, Polar, Regime map and Equations tabs); the map's CSV and SVG downloads
give the map; the polar CSV is offered only once its sweep exists."""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

TABS = (("Array", "array"), ("Orientation", "polar"), ("Regime map", "map"),
        ("Load", "load"), ("Equations", "equations"), ("One support", "support"))


def _headline(page) -> str:
    return pt.live_html(page, "headline")


def test_the_headline_settles_on_every_tab(page, page_log, app_url):
    # Opened on each tab in turn, with the slider's springs (as the issue did).
    for title, tab in TABS:
        pt.wait_for_app(page, f"{app_url}?regime=slider&tab={tab}")
        pt.wait_for(page, lambda: "all orientations the slab feels" in _headline(page)
                    and "being computed" not in _headline(page), timeout_s=120,
                    what=lambda: f"the headline on the {title} tab: {_headline(page)!r}")
        assert "15.5 % below a rigid surface (each support counted" in _headline(page)
    assert page_log.errors == [], page_log.errors


def _download(page, label: str, timeout_s: float = 60) -> tuple[str, str]:
    with page.expect_download(timeout=timeout_s * 1000) as info:
        pt.click_button(page, label)
    download = info.value
    return download.suggested_filename, open(download.path(), encoding="utf-8").read()


def test_the_map_downloads_as_csv_and_svg(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=map&F_N=3")
    pt.wait_for_plot(page, "regime_map")
    pt.wait_for(page, lambda: page.get_by_role("button", name="Map CSV").is_enabled(),
                timeout_s=60, what="the map's CSV")
    name, text = _download(page, "^Map CSV$")
    assert name == "regime_map.csv" and text.startswith("# kind: regime_map")
    assert "# F_N: 3.0" in text and len(text.splitlines()) > 24 * 24
    name, text = _download(page, r"^Figure \(SVG\)$")
    assert name == "regime_map.svg" and "<svg" in text[:300]
    assert "Uniform array F_T,x" in text and "F_N = 3" in text  # the title, as drawn
    assert page_log.errors == [], page_log.errors


def test_the_sidebar_svg_button_saves_each_figure_on_screen(page, page_log, app_url):
    """The sidebar's SVG button, answered by the page's own code (``PageBehaviour``):
    one file per figure of the tab on show, none of a tab not shown."""
    pt.wait_for_app(page, f"{app_url}?tab=support")
    for name in ("scene", "forces"):
        pt.wait_for_plot(page, name)
    saved: list = []

    def on_download(download):
        saved.append(download)
    page.on("download", on_download)  # the page is shared by the module's tests
    try:
        pt.click_button(page, r"^Figures on screen \(SVG\)$")
        pt.wait_for(page, lambda: {"scene.svg", "forces.svg", "friction_law.svg"}
                    <= {d.suggested_filename for d in saved}, timeout_s=30,
                    what=lambda: f"the figures saved: {[d.suggested_filename for d in saved]}")
        page.wait_for_timeout(500)  # any other file would have started by now
    finally:
        page.remove_listener("download", on_download)
    names = sorted(d.suggested_filename for d in saved)
    assert len(names) == len(set(names)) and "regime_map.svg" not in names, names
    assert all("<svg" in open(d.path(), encoding="utf-8").read()[:300] for d in saved)
    assert page_log.errors == [], page_log.errors


def test_the_polar_csv_waits_for_its_sweep(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=support&k_r=0.7")
    compute = page.get_by_role("button", name="Compute polar sweep CSV")
    compute.wait_for(state="visible")
    compute.click()
    pt.wait_for(page, lambda: page.get_by_role(
        "button", name=re.compile("^Polar sweep CSV")).first.is_visible(), timeout_s=30)
    name, text = "", ""
    # Disabled and saying so until the sweep is there; then the file is the sweep.
    ready = page.get_by_role("button", name="Polar sweep CSV", exact=True)
    ready.wait_for(state="visible", timeout=120_000)
    pt.wait_for(page, ready.is_enabled, timeout_s=120, what="the polar sweep")
    name, text = _download(page, "^Polar sweep CSV$")
    assert text.startswith("# kind: orientation") and "being computed" not in text
    assert page_log.errors == [], page_log.errors
