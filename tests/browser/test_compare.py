"""Comparing two states in the browser: an address with ``A=`` shows the pinned state A
beside the current B -- both data sets in the top view, the Fig. 7 histories, the polar
diagrams and the load curve, and the readouts with their differences; Clear A removes A
from the plots and the address, Pin as A puts the current state back in it. On the Design
tab, A's point on the map, its Fig. 11a curve and distribution, and its array's numbers
beside B's."""
from __future__ import annotations

import html as html_module
import re
from urllib.parse import parse_qs, quote, urlsplit

import pytest

from . import page_tools as pt
from .test_dashboard import _no_errors

pytestmark = [pytest.mark.browser, pytest.mark.timeout(300)]

A = "k_r:0.5,k_theta:0.2,F_N:1,theta0_deg:60"
QUERY = f"?A={A}&k_r=3&k_theta=0.01&F_N=1&theta0_deg=90"


def _rows(page, name: str, column: str) -> list:
    data = pt.read_source(page, name) or {}
    return [v for v in data.get(column, []) if v is not None]


def _wait_rows(page, name: str, column: str, timeout_s: float = 60.0) -> list:
    pt.wait_for(page, lambda: len(_rows(page, name, column)) > 1, timeout_s,
                what=f"data in the source {name!r}")
    return _rows(page, name, column)


def _compare_text(page, css_class: str = "readout-compare") -> str:
    """The compare readout as text, one table row a line, cells separated by "|"."""
    html = pt.model_value(page, r"Markdown$|HTML$", "text", css_class) or ""
    html = html_module.unescape(html).replace("\n", "").replace("</tr>", "\n")
    return re.sub(r"\|+", "|", re.sub(r"<[^>]+>", "|", html))


def test_an_address_with_a_shows_both_states(page, page_log, app_url):
    pt.wait_for_app(page, app_url + QUERY)
    # The top view and Fig. 7 carry A's and B's data, and they differ.
    a_x, b_x = _wait_rows(page, "orbit_A", "x"), _wait_rows(page, "orbit", "x0")
    a_F, b_F = _wait_rows(page, "forces_A", "F_x"), _wait_rows(page, "forces", "F_x")
    assert a_x[:len(b_x)] != b_x and a_F[:len(b_F)] != b_F
    # The readouts: A, B and B - A, which is not zero for these two states.
    pt.wait_for(page, lambda: "B − A" in _compare_text(page) and
                "–" not in _compare_text(page), 60,
                what=f"every number of the compare readout ({_compare_text(page)!r})")
    text = _compare_text(page)
    rows = [[c.strip() for c in line.split("|") if c.strip()] for line in text.splitlines()]
    row = next(r for r in rows if r and r[0] == "F_T,x/(μ₀F_N)")
    a, b, diff = (float(cell) for cell in row[1:4])
    assert a != b and diff == pytest.approx(b - a, rel=2e-3, abs=2e-4), row
    assert "k_r = 0.5" in text and "k_r = 3" in text
    # The headline: a second line with A's friction and B − A of the fixed arrays.
    headline = pt.live_html(page, "headline")
    assert "A (pinned)" in headline and f"B − A = {row[3]}," in html_module.unescape(
        headline), (headline, row)  # the readout's B − A, as text
    # The polar diagrams: A's curves beside B's.
    pt.open_tab(page, "Orientation")
    for key in ("FTx", "DyDx", "FTy"):
        assert len(_wait_rows(page, f"polar_{key}_A", "x")) == \
            len(_wait_rows(page, f"polar_{key}", "x"))
    assert _rows(page, "polar_FTx_A", "value") != _rows(page, "polar_FTx", "value")
    # The load curve: A's beside B's (uniform arrays at seven loads each).
    pt.open_tab(page, "Load")
    a_load = _wait_rows(page, "load_curve_A", "value", timeout_s=120)
    b_load = _wait_rows(page, "load_curve", "value", timeout_s=120)
    assert len(a_load) == len(b_load) and a_load != b_load
    _no_errors(page_log)


