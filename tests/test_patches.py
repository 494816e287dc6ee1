"""``app.patches.release``: a served session's held changes leave as one PATCH-DOC."""
import asyncio
import weakref

from bokeh.document import Document
from bokeh.models import ColumnDataSource, Range1d
from bokeh.protocol import Protocol
from bokeh.server.connection import ServerConnection
from bokeh.server.contexts import BokehSessionContext
from bokeh.server.session import ServerSession

from app.patches import release


class Socket:
    def __init__(self):
        self.messages = []

    async def _written(self):
        return None

    def send_message(self, message):
        self.messages.append(message)
        return self._written()


class Connection:
    """A server connection (``bokeh.server.connection.ServerConnection``'s two members
    that sending uses) whose websocket records the messages."""

    def __init__(self):
        self.protocol, self._socket = Protocol(), Socket()

    send_patch_document = ServerConnection.send_patch_document


def served_document(io_loop=None):
    """A document with three models behind a server session with one connection (its
    callbacks run on ``io_loop``, when given)."""
    doc = Document()
    source, x, y = ColumnDataSource(data={"a": [1, 2]}), Range1d(0, 1), Range1d(0, 1)
    for model in (source, x, y):
        doc.add_root(model)
    session = ServerSession("s", doc, io_loop=io_loop)
    context = BokehSessionContext("s", None, doc)
    context._set_session(session)
    doc._session_context = weakref.ref(context)
    connection = Connection()
    session.subscribe(connection)
    return doc, session, connection, context, (source, x, y)


def changed(message) -> list:
    return sorted((e["kind"], e.get("attr", "")) for e in message.content["events"])


def test_held_changes_leave_in_one_message_per_connection():
    doc, session, connection, _context, (source, x, y) = served_document()

    def update():
        doc.hold("combine")
        source.data = {"a": [3, 4, 5]}
        x.start, x.end, y.start = -1.0, 2.0, -3.0
        x.start = -2.0  # combined with the first change of x.start
        assert release(doc) == 1
    asyncio.run(session.with_document_locked(update))
    [message] = connection._socket.messages
    assert message.header["msgtype"] == "PATCH-DOC"
    assert changed(message) == [("ColumnDataChanged", "data"), ("ModelChanged", "end"),
                                ("ModelChanged", "start"), ("ModelChanged", "start")]
    # ... and it reproduces the server's document in a replica of its former state
    replica = Document.from_json(doc.to_json())
    replica.get_model_by_id(x.id).start = 0.0
    message.apply_to_document(replica)
    assert replica.get_model_by_id(x.id).start == -2.0
    assert list(replica.get_model_by_id(source.id).data["a"]) == [3, 4, 5]
    assert doc.callbacks.hold_value is None


def test_python_callbacks_of_the_changed_properties_still_run():
    doc, session, _connection, _context, (_source, x, _y) = served_document()
    seen = []
    x.on_change("start", lambda attr, old, new: seen.append((old, new)))

    def update():
        doc.hold("combine")
        x.start = 5.0
        release(doc)
    asyncio.run(session.with_document_locked(update))
    assert seen == [(0, 5.0)]


def test_without_a_server_session_it_is_unhold():
    doc = Document()
    x = Range1d(0, 1)
    doc.add_root(x)
    events = []
    doc.on_change(events.append)
    doc.hold("combine")
    x.start, x.end = 1.0, 2.0
    assert release(doc) == 0
    assert len(events) == 2 and doc.callbacks.hold_value is None


def test_another_listener_on_the_document_gets_every_change_as_before():
    doc, session, connection, _context, (_source, x, _y) = served_document()
    events = []
    doc.on_change(events.append)

    def update():
        doc.hold("combine")
        x.start, x.end = 1.0, 2.0
        assert release(doc) == 0  # not batched: unhold() as before
    asyncio.run(session.with_document_locked(update))
    assert len(events) == 2 and len(connection._socket.messages) == 2


