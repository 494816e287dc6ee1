"""A session's held document changes sent to its browser as one message.

Bokeh's ``Document.unhold()`` hands the held changes to the server session one at a time,
and the session sends each as its own ``PATCH-DOC`` message; every message costs the
server a pass over all of the document's models (``Serializer(references=...)``: about
400 models on this page) besides its own websocket frames. One update of the Support tab
changes ~30 properties (sources, ranges, readouts), so a slider move cost ~30 such passes
per session: measured in ``benchmarks/bench_dashboard.py`` ("one message per change" vs
"one message").

``release(doc)`` ends a hold begun with ``doc.hold(...)`` like ``unhold()``, but sends the
held changes of a served session in one ``PATCH-DOC`` per connection, written through
Bokeh's own locked write path (the session's pending writes, awaited before its document
lock is released), so ordering with the session's other messages is kept. Anything it
cannot batch -- no server session, another listener on the document, a change made by
the session itself -- goes through ``unhold()`` as before.
"""
from __future__ import annotations

import logging

from bokeh.document.callbacks import invoke_with_curdoc
from bokeh.document.events import DocumentPatchedEvent

log = logging.getLogger(__name__)


def _batchable_session(doc):
    """The server session whose pending writes take ``doc``'s held changes, or None."""
    context = getattr(doc, "session_context", None)
    session = getattr(context, "_session", None)
    callbacks = doc.callbacks
    if (session is None or getattr(session, "_pending_writes", None) is None
            or tuple(callbacks._change_callbacks) != (session,)):
        return None
    return session


def release(doc) -> int:
    """End ``doc``'s hold and send what it held; the number of ``PATCH-DOC`` messages
    sent as one batch per connection (0: handed to ``unhold()``)."""
    callbacks = doc.callbacks
    session = _batchable_session(doc) if callbacks.hold_value else None
    if session is None:
        doc.unhold()
        return 0
    held, callbacks._held_events = list(callbacks._held_events), []
    callbacks._hold = None
    batch = [e for e in held if isinstance(e, DocumentPatchedEvent) and e.setter is not session]
    if not batch:
        for event in held:
            callbacks.trigger_on_change(event)
        return 0
    for event in batch:  # Python callbacks of the changed properties, as unhold() runs them
        if event.callback_invoker is not None:
            invoke_with_curdoc(doc, event.callback_invoker)
    sent = 0
    for connection in list(session._subscribed_connections):
        message = connection.protocol.create("PATCH-DOC", batch)
        session._pending_writes.append(connection._socket.send_message(message))
        sent += 1
    for event in held:
        if event not in batch:
            callbacks.trigger_on_change(event)
    return sent


def hold_until_next_tick(doc, then=None) -> bool:
    """Hold ``doc``'s changes until the event loop's next turn, then ``release`` them (and
    call ``then()`` right after, in the same turn, when a hold was begun).

    Called as the first reaction to a change of the controls (``Dashboard``): a slider move
    changes ~15 properties across the views (busy markers, readouts, the address bar,
    download names) before any result arrives, and Panel would send each as its own
    ``PATCH-DOC`` (one pass over every model of the page each). Held, they leave together.
    Nothing is held when ``doc`` is not a served session's or is held already (a result
    being applied: its holder releases it). Returns whether a hold was begun.
    """
    if doc is None or getattr(doc, "session_context", None) is None \
            or doc.callbacks.hold_value:
        return False

    def later():
        if doc.callbacks.hold_value:
            release(doc)
        if then is not None:
            then()
    try:
        # Before the hold: a held document holds the news of a new callback too (Bokeh's
        # ``SessionCallbackAdded``), and the release would never be scheduled.
        doc.add_next_tick_callback(later)
    except Exception:  # the session is closing: nothing will be sent anyway
        return False
    doc.hold("combine")
    return True


async def _not_yet():
    return None


def hold_patches(doc):
    """Keep back the ``PATCH-DOC`` messages of ``doc``'s server session from its open
    connections until the returned function is called, which sends them in their order
    (as one task, so later messages wait behind them) and stops keeping them back.

    Unlike a document hold this leaves the document alone: changes from the browser and
    the session's callbacks (Panel's debounce runs in one) go on as usual, only their
    messages wait. Returns a function that does nothing when there is no server session.
    """
    session = getattr(getattr(doc, "session_context", None), "_session", None)
    sockets = [getattr(c, "_socket", None)
               for c in getattr(session, "_subscribed_connections", ())]
    sockets = [s for s in sockets if s is not None and "send_message" not in vars(s)]
    queues = []
    for socket in sockets:
        queue, send = [], socket.send_message

        def keep(message, queue=queue, send=send):
            if queue or message.header.get("msgtype") == "PATCH-DOC":
                queue.append(message)
                return _not_yet()
            return send(message)
        socket.send_message = keep
        queues.append((socket, queue, send))

    async def drain(socket, queue, send):
        while queue:
            await send(queue[0])
            queue.pop(0)
        vars(socket).pop("send_message", None)

    def send_kept() -> int:
        """Send what was kept back; the number of messages."""
        import asyncio

        kept = sum(len(queue) for _, queue, _ in queues)
        for socket, queue, send in queues:
            if queue:
                asyncio.ensure_future(drain(socket, queue, send))
            else:
                vars(socket).pop("send_message", None)
        queues.clear()
        return kept
    return send_kept
