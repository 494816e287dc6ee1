"""A page opened with a value Panel's query parser cannot convert still works in the browser.

``?x=`` + 4301 digits made Panel raise while building the page (Python converts at most
4300 digits to an int): the page drew, but its widgets stopped syncing with the server
(``UnknownReferenceError`` in the log). Now the value is refused with a notice, the
address bar is rewritten from the state, and the controls keep driving the server.
"""
from __future__ import annotations

from urllib.parse import parse_qs, urlsplit

import pytest

from . import page_tools as pt
from .test_dashboard import _handle, _no_errors, _value

pytestmark = [pytest.mark.browser, pytest.mark.timeout(180)]

LONG_DIGITS = "1" * 4301


def test_over_long_number_leaves_the_widgets_in_sync(page, page_log, app_url, server_log):
    with page.expect_response(lambda r: urlsplit(r.url).path.endswith("/app")) as first:
        pt.wait_for_app(page, f"{app_url}?x={LONG_DIGITS}&k_r={LONG_DIGITS}&theta0_deg=45")
    pt.settle(page)
    headers = first.value.headers
    assert headers.get("x-frame-options") == "SAMEORIGIN", headers
    assert headers.get("x-content-type-options") == "nosniff", headers
    text = pt.model_value(page, r"\bHTML$|Markdown$|Alert$", "text", "page-notice") or ""
    assert "too long" in text and "k_r" in text, text
    # The server answers the controls: a moved slider reaches the address bar.
    pt.move_slider(page, _handle(page, "theta0"), "ArrowRight", presses=2)
    pt.wait_for(page, lambda: parse_qs(urlsplit(page.url).query).get("theta0_deg") == ["47"],
              what=f"theta0_deg=47 in the URL (now {page.url[:200]})")
    assert LONG_DIGITS not in page.url
    assert "UnknownReferenceError" not in server_log.read_text(encoding="utf-8", errors="replace")
    _no_errors(page_log)


def test_the_busy_page_goes_back_to_its_page_and_nowhere_else(page, page_log, app_url):
    """The busy page (where a client with too many unopened pages is sent, ``?next=`` the
    page it asked for) goes back there by itself within 3-6 s; a ``next`` off this server
    is not followed: the busy page reloads itself."""
    from app.opening import BUSY_TITLE, busy_address

    origin, path = app_url.split("/app", 1)[0], "/app"
    page.goto(origin + busy_address(path, "https://example.org/app"))
    assert page.title() == BUSY_TITLE
    with page.expect_navigation(timeout=15_000):
        page.get_by_role("button", name="Reload now").click()
    assert page.url == origin + busy_address(path, "https://example.org/app")
    page.goto(origin + busy_address(path, f"{path}?theta0_deg=45"))
    page.wait_for_url(f"{app_url}?theta0_deg=45", timeout=15_000)  # by itself, no click
    pt.wait_for_rendered(page)
    pt.settle(page)
    assert _value(page, "theta0") == pytest.approx(45.0, abs=1e-6)
    _no_errors(page_log)
