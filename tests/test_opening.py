"""``app.opening``: a page request gets a light page, the dashboard comes once opened; a
client without room in the page gate gets the busy page before any session is made. What a
visitor sees of a served page (one message per change, the dashboard arriving once
opened): tests/test_serving.py."""
import asyncio
import logging

import panel as pn
import pytest

from app.opening import (AUTO_RELOAD_JS, BUSY_HTML, BUSY_TITLE, _build, build_when_opened,
                         loading_shell)
from app.pages import PageGate


def test_a_page_that_cannot_be_built_says_so_in_place(caplog):
    def make():
        raise RuntimeError("broken")
    shell = loading_shell()
    with caplog.at_level(logging.ERROR, logger="app.opening"):
        _build(shell, make)
    [alert] = shell.objects
    assert "page-failed" in alert.css_classes and "could not be built" in alert.object
    assert "broken" in caplog.text


def test_without_a_server_the_page_is_built_at_once():
    shell = loading_shell()
    page = pn.pane.Markdown("page")
    build_when_opened(shell, lambda: page)
    assert shell.objects == [page]


def test_the_busy_page_reloads_itself_and_says_it_is_busy():
    assert f"<title>{BUSY_TITLE}</title>" in BUSY_HTML
    assert f"<script>{AUTO_RELOAD_JS}</script>" in BUSY_HTML
    assert 'onclick="window.location.reload()"' in BUSY_HTML
    assert "token" not in BUSY_HTML  # no Bokeh session behind it


class _Request:
    """What Panel and the page read of a page request."""
    remote_ip, arguments, cookies, headers = "10.0.0.9", {}, {}, {}


class _Handler:
    def __init__(self):
        self.request, self.headers, self.body = _Request(), {}, ""

    def set_header(self, name, value):
        self.headers[name] = value

    def write(self, text):
        self.body += text


@pytest.fixture
def wrapped_page_handler(monkeypatch):
    """Panel's page handler with a stand-in ``get`` (records the pages it would build),
    wrapped by the server hook; the page gate a fresh one."""
    from panel.io.server import DocHandler

    import app.pages
    from app.edge import answer_busy_before_building
    from app.opening import BUSY_HTML

    built = []

    async def get(self, *args, **kwargs):
        built.append(self)
    monkeypatch.setattr(DocHandler, "get", get)
    gate = PageGate(max_unopened=1, window_s=60)
    monkeypatch.setattr(app.pages, "_GATE", gate)
    answer_busy_before_building(BUSY_HTML, lambda ip: app.pages.page_gate().has_room(ip))
    return DocHandler.get, gate, built


def test_a_client_without_room_gets_the_busy_page_before_any_session(wrapped_page_handler):
    get, gate, built = wrapped_page_handler
    first = _Handler()
    asyncio.run(get(first))
    assert built == [first] and first.body == ""  # room: Panel builds the page
    assert gate.admit(_Request.remote_ip, "page 1")  # ... and the page script admits it
    second = _Handler()
    asyncio.run(get(second))
    assert built == [first]  # no session, no page script
    assert second.body == BUSY_HTML
    assert second.headers["Content-Type"].startswith("text/html")
    assert second.headers["Cache-Control"] == "no-store"
    gate.opened(_Request.remote_ip, "page 1")
    third = _Handler()
    asyncio.run(get(third))
    assert built == [first, third]


def test_has_room_agrees_with_admit():
    gate = PageGate(max_unopened=2, window_s=60)
    assert gate.has_room("a") and gate.admit("a", 1)
    assert gate.has_room("a") and gate.admit("a", 2)
    assert not gate.has_room("a") and not gate.admit("a", 3)
    assert gate.has_room("b")
    gate.opened("a", 1)
    assert gate.has_room("a")  # and the open earned credit
    assert gate.allowance("a") == 3
