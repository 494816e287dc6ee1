"""``app.opening``: a page request gets a light page, the dashboard comes once opened; a
client without room in the page gate gets the busy page before any session is made. What a
visitor sees of a served page (one message per change, the dashboard arriving once
opened): tests/test_serving.py."""
import html
import logging
import types
import urllib.parse

import panel as pn
import pytest

from app.opening import (AUTO_RELOAD_JS, BACK_JS, BUSY_FILE, BUSY_HTML, BUSY_TITLE, build_steps,
                         admit_or_busy, busy_address, build_when_opened, loading_shell)
from app.pages import PageGate


def test_a_page_that_cannot_be_built_says_so_in_place(caplog):
    def make():
        raise RuntimeError("broken")
    shell = loading_shell()
    with caplog.at_level(logging.ERROR, logger="app.opening"):
        assert list(build_steps(None, shell, make)) == []  # no step after the failed one
    [alert] = shell.objects
    assert "page-failed" in alert.css_classes and "could not be built" in alert.object
    assert "broken" in caplog.text


def test_without_a_server_the_page_is_built_at_once():
    shell = loading_shell()
    page = pn.pane.Markdown("page")
    build_when_opened(shell, lambda: page)
    assert shell.objects == [page]


def test_the_busy_page_goes_back_and_says_it_is_busy():
    assert f"<title>{BUSY_TITLE}</title>" in BUSY_HTML
    assert f"<script>{AUTO_RELOAD_JS}</script>" in BUSY_HTML and BACK_JS in AUTO_RELOAD_JS
    assert f'onclick="{html.escape(BACK_JS)}"' in BUSY_HTML
    assert "token" not in BUSY_HTML  # no Bokeh session behind it


def test_the_served_busy_page_is_busy_html():
    """The file the server sends is ``BUSY_HTML``; after a change of the text, write it:
    ``python -c "from app.opening import BUSY_FILE as F, BUSY_HTML; F.write_text(BUSY_HTML)"``.
    """
    assert BUSY_FILE.read_text(encoding="utf-8") == BUSY_HTML


def test_the_busy_address_is_beside_the_app_and_carries_the_page_address():
    address = busy_address("/friction/app", "/friction/app?k_r=0.5&theta0=40")
    path, query = address.split("?", 1)
    assert path == "/friction/app/static/busy.html"  # Bokeh serves app/static there
    assert urllib.parse.parse_qs(query) == {"next": ["/friction/app?k_r=0.5&theta0=40"]}
    assert busy_address("/app/", "/app/").startswith("/app/static/busy.html?")


class _Request:
    """What the page gate and the busy address read of a page request."""
    remote_ip, uri = "10.0.0.9", "/app?F_N=2"


@pytest.fixture
def gate(monkeypatch):
    import app.pages

    gate = PageGate(max_unopened=1, window_s=60)
    monkeypatch.setattr(app.pages, "_GATE", gate)
    return gate


def _authorize(request=_Request):
    """Run ``admit_or_busy`` as Panel's page handler does: in the request's stand-in
    document, with the page's path."""
    from panel.io.state import set_curdoc

    doc = types.SimpleNamespace(session_context=types.SimpleNamespace(request=request))
    with set_curdoc(doc):
        return admit_or_busy({}, "/app")


def test_a_client_without_room_is_sent_to_the_busy_page_before_any_session(gate):
    assert _authorize() is True  # room: Panel builds the page ...
    assert gate.admit(_Request.remote_ip, "page 1")  # ... and the page script admits it
    assert _authorize() == busy_address("/app", "/app?F_N=2")  # no room: Panel redirects
    other = types.SimpleNamespace(remote_ip="10.0.0.10", uri="/app")
    assert _authorize(other) is True  # another client has its own room
    gate.opened(_Request.remote_ip, "page 1")
    assert _authorize() is True


def test_the_server_hooks_set_the_busy_gate_as_panels_authorize_callback(monkeypatch):
    import app.app_hooks as hooks

    monkeypatch.setattr(hooks, "start_warm_up", lambda: True)  # no rehearsal here
    monkeypatch.setattr(hooks, "install", lambda: True)
    monkeypatch.setattr(hooks, "quiet_diagnostics", lambda: False)  # Bokeh's global setting
    monkeypatch.setattr(pn.config, "authorize_callback", None)
    monkeypatch.setattr(pn.config, "design", None)  # set by the hook
    hooks.on_server_loaded(None)
    assert pn.config.authorize_callback is admit_or_busy


def test_has_room_agrees_with_admit():
    gate = PageGate(max_unopened=2, window_s=60)
    assert gate.has_room("a") and gate.admit("a", 1)
    assert gate.has_room("a") and gate.admit("a", 2)
    assert not gate.has_room("a") and not gate.admit("a", 3)
    assert gate.has_room("b")
    gate.opened("a", 1)
    assert gate.has_room("a")  # and the open earned credit
    assert gate.allowance("a") == 3


def _sources(doc) -> set[str]:
    from bokeh.models import ColumnDataSource
    return {m.name for m in doc.models if isinstance(m, ColumnDataSource)}


