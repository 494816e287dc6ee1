"""``app.opening``: a page request gets a light page, the dashboard comes once opened; a
client without room in the page gate gets the busy page before any session is made."""
import asyncio
import logging

import panel as pn
import pytest
from panel.io.state import set_curdoc

from app.opening import (AUTO_RELOAD_JS, BUSY_HTML, BUSY_TITLE, build_when_opened,
                         loading_shell)
from app.pages import PageGate
from tests.test_patches import changed, served_document


def _classes(message) -> set:
    """CSS classes of the models a message carries."""
    found = set()

    def walk(node):
        if isinstance(node, dict):
            found.update(node.get("css_classes") or ())
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)
    walk(message.content)
    return found


async def _next_turns(connection, turns: int = 50):
    for _ in range(turns):
        await asyncio.sleep(0.01)
        if connection._socket.messages:
            break
    await asyncio.sleep(0.05)


async def _requested(make):
    """A page request served as the page script does it (a light page with
    ``build_when_opened(make)``): (doc, session, connection, shell, context); keep the
    context while the page is used (the document holds it by a weak reference)."""
    from tornado.ioloop import IOLoop

    doc, session, connection, context, _models = served_document(IOLoop.current())
    context._request = _Request()
    shell = loading_shell()

    def request():
        with set_curdoc(doc):
            doc.add_root(shell.get_root(doc))
            build_when_opened(shell, make, doc)
    await session.with_document_locked(request)
    return doc, session, connection, shell, context


async def _opened(doc, session, connection):
    """The browser's websocket opens and its document_ready arrives; the turns after."""
    pn.state._connected[doc] = True
    await asyncio.sleep(0.05)
    connection._socket.messages.clear()
    await session.with_document_locked(lambda: pn.state._on_load(doc))
    await _next_turns(connection)


def _open(make):
    """A served light page with ``build_when_opened(make)``; what each step did."""
    seen = {}

    async def main():
        doc, session, connection, shell, _context = await _requested(make)
        seen["shell after request"] = list(shell.objects)
        pn.state._connected[doc] = True  # the browser's websocket is open
        await asyncio.sleep(0.05)
        connection._socket.messages.clear()

        def ready():  # the browser's document_ready
            pn.state._on_load(doc)
            seen["shell after onload"] = list(shell.objects)
            seen["sent in the onload turn"] = len(connection._socket.messages)
        await session.with_document_locked(ready)
        await _next_turns(connection)
        seen["shell"] = list(shell.objects)
        seen["messages"] = [m for m in connection._socket.messages
                            if m.header["msgtype"] == "PATCH-DOC"]
        return seen
    return asyncio.run(main())


def test_the_dashboard_is_built_when_the_page_is_opened_and_sent_in_one_message():
    built = []

    def make():
        built.append(pn.Column(pn.pane.Markdown("the page"), css_classes=["dashboard"]))
        return built[-1]
    seen = _open(make)
    [spinner_row] = seen["shell after request"]
    assert len(built) == 1  # built once, when opened
    assert seen["shell after onload"] == [spinner_row]  # its models: a later turn
    assert seen["sent in the onload turn"] == 0
    assert seen["shell"] == built
    [message] = seen["messages"]  # the page's models leave together
    assert "dashboard" in _classes(message)
    assert ("ModelChanged", "children") in changed(message)


def test_nothing_is_built_for_a_page_never_opened():
    built = []

    async def main():
        doc, _session, _connection, _shell, _context = await _requested(lambda: built.append(1))
        await asyncio.sleep(0.1)
        pn.state._onload.pop(doc, None)  # the session ends unopened
    asyncio.run(main())
    assert built == []


def test_a_page_that_cannot_be_built_says_so_in_place(caplog):
    def make():
        raise RuntimeError("broken")
    with caplog.at_level(logging.ERROR, logger="app.opening"):
        seen = _open(make)
    [alert] = seen["shell"]
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
    from app.app_hooks import answer_busy_before_building

    built = []

    async def get(self, *args, **kwargs):
        built.append(self)
    monkeypatch.setattr(DocHandler, "get", get)
    gate = PageGate(max_unopened=1, window_s=60)
    monkeypatch.setattr(app.pages, "_GATE", gate)
    answer_busy_before_building()
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


