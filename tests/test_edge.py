"""``app.edge``: the server's guards run only on the tested stack, and each of these canary
tests fails the day an internal a guard relies on changes (then: re-check the reproducer
in ``docs/upstream/``, and delete the guard if the bug is fixed upstream). What the guards
do for a visitor is checked on a served page (tests/test_url_served.py,
tests/browser/test_hostile_url.py)."""
from __future__ import annotations

import inspect
import logging
from pathlib import Path

from app import edge

ROOT = Path(__file__).resolve().parents[1]


def test_the_installed_stack_is_the_tested_one():
    """A new Panel, Bokeh or Tornado: run the canaries below and the browser tests on it,
    then move ``TESTED``."""
    assert edge.versions() == edge.TESTED
    assert edge.untested_note() is None


def test_on_another_stack_the_server_says_so_in_one_line_and_installs_nothing(
        monkeypatch, caplog):
    from tornado.web import RequestHandler

    monkeypatch.setattr(edge, "versions", lambda: dict(edge.TESTED, panel="9.9.9"))
    installed = []
    for name in ("add_security_headers", "keep_queued_writes"):
        monkeypatch.setattr(edge, name, lambda *args, name=name: installed.append(name))
    with caplog.at_level(logging.WARNING, logger="app.edge"):
        assert edge.install() is False
    assert installed == []
    [record] = caplog.records
    assert "9.9.9" in record.message and "1.9.4" in record.message
    assert "\n" not in record.message
    assert not edge.on_tested_stack()
    assert RequestHandler is not None


def test_canary_default_headers_are_set_for_every_response():
    """Guard 1 relies on Tornado calling ``set_default_headers`` from ``clear`` (on each
    handler's creation and before an error page), and on the page and websocket handlers
    not overriding it."""
    from panel.io.server import DocHandler, WSHandler
    from tornado.web import RequestHandler

    assert "self.set_default_headers()" in inspect.getsource(RequestHandler.clear)
    assert "self.clear()" in inspect.getsource(RequestHandler.__init__)
    assert "self.clear()" in inspect.getsource(RequestHandler.send_error)
    for handler in (DocHandler, WSHandler):
        overrides = [c for c in handler.__mro__
                     if "set_default_headers" in vars(c) and c is not RequestHandler]
        assert overrides == [] or all(
            getattr(vars(c)["set_default_headers"], "_security_headers", False)
            for c in overrides), overrides


def test_canary_tornado_reads_control_characters_as_the_guard_does():
    """Guard 1 drops a ``bokeh-session-id`` that Tornado's ``get_argument`` makes empty."""
    from tornado.web import RequestHandler

    assert RequestHandler._remove_control_chars_regex.pattern == edge.CONTROL_CHARS.pattern


def test_canary_panels_text_views_make_their_container_when_drawn():
    """Guard 2 defines ``container`` on the prototype of Panel's markup view; it works
    while Panel's bundle assigns it in ``render`` and declares no class field (which
    would shadow the prototype's property)."""
    import panel
    from panel.models.markup import HTML

    assert HTML.__qualified_model__ == "panel.models.markup.HTML"
    bundle = (Path(panel.__file__).parent / "dist" / "panel.js").read_text(encoding="utf-8")
    start = bundle.index("class PanelMarkupView extends")
    constructor = bundle[start:bundle.index("}", start)]
    assert "container" not in constructor
    view = bundle[start:bundle.index("\n    }\n", start)]
    assert "this.container = (0, dom_1.div)();" in view


def _changes_written(dispatch) -> tuple[int, int]:
    """The reproducer's two queued changes with ``dispatch`` as Panel's writing task:
    (written, left queued)."""
    import asyncio
    import runpy

    from panel.io import document

    reproducer = runpy.run_path(str(ROOT / "docs" / "upstream" /
                                    "write_queue_strands_last_change.py"))
    saved = document._dispatch_msgs, dict(document.extra_socket_handlers)
    document._dispatch_msgs = dispatch
    try:
        return asyncio.run(reproducer["changes_written"]())
    finally:
        document._dispatch_msgs = saved[0]
        document.extra_socket_handlers.clear()
        document.extra_socket_handlers.update(saved[1])


def test_canary_panel_leaves_a_change_queued_as_the_previous_write_ends():
    """Guard 3's bug: the day Panel writes the second change, delete the guard."""
    from panel.io import document

    assert _changes_written(inspect.unwrap(document._dispatch_msgs)) == (1, 1)


def test_with_guard_3_every_queued_change_is_written(monkeypatch):
    from panel.io import document

    monkeypatch.setattr(document, "_dispatch_msgs", inspect.unwrap(document._dispatch_msgs))
    edge.keep_queued_writes()
    guarded = document._dispatch_msgs
    assert guarded._keeps_queue
    edge.keep_queued_writes()  # once per process
    assert document._dispatch_msgs is guarded
    assert _changes_written(guarded) == (2, 0)


def test_the_page_guards_and_the_bokehjs_fix_are_in_the_page_on_the_tested_stack(monkeypatch):
    from bokeh.document import Document
    from bokeh.models import CustomJS

    doc = Document()
    edge.guard_markup_views(doc)
    callbacks = doc.callbacks.js_event_callbacks.get("document_ready", [])
    assert [c.code for c in callbacks if isinstance(c, CustomJS)] == [edge.page_js()]
    code = edge.page_js()
    assert code.startswith(edge.MARKUP_GUARD_JS)
    # The offline page's BokehJS fix, the same file, applied to the BokehJS version tested.
    assert edge.BOKEH_FIX_JS.read_text(encoding="utf-8") in code
    assert f'MicropillarBokehFix.apply(Bokeh, "{edge.TESTED["bokeh"]}");' in code
    monkeypatch.setattr(edge, "versions", lambda: dict(edge.TESTED, bokeh="9.9.9"))
    other = Document()
    edge.guard_markup_views(other)
    assert not other.callbacks.js_event_callbacks.get("document_ready")