def test_a_served_page_leaves_its_support_views_and_its_mark_for_a_second_message(pool):
    """``app.opening`` sends a served page's models in two messages (two shorter holds of
    the event loop): the support tab's views, and the root's class that marks the page
    complete, come with the second."""
    from bokeh.document import Document

    from app.healthcheck import has_dashboard
    from app.views import Dashboard

    page = Dashboard()
    rest = page.in_two_parts()
    doc = Document()
    doc.add_root(pn.panel(page).get_root(doc))
    first = len(doc.models)
    assert "orbit" not in _sources(doc) and not has_dashboard(doc)
    # The controls come first.
    assert any("ctl-theta0" in (getattr(m, "css_classes", None) or ()) for m in doc.models)
    rest()
    total = len(doc.models)
    assert "orbit" in _sources(doc) and has_dashboard(doc)
    # Neither message carries most of the page.
    assert 0.15 * total < first < 0.6 * total, (first, total)


def test_a_page_built_at_once_is_whole(pool):
    """Without ``in_two_parts`` (notebooks, the offline pack, ``panel serve app/main.py``
    without a browser) the page has its views and its mark from the start."""
    from bokeh.document import Document

    from app.healthcheck import has_dashboard
    from app.views import Dashboard

    doc = Document()
    doc.add_root(pn.panel(Dashboard()).get_root(doc))
    assert "orbit" in _sources(doc) and has_dashboard(doc)


def test_the_rehearsal_builds_the_whole_page_and_computes_the_default_results(pool):
    from app.opening import rehearse

    assert rehearse() > 0
    # The default state's results, computed then (and kept for the first visitor).
    assert {"compute_support", "compute_uniform"} <= set(pool.calls), pool.calls


def test_a_rehearsal_that_fails_leaves_the_server_serving(monkeypatch, caplog):
    import app.app_hooks as hooks

    def broken():
        raise RuntimeError("no page")
    monkeypatch.setattr(hooks, "quiet_diagnostics", lambda: False)
    monkeypatch.setattr(hooks, "install", lambda *args: None)
    monkeypatch.setattr(hooks, "start_warm_up", lambda: False)
    monkeypatch.setattr(hooks, "rehearse", broken)
    monkeypatch.setattr(pn.config, "design", None)  # set by the hook
    with caplog.at_level(logging.ERROR, logger="app.app_hooks"):
        hooks.on_server_loaded(None)
    assert "could not be rehearsed" in caplog.text and "no page" in caplog.text


def _served_doc():
    from fakes import served_document
    return served_document()


def _busy(flag: bool) -> None:
    """As Panel marks it while it processes an event from a browser."""
    from panel.util import edit_readonly
    with edit_readonly(pn.state):
        pn.state.busy = flag


def test_an_answer_begun_while_a_result_is_applied_leaves_the_page_unheld():
    """A browser event processed while the page is held by another change (a result
    applied) must not leave the page held once both are done: Panel's hold restores the
    hold it found, and a page held for good never sends another change."""
    from panel.io.state import set_curdoc

    from app.opening import answer_each_event_in_one_message

    answer_each_event_in_one_message()
    doc = _served_doc()
    with set_curdoc(doc):
        result = pn.io.hold(doc)
        result.__enter__()
        _busy(True)  # an event from the browser begins
        result.__exit__(None, None, None)  # the result's message leaves
        _busy(False)  # the event is answered
    assert not doc.callbacks.hold_value


def test_an_answer_is_held_until_the_event_is_processed():
    from panel.io.state import set_curdoc

    from app.opening import answer_each_event_in_one_message

    answer_each_event_in_one_message()
    doc = _served_doc()
    with set_curdoc(doc):
        _busy(True)
        assert doc.callbacks.hold_value  # the answer's changes wait for one message
        _busy(False)
    assert not doc.callbacks.hold_value


def test_a_page_opened_on_another_tab_is_sent_whole(pool):
    """Figures added to a hidden tab later are never laid out (BokehJS then fails on them
    as the shown tab's player plays): a page opened on another tab goes in one message."""
    from app.state import ExplorerState
    from app.views import Dashboard

    assert Dashboard(ExplorerState(tab="array")).in_two_parts() is None


def test_the_light_page_says_how_many_pages_are_built_before_it():
    from app.opening import opening_html

    assert "Opening the explorer" in opening_html() and "other page" not in opening_html()
    assert "building 1 other page first." in opening_html(1, None)
    assert "building 12 other pages first (about 20 s)." in opening_html(12, 19.6)
    assert "(about 1 s)" in opening_html(1, 0.2)  # never "about 0 s"
    assert opening_html(3, 4.0).startswith('<span role="status">')


def test_a_waiting_page_shows_its_place_on_its_own_documents_next_turn():
    from app.opening import _tell_waiting, opening_html

    class Doc:
        ticks = []

        def add_next_tick_callback(self, callback):
            self.ticks.append(callback)

    shell, doc = loading_shell(), Doc()
    _tell_waiting(doc, shell, 4, 7.0)
    [text] = [p for p in shell.select(pn.pane.HTML) if "opening-text" in p.css_classes]
    assert text.object == opening_html()  # nothing changed outside the document's turn
    [tick] = doc.ticks
    tick()
    assert text.object == opening_html(4, 7.0)