def test_a_hold_until_the_next_tick_sends_the_changes_then_in_one_message():
    from tornado.ioloop import IOLoop

    from app.patches import hold_until_next_tick

    async def main():
        doc, session, connection, _context, (source, x, y) = served_document(IOLoop.current())

        def change():
            assert hold_until_next_tick(doc)
            assert not hold_until_next_tick(doc)  # held already: the first hold sends
            x.start, y.end = 4.0, 5.0
            source.data = {"a": [7]}
        await session.with_document_locked(change)
        assert connection._socket.messages == [] and doc.callbacks.hold_value
        for _ in range(20):  # the next turn of the loop
            await asyncio.sleep(0.01)
            if connection._socket.messages:
                break
        return doc, connection
    doc, connection = asyncio.run(main())
    [message] = connection._socket.messages
    assert changed(message) == [("ColumnDataChanged", "data"), ("ModelChanged", "end"),
                                ("ModelChanged", "start")]
    assert doc.callbacks.hold_value is None


def test_no_hold_without_a_served_session():
    from app.patches import hold_until_next_tick

    doc = Document()
    assert not hold_until_next_tick(doc) and not hold_until_next_tick(None)
    assert doc.callbacks.hold_value is None


def test_a_change_of_the_controls_reaches_the_page_as_one_message():
    """The dashboard holds its page's reactions to a control (busy markers, readouts, the
    address bar, download names) until the next tick: one PATCH-DOC, not one per change."""
    import panel as pn
    from panel.io.state import set_curdoc
    from tornado.ioloop import IOLoop

    from app.views import Dashboard

    async def main():
        doc, session, connection, context, _models = served_document(IOLoop.current())
        context._request = type("Request", (), {"arguments": {}, "remote_ip": "127.0.0.1",
                                                "cookies": {}, "headers": {}})()
        built = []

        def build():
            with set_curdoc(doc):
                built.append(Dashboard())
                doc.add_root(pn.panel(built[0]).get_root(doc))
        await session.with_document_locked(build)
        page = built[0]
        pn.state._connected[doc] = True  # the browser's websocket is open (Panel's record)
        await asyncio.sleep(0.2)  # what the build sent
        connection._socket.messages.clear()
        seen = {}

        def move():
            with set_curdoc(doc):
                page.state.theta0 = 40.0
            seen["held"] = doc.callbacks.hold_value
            seen["sent"] = len(connection._socket.messages)
        await session.with_document_locked(move)
        for _ in range(50):  # the next turn of the loop
            await asyncio.sleep(0.01)
            if connection._socket.messages:
                break
        await asyncio.sleep(0.05)
        return seen, connection._socket.messages
    seen, messages = asyncio.run(main())
    assert seen["held"] == "combine" and seen["sent"] == 0, seen
    patches = [m for m in messages if m.header["msgtype"] == "PATCH-DOC"]
    # the slider's position and the trajectory download's name (theta0 is in it): without
    # the hold, each left as its own message
    assert len(patches) == 1, ([changed(m) for m in patches], seen)
    assert changed(patches[0]) == [("ModelChanged", "filename"), ("ModelChanged", "value")]


def test_kept_messages_leave_in_their_order_once_released():
    from app.patches import hold_patches

    async def main():
        doc, session, connection, _context, (source, x, y) = served_document()
        socket = connection._socket
        send_kept = hold_patches(doc)
        from bokeh.document.events import ModelChangedEvent

        first = connection.protocol.create("PATCH-DOC", [ModelChangedEvent(doc, x, "start", 5.0)])
        other = connection.protocol.create("OK", "1")
        await socket.send_message(other)  # not a patch, nothing kept before it: it goes
        await socket.send_message(first)
        await socket.send_message(other)  # behind a kept patch: it waits too
        assert socket.messages == [other]
        assert send_kept() == 2
        await asyncio.sleep(0.05)
        assert socket.messages == [other, first, other]
        assert "send_message" not in vars(socket)  # back to the plain socket
        assert hold_patches(Document())() == 0  # no server session: nothing kept
    asyncio.run(main())
