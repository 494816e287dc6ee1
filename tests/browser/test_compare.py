"""Comparing two states in the browser: an address with ``A=`` shows the pinned state A
beside the current B -- both data sets in the top view, the Fig. 7 histories, the polar
diagrams and the load curve, and the readouts with their differences; Clear A removes A
from the plots and the address, Pin as A puts the current state back in it."""
from __future__ import annotations

import html as html_module
import re
from urllib.parse import parse_qs, urlsplit

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


def _compare_text(page) -> str:
    """The compare readout as text, one table row a line, cells separated by "|"."""
    html = pt.model_value(page, r"Markdown$|HTML$", "text", "readout-compare") or ""
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
