"""What a visitor's browser receives from the served dashboard (``slow``; loopback only):
the page arrives once opened, and each step of an update -- the answer to a slider move, a
result -- arrives as one message, in order (a message naming a model the page does not
have yet would stop the page). Seen from a protocol-level browser stand-in
(``benchmarks/load_client.py``), which applies every message to its copy of the page as
BokehJS does, and fails on a model it does not know."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
pytestmark = [pytest.mark.slow, pytest.mark.timeout(600)]


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``panel serve app`` on a free loopback port: (base URL, log path)."""
    from browser.serving import ServerError, serve_app

    log = tmp_path_factory.mktemp("serving") / "panel-serve.log"
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("PYTHONPATH", path)
        try:
            with serve_app(log, timeout_s=90.0) as base:
                yield base, log
        except ServerError as error:
            pytest.fail(str(error), pytrace=False)


#: Run in ``benchmarks/`` (the client is a benchmark's module): open a page, wait for its
#: first plot and a quiet moment, move θ₀ and wait until the readout shows it and two
#: quiet seconds more; print the messages received after the move as
#: [[seconds after, [[kind, attribute], ...]], ...] and the client's errors, as JSON.
_MOVE = """
import asyncio, json, sys, time
import load_client as lc

async def main(base, degrees):
    session = lc.Session(0, base)
    await session.open()
    await session.first_plot()
    await asyncio.sleep(2.0)
    before, sent = session.patches, time.perf_counter()
    await session._set("theta0", degrees)
    deadline = sent + 60
    while not session._readout_shows(degrees) and time.perf_counter() < deadline \\
            and not session.errors:
        await asyncio.sleep(0.05)
    await asyncio.sleep(2.0)
    count = session.patches - before
    received = [(t - sent, events) for t, events in list(session.recent)[-count:]] \\
        if count else []
    errors = list(session.errors)
    if not session._readout_shows(degrees):
        errors.append(f"the readout never showed theta0 = {degrees:g}")
    session.socket.close()
    print(json.dumps([received, errors]))

asyncio.run(main(sys.argv[1], float(sys.argv[2])))
"""


