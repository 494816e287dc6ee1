"""The regime map follows the load (Fig. 5 at any F_N): moving the F_N slider on the Map
tab changes the plotted map -- the shipped map of another load or one computed here."""
from __future__ import annotations

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]


def _map_values(page) -> list:
    data = pt.read_source(page, "regime_map") or {}
    return list(data.get("value", []))


def test_moving_F_N_changes_the_regime_map(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=map")
    pt.settle(page)
    pt.wait_for_plot(page, "regime_map")
    page.wait_for_timeout(500)
    before = _map_values(page)
    assert len(before) == 24 * 24, len(before)  # the shipped map at F_N = 1
    handle = pt.slider_handle(page, "ctl-F_N", r"F_N")
    pt.move_slider(page, handle, "ArrowRight", presses=5)
    deadline = 120_000
    waited = 0
    while _map_values(page) == before and waited < deadline:
        page.wait_for_timeout(250)
        waited += 250
    after = _map_values(page)
    assert after and after != before, "the regime map did not follow the F_N slider"
    assert page_log.errors == [], page_log.errors
