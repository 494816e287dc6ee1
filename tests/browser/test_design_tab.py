"""The Design tab of the served dashboard: the pillar array's dimensionless point is
computed and marked on the regime map, and it moves along its speed line when the
sliding speed is typed in."""
from __future__ import annotations

import pytest

from model.units import PillarDesign

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]


def _wait_point(page, predicate, timeout_ms=60_000):
    waited, data = 0, None
    while waited < timeout_ms:
        data = pt.read_source(page, "design_point")
        if data and data.get("k_r") and predicate(data):
            return data
        page.wait_for_timeout(250)
        waited += 250
    pytest.fail(f"the design's point never showed as expected; last: {data}")


def test_the_design_tab_marks_its_point_on_the_map(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=design")
    pt.wait_for_plot(page, "regime_map")
    # The default pillars (LDPE, the notes' example) at the default speed of 1 m/s.
    expected = PillarDesign.example(V0="1 m/s").dimensionless()
    point = _wait_point(page, lambda d: True)
    assert point["k_r"][0] == pytest.approx(expected["k_r"], rel=1e-9)
    assert point["k_theta"][0] == pytest.approx(expected["k_theta"], rel=1e-9)
    line = pt.read_source(page, "design_line")
    assert len(line["k_r"]) > 10  # the speed line through it
    # Outside the paper's map: the log axes widen to show it.
    x_end = page.evaluate("""() => [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "regime_map" && "x_range" in m).x_range.end""")
    assert x_end > expected["k_r"]
    shown = page.locator(".design-point p").filter(has_text="outside the paper's explored map")
    shown.first.wait_for(timeout=30_000)
    assert "stiff" in shown.first.inner_text()

    # Typing a faster slab moves the point down the diagonal: both k~ scale as 1/V0^2.
    box = page.locator(".ctl-design_V0 input").first
    box.fill("2 m/s")
    box.press("Enter")
    moved = _wait_point(page, lambda d: abs(d["k_r"][0] - expected["k_r"] / 4)
                        <= 1e-6 * expected["k_r"])
    assert moved["k_theta"][0] == pytest.approx(expected["k_theta"] / 4, rel=1e-9)
    assert _wait_url(page, "d_V0=2"), page.url  # the link carries it

    # A wrong unit is named, and nothing is marked.
    box.fill("2 kg")
    box.press("Enter")
    page.locator(".design-point p").filter(has_text="V0='2 kg'").first.wait_for(timeout=30_000)
    page.wait_for_function("""() => { const s = [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "design_point" && /DataSource$/.test(m.type));
        const d = s.data instanceof Map ? Object.fromEntries(s.data) : s.data;
        return d.k_r.length === 0; }""", timeout=30_000)
    assert page_log.errors == [], page_log.errors


def _wait_url(page, fragment, timeout_ms=5_000):
    waited = 0
    while waited < timeout_ms:
        if fragment in page.url:
            return True
        page.wait_for_timeout(200)
        waited += 200
    return False


FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s&dist=pair&dist_deg=40"


def test_optimise_runs_in_the_background_and_sets_the_optimum(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}{FAST}")
    _wait_point(page, lambda d: True)
    page.locator(".design-optimise button").first.click()
    # Done (about a second of a worker here) or still running: either way the page says so.
    page.locator(".design-optimum p").filter(has_text="less friction").first.wait_for(
        timeout=90_000)
    text = page.locator(".design-optimum p").filter(has_text="less friction").first.inner_text()
    assert "Optimum (pair)" in text
    # The editor is set to the optimum, and the link carries it.
    page.wait_for_function("() => /dist_deg=/.test(location.search) && "
                           "!/dist_deg=40(&|$)/.test(location.search)", timeout=10_000)
    assert page_log.errors == [], page_log.errors


def test_a_long_optimisation_shows_progress_and_can_be_cancelled(page, page_log, app_url):
    # The default pillars lie far outside the map (k~ ~ 1e3): the search takes long.
    pt.wait_for_app(page, f"{app_url}?tab=design&dist=fixed")
    _wait_point(page, lambda d: True)
    page.locator(".design-optimise button").first.click()
    page.locator(".design-optimum p").filter(has_text="s so far").first.wait_for(
        timeout=20_000)
    page.locator(".design-cancel button").first.click()
    page.locator(".design-optimum p").filter(has_text="Cancelled").first.wait_for(
        timeout=10_000)
    assert not page.locator(".design-cancel button").first.is_enabled()
    assert page.locator(".design-optimise button").first.is_enabled()
    assert page_log.errors == [], page_log.errors