def _moved(base: str, degrees: float = 33.0) -> tuple[list, list]:
    done = subprocess.run([sys.executable, "-c", _MOVE, base, str(degrees)],
                          cwd=ROOT / "benchmarks", capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    received, errors = json.loads(done.stdout.strip().splitlines()[-1])
    return received, errors


def test_a_slider_move_reaches_the_page_in_one_message(served):
    base, log = served
    received, errors = _moved(base)
    assert errors == [], errors
    # A move of theta0 (the uniform array does not depend on it) is answered by one
    # message: the orbit's new data with the rest of its result (the other figures'
    # sources, ranges, the readouts, the headline) and the address bar's new state.
    assert len(received) == 1, received
    events = received[0][1]
    assert sum(kind == "ColumnDataChanged" for kind, _ in events) >= 5, events
    assert len(events) >= 15, events
    assert ["ModelChanged", "search"] in events, events
    text = log.read_text(encoding="utf-8", errors="replace")
    assert "Traceback" not in text and "UnknownReferenceError" not in text


#: Run in ``benchmarks/``: open a page and print, for each message the server sent once
#: the page said it was ready until the dashboard was complete, the number of models it
#: brought and whether it brought the orbit's source and the dashboard's mark, as JSON.
_OPEN = """
import asyncio, json, sys
import load_client as lc

async def main(base):
    session = lc.Session(0, base)
    received = []
    read = session._read

    async def recording():
        message = await read()
        if message is not None and message.msgtype == "PATCH-DOC" and session.doc is not None:
            text = json.dumps(message.content)
            received.append([text.count('"type": "object"'), '"name": "orbit"' in text,
                             '["dashboard"]' in text])
        return message
    session._read = recording
    await session.open()
    session.socket.close()
    print(json.dumps(received))

asyncio.run(main(sys.argv[1]))
"""


def test_an_opened_page_arrives_in_two_parts_the_support_views_second(served):
    """``app.opening``: the dashboard's models leave in two messages on two turns of the
    server's loop, so neither holds it as long as the whole page did (a liveness probe or
    another visitor's move waits at most one part); the page is marked complete (the
    root's class, which the health check and the browser tests wait for) with the
    second, which brings the support tab's figures."""
    base, log = served
    done = subprocess.run([sys.executable, "-c", _OPEN, base], cwd=ROOT / "benchmarks",
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    received = json.loads(done.stdout.strip().splitlines()[-1])
    parts = [r for r in received if r[0] >= 50]
    assert len(parts) == 2, received
    (first, orbit_first, mark_first), (second, orbit_second, mark_second) = parts
    assert not orbit_first and not mark_first, received
    assert orbit_second and mark_second, received
    assert received[-1] == parts[1], received  # nothing was waited for after it


#: Run in ``benchmarks/``: three pages requested and pulled together, their browsers
#: saying "rendered" together; print, for each in the order it said so, when it said so,
#: when each message with the dashboard's models arrived and when each telling it the
#: pages to be built before it did (seconds), as JSON.
_OPEN_TOGETHER = """
import asyncio, json, sys, time
import load_client as lc

async def main(base, n):
    sessions = [lc.Session(i, base) for i in range(n)]
    pulled, ready_at, parts = asyncio.Event(), {}, {i: [] for i in range(n)}
    notes = {i: [] for i in range(n)}

    def watch(session):
        read, flush = session._read, session._flush

        async def reading():
            message = await read()
            if message is not None and message.msgtype == "PATCH-DOC":
                text = json.dumps(message.content)
                if text.count('"type": "object"') >= 50:
                    parts[session.index].append(time.perf_counter())
                elif "other page" in text:  # told its place while it waits
                    notes[session.index].append(time.perf_counter())
            return message

        async def flushing():  # the first flush says "rendered": all at once
            if session.index not in ready_at:
                pulled.set() if len(ready_at) == n - 1 else None
                ready_at[session.index] = None
                await pulled.wait()
                ready_at[session.index] = time.perf_counter()
            await flush()
        session._read, session._flush = reading, flushing
    for session in sessions:
        watch(session)
    await asyncio.gather(*(s.open() for s in sessions))
    for session in sessions:
        session.socket.close()
    order = sorted(range(n), key=lambda i: ready_at[i])
    print(json.dumps([[ready_at[i], parts[i], notes[i]] for i in order]))

asyncio.run(main(sys.argv[1], int(sys.argv[2])))
"""


def test_pages_opened_together_arrive_one_after_another_the_first_opened_first(served):
    """``app.page_lane``: three visitors whose pages open at the same moment get them one
    after another, whole, in the order they opened; not all three at the end, as when the
    pages' steps took turns on the server's loop. A page waiting is told how many pages
    will be built before it."""
    base, _log = served
    done = subprocess.run([sys.executable, "-c", _OPEN_TOGETHER, base, "3"],
                          cwd=ROOT / "benchmarks", capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    pages = json.loads(done.stdout.strip().splitlines()[-1])
    assert all(len(parts) == 2 for _ready, parts, _notes in pages), pages
    # Every browser had said so before the first page's models came: built together.
    assert max(ready for ready, _parts, _notes in pages) < pages[0][1][0], pages
    for (_, earlier, _n), (_, later, _m) in zip(pages, pages[1:]):
        assert earlier[-1] < later[0], pages  # the earlier page whole before the later's
    # The first page is built at once; the last waits, told so ("2 other pages", then 1).
    assert pages[0][2] == [] and len(pages[-1][2]) == 2, pages
    assert max(pages[-1][2]) < pages[-1][1][0], pages


#: Run in ``benchmarks/``: pages with different addresses opened at the same moment; print
#: the θ₀ each page's slider shows once it is whole, in the order opened, as JSON.
_OPEN_DIFFERENT = """
import asyncio, json, sys
import load_client as lc

async def main(base, angles):
    sessions = [lc.Session(i, base, query=f"?theta0_deg={a}") for i, a in enumerate(angles)]
    await asyncio.gather(*(s.open() for s in sessions))
    shown = [s._find("ctl-theta0").value for s in sessions]
    for session in sessions:
        session.socket.close()
    print(json.dumps(shown))

asyncio.run(main(sys.argv[1], [int(a) for a in sys.argv[2:]]))
"""


def test_pages_opened_together_each_show_their_own_address(served):
    """Pages waiting in the lane are built from their own session (its address, its
    document), not from the page built before them: three links with different angles,
    opened at once, show their three angles (``app.page_lane``)."""
    base, log = served
    angles = [10, 20, 30]
    done = subprocess.run([sys.executable, "-c", _OPEN_DIFFERENT, base, *map(str, angles)],
                          cwd=ROOT / "benchmarks", capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    assert json.loads(done.stdout.strip().splitlines()[-1]) == angles, done.stdout[-500:]
    text = log.read_text(encoding="utf-8", errors="replace")
    assert "Traceback" not in text, text[-3000:]
