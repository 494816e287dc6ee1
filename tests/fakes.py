"""Stand-ins for the server's work pool (``app.jobs.WorkPool``) in tests without workers, and
for a served session's document."""
from __future__ import annotations

import concurrent.futures as cf


class InProcessPool:
    """Runs every job here and now, so patches of ``app.worker`` take effect; records the
    names of the functions it ran."""

    def __init__(self):
        self.calls = []

    def session_id(self):
        return 0

    def submit(self, lane, key, fn, *args, **options):
        self.calls.append(fn.__name__)
        future = cf.Future()
        try:
            future.set_result(fn(*args))
        except Exception as exc:
            future.set_exception(exc)
        return future


def served_document():
    """A document as a server's session has it (Bokeh keeps its session context behind a
    weak reference: a callable; Panel reads the request's arguments), with Panel told that
    this thread is the event loop's."""
    import threading
    from types import SimpleNamespace

    import panel as pn
    from bokeh.document import Document
    from panel.io.state import set_curdoc

    request = SimpleNamespace(arguments={}, headers={}, cookies={})
    doc, context = Document(), SimpleNamespace(id="a served session", request=request)
    doc._session_context = lambda: context
    with set_curdoc(doc):
        pn.state._thread_id = threading.get_ident()
    return doc