def test_clear_and_pin_follow_the_address(page, page_log, app_url):
    pt.wait_for_app(page, app_url + QUERY)
    _wait_rows(page, "orbit_A", "x")
    pt.click_button(page, r"^Clear A$")
    pt.wait_for(page, lambda: not _rows(page, "orbit_A", "x"), what="A's path removed")
    pt.wait_for(page, lambda: "A" not in parse_qs(urlsplit(page.url).query),
                what=f"no A in the address (now {page.url})")
    assert not pt.model_value(page, r"Markdown$|HTML$", "visible", "readout-compare")
    pt.click_button(page, r"^Pin as A$")
    pt.wait_for(page, lambda: parse_qs(urlsplit(page.url).query).get("A") ==
                ["k_r:3,k_theta:0.01,F_N:1,theta0_deg:90"],
                what=f"the current state pinned in the address (now {page.url})")
    # Pinned at B: A's path is B's.
    pt.wait_for(page, lambda: len(_rows(page, "orbit_A", "x")) > 1, what="A's path")
    assert _rows(page, "orbit_A", "x")[:-1] == _rows(page, "orbit", "x0")
    _no_errors(page_log)


#: A: the notes' LDPE pillars at 100 m/s with the default von Mises orientations; B: the
#: same pillars at 80 m/s, in pairs at ±30° (both inside the paper's map: seconds each).
#: A's diameter and height are written at length: an A over 100 characters is read too.
DESIGN_A = ("k_r:3,k_theta:0.01,F_N:1,theta0_deg:90,d_D:5.00000 um,d_h:50.0000 um,d_FN:1 N,"
            "d_V0:100 m/s,d_Vs:10 m/s")
assert len(DESIGN_A) > 100
DESIGN_QUERY = ("?tab=design&d_FN=1%20N&d_V0=80%20m/s&d_Vs=10%20m/s&dist=pair&dist_deg=30"
                f"&A={quote(DESIGN_A, safe=':,')}")


def _row(text: str, label: str) -> list:
    rows = [[c.strip() for c in line.split("|") if c.strip()] for line in text.splitlines()]
    return next((r for r in rows if r and r[0] == label), [])


def _numbers(row: list) -> list | None:
    try:
        return [float(cell.replace("−", "-")) for cell in row[1:4]]
    except (ValueError, IndexError):
        return None


def test_the_design_tab_shows_both_designs(page, page_log, app_url):
    pt.wait_for_app(page, app_url + DESIGN_QUERY)
    # The map: A's point (muted) beside B's, each where its speed puts it.
    pt.wait_for(page, lambda: _rows(page, "design_point_A", "k_r") and
                _rows(page, "design_point", "k_r"), 60, what="both designs on the map")
    a_k, b_k = _rows(page, "design_point_A", "k_r")[0], _rows(page, "design_point", "k_r")[0]
    assert a_k == pytest.approx(b_k * (80.0 / 100.0) ** 2, rel=1e-9)  # k~ ~ 1/V0^2
    # Fig. 11a: A's curve at its springs beside B's, A's density (von Mises) and B's
    # point masses (the pair).
    a_curve = _wait_rows(page, "design_curve_A", "value", timeout_s=120)
    b_curve = _wait_rows(page, "polar_FTx", "value", timeout_s=120)
    assert len(a_curve) == len(b_curve) and a_curve != b_curve
    assert len(_wait_rows(page, "design_density_A", "x")) > 10
    assert len(_rows(page, "design_atoms", "xs")) == 2
    assert not _rows(page, "design_atoms_A", "xs") and not _rows(page, "design_density", "x")
    # The readouts: A's array, B's and B − A.
    label = "F_T,x/(μ₀F_N) (Eq. 10)"
    pt.wait_for(page, lambda: _numbers(_row(_compare_text(page, "design-compare"), label)),
                120, what=f"A's and B's arrays ({_compare_text(page, 'design-compare')!r})")
    text = _compare_text(page, "design-compare")
    a, b, diff = _numbers(_row(text, label))
    assert a != b and diff == pytest.approx(b - a, rel=2e-3, abs=2e-4), text
    assert "von Mises about 90°" in text and "pair ±30°" in text
    # The address keeps A with its design part.
    pt.wait_for(page, lambda: "d_V0:100 m/s" in (parse_qs(urlsplit(page.url).query).get("A")
                                                  or [""])[0], what=f"A in {page.url}")
    _no_errors(page_log)
