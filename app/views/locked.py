"""Edits of a served page's Bokeh figures made from a watcher, with its document locked."""
from __future__ import annotations

import panel as pn


def locked(draw) -> None:
    """Edit the Bokeh figures with the session's document locked: a text input's change
    reaches the watchers outside Bokeh's lock (an edit there raises in the server), so
    with a server the edit waits for the next tick, which Bokeh runs locked; its changes
    leave through Panel's hold as one message, in order with the page's other updates."""
    doc = pn.state.curdoc
    if doc is not None and doc.session_context is not None:
        def held():
            with pn.io.hold(doc):
                draw()
        doc.add_next_tick_callback(held)
    else:
        draw()
