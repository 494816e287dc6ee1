"""Edits of a served page's Bokeh figures made from a watcher, with its document locked."""
from __future__ import annotations

import panel as pn


def locked(draw, model) -> None:
    """Edit the Bokeh figures with their document locked: a text input's change reaches
    the watchers outside Bokeh's lock (an edit there raises in the server), so with a
    server the edit waits for the next tick, which Bokeh runs locked; its changes leave
    through Panel's hold as one message, in order with the page's other updates.

    The document is the one ``model`` (a figure ``draw`` edits) belongs to, not
    ``pn.state.curdoc``: a watcher may run in a context that names another session's
    document (a callback scheduled while that session was current), whose next tick
    never comes once it has closed, and the edit would be lost. Before the figure is
    in a served document, ``draw`` runs at once."""
    doc = model.document
    if doc is not None and doc.session_context is not None:
        def held():
            with pn.io.hold(doc):
                draw()
        doc.add_next_tick_callback(held)
    else:
        draw()