class _Page(pn.viewable.Viewer):
    """A page that says when it has been drawn (as the dashboard does)."""

    def __init__(self, **params):
        super().__init__(**params)
        self.text = pn.pane.Markdown("before", css_classes=["dashboard"])
        self.callbacks = []

    def __panel__(self):
        return pn.Column(self.text)

    def when_shown(self, callback):
        self.callbacks.append(callback)


def test_updates_wait_until_the_browser_has_drawn_the_page():
    """BokehJS fails on a change reaching a view it has built but not drawn yet: after
    the page, its updates wait for the page's word that it is drawn."""
    page = _Page()

    async def main():
        doc, session, connection, _shell, _context = await _requested(lambda: page)
        await _opened(doc, session, connection)
        sent_page = list(connection._socket.messages)

        def update():
            with set_curdoc(doc):
                page.text.object = "after"
        await session.with_document_locked(update)
        await asyncio.sleep(0.1)
        kept = len(connection._socket.messages) - len(sent_page)
        [shown] = page.callbacks
        await session.with_document_locked(shown)
        await asyncio.sleep(0.1)
        return sent_page, kept, connection._socket.messages[len(sent_page):]
    sent_page, kept, after = asyncio.run(main())
    assert len(sent_page) == 1 and "dashboard" in _classes(sent_page[0])
    assert kept == 0  # the update waited ...
    [message] = after  # ... until the page was drawn
    assert message.header["msgtype"] == "PATCH-DOC" and "after" in str(message.content)


def test_the_dashboard_says_when_the_browser_has_drawn_it():
    from app.views import Dashboard

    page, calls = Dashboard(), []
    page.when_shown(lambda: calls.append(1))
    page.behaviour.shown = 1  # as the page's behaviour component does once drawn
    page.behaviour.shown = 2  # drawn again (a tab moved): said once
    assert calls == [1]


def test_the_light_page_guards_panels_text_views_before_the_dashboard_arrives():
    """Installed with the light page (its document_ready), so it is in place before any
    view of the dashboard exists; the browser tests exercise it (a hidden tab's spinner)."""
    from bokeh.document import Document
    from bokeh.models import CustomJS

    from app.opening import MARKUP_GUARD_JS

    doc = Document()
    with set_curdoc(doc):
        build_when_opened(loading_shell(), lambda: None, doc)
    callbacks = doc.callbacks.js_event_callbacks.get("document_ready", [])
    assert any(isinstance(c, CustomJS) and c.code == MARKUP_GUARD_JS for c in callbacks)
    assert 'Object.defineProperty(base, "container"' in MARKUP_GUARD_JS
    pn.state._onload.pop(doc, None)


@pytest.mark.parametrize("connected", [True, False])
def test_a_page_never_said_drawn_gets_its_updates_after_a_while(monkeypatch, caplog, connected):
    """The browser's word may never come (a client without the page's code, a tab in the
    background): the updates go after ``SHOWN_WITHIN_S``, with a warning only while the
    page is still open (the health check closes its page at once)."""
    import app.opening

    monkeypatch.setattr(app.opening, "SHOWN_WITHIN_S", 0.1)
    page = _Page()

    async def main():
        doc, session, connection, _shell, _context = await _requested(lambda: page)
        await _opened(doc, session, connection)
        if not connected:
            session.unsubscribe(connection)
        sent = len(connection._socket.messages)

        def update():
            with set_curdoc(doc):
                page.text.object = "after"
        await session.with_document_locked(update)
        await asyncio.sleep(0.4)
        return sent, connection._socket.messages[sent:]
    with caplog.at_level(logging.WARNING, logger="app.opening"):
        sent, after = asyncio.run(main())
    assert ("did not say" in caplog.text) == connected
    if connected:
        [message] = after
        assert "after" in str(message.content)
