"""Panel: a change queued while the websocket is busy, in the turn in which the previous
queued write ends, is not written until the document's next change.

Panel 1.9.4 (Bokeh 3.9.2). When Panel's hold (``unlocked``) ends while a write is under
way, it serialises the changes into a queue (``schedule_write_events``: ``_WRITE_MSGS``,
flag ``_WRITE_BLOCK``) and starts a task (``_dispatch_msgs``) that writes the queue. That
task returns at once if the flag is cleared; the task of the previous write clears it once
its write has ended. So a change queued in the turn in which that write ends gets a task
that runs after the flag was cleared, finds no flag, and returns: the change stays queued
until the next change starts another task. Expected: every queued change written.

Seen in this project's dashboard under a class's load (30 sessions, each dragging θ₀ over
four positions): the final position of ~1 drag in 500 stayed on the server for 30 s, the
page showing the previous one; a trace found each lost message queued and its task
returned without writing.

Run: ``python docs/upstream/write_queue_strands_last_change.py``. It needs no server: a
stand-in websocket (Panel's ``extra_socket_handlers``) whose writes end when the script
says; a first change is queued and written, and the second is queued in the turn its write
ends. Here (2026-11-28): reproduced, 1 of 2 changes written, 1 left queued.

Panel 1.10.0 (read, not run: it needs Python 3.12) queues the events instead of their
messages (``_WRITE_EVENTS``), but its task still returns at once when the flag is cleared
and clears it after its own writes, so the race is the same. Panel's main branch (read
2026-11-28) drains the queue in a loop until it is empty and has a test for a batch
arriving while the first is written: once released, this script and the guard go.

Worked around in this project: ``app/edge.py`` (``keep_queued_writes``: the task writes
what it finds queued), on the tested stack only; ``tests/test_edge.py`` runs this scenario
with and without it.
"""
import asyncio

import bokeh
import panel as pn
from bokeh.document import Document
from bokeh.document.events import ModelChangedEvent
from bokeh.models import Div
from bokeh.protocol import Protocol
from panel.io import document as panel_document


class Socket:
    """A websocket whose writes end when ``end_writes`` is called."""

    def __init__(self):
        self.written, self.pending = [], []

    def end_writes(self):
        for write in self.pending:
            write.set_result(None)
        self.pending = []


class Connection:
    def __init__(self):
        self._socket = Socket()
        self.protocol = Protocol()


def write(connection, msg=None, events=None):
    done = asyncio.get_running_loop().create_future()
    connection._socket.written.append(msg)
    connection._socket.pending.append(done)
    return [done]


async def changes_written() -> tuple[int, int]:
    """(changes written, changes left queued) of two queued changes of one document."""
    panel_document.extra_socket_handlers[Socket] = write
    doc = Document()
    div = Div(text="0")
    doc.add_root(div)
    connection = Connection()

    def change(text):
        div.text = text
        panel_document.schedule_write_events(
            doc, [connection], [ModelChangedEvent(doc, div, "text", text)])

    change("first")
    await asyncio.sleep(0.01)  # its task has written it; the write is under way
    connection._socket.end_writes()
    change("last")  # queued in the turn the first write ends
    await asyncio.sleep(0.1)
    connection._socket.end_writes()
    await asyncio.sleep(0.01)
    queued = sum(len(m) for m in panel_document._WRITE_MSGS.get(doc, {}).values())
    return len(connection._socket.written), queued


def main() -> None:
    written, queued = asyncio.run(changes_written())
    print(f"Panel {pn.__version__}, Bokeh {bokeh.__version__}: 2 changes queued, "
          f"{written} written, {queued} left queued")
    print("REPRODUCED: the change queued as the previous write ended was not written"
          if queued else "not reproduced: every queued change was written")


if __name__ == "__main__":
    main()
