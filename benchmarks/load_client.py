"""Protocol-level browser stand-ins for the load test (benchmarks/load_test.py): a
session loads the page, opens its websocket, pulls the document and moves sliders with the
``PATCH-DOC`` messages BokehJS sends; see load_test.py for the method."""
from __future__ import annotations

import asyncio
import collections
import math
import random
import re
import time

import panel  # noqa: F401  (registers Panel's Bokeh models for the replicas)
import app.views  # noqa: F401  (and the app's own: the player's frame, the page's behaviour)
from app.healthcheck import has_dashboard
from bokeh.client.websocket import WebSocketClientConnectionWrapper
from bokeh.core.serialization import Serialized
from bokeh.document import Document
from bokeh.events import DocumentReady
from bokeh.protocol import Protocol
from bokeh.protocol.receiver import Receiver
from bokeh.util.token import get_session_id
from tornado.httpclient import AsyncHTTPClient, HTTPRequest
from tornado.websocket import websocket_connect

from load_moves import (CLASS_GAP_S, DRAG_GAP_S, DRAG_PROBABILITY, DRAG_STEPS,  # noqa: F401
                        PROFILES, THINK_S, UPDATE_TIMEOUT_S, SessionFailure, SliderMoves)

OPEN_TIMEOUT_S = 120.0
#: The title of the server's busy page (app/main.py) and how long a client waits before
#: it reloads it.
BUSY_TITLE, BUSY_RETRY_S = b"(busy)</title>", 1.0
#: How a client keeps its copy of the page once the dashboard has arrived: ``full``
#: applies every patch the server sends (as BokehJS does, at ~55 ms of this process's CPU
#: per patch); ``watched`` applies only the changes to the models it reads (the headline,
#: and the buttons and plot it asks for) and counts the rest. Thirty full replicas in one
#: Python process saturate its event loop (a class of 30 at a move every 3 s needs more
#: than one core of patch applying), and a saturated loop reads the server's answers late:
#: the latency would then measure this process, not the server. In a class each browser
#: applies its own patches on its own device.
REPLICAS = {
    "full": "every patch applied to the client's copy of the page (as BokehJS does)",
    "watched": "only changes to the models the client reads applied (one process stands "
               "in for 30 devices)",
}


#: The steps of opening a page, timed from its request (``Session.open_steps``): the page
#: answered (its light document built, app.opening), the document pulled over the
#: websocket, the dashboard's patch read (the server built it once the page said it was
#: ready) and applied to this client's copy (a browser's work, done here in Python).
OPEN_STEPS = ("page", "pulled", "dashboard read", "dashboard applied")



class Session(SliderMoves):
    """One browser stand-in (see the module doc): a replica of the page's document."""

    def __init__(self, index: int, base: str, app: str = "app", seed: int = 0,
                 query: str = "", source: str | None = None, replica: str = "full"):
        if replica not in REPLICAS:
            raise ValueError(f"replica={replica!r}: give one of {sorted(REPLICAS)}")
        self.index, self.base, self.app = index, base, app
        #: How much of the server's patches this client applies to its copy of the page
        #: once the dashboard is open (``REPLICAS``).
        self.replica = replica
        #: The page's URL query (``?k_r=...``) and the local address to connect from (a
        #: loopback address such as 127.0.0.2 is another client to the server).
        self.query, self.source = query, source
        self.rng = random.Random(seed * 1000 + index)
        self.protocol = Protocol()
        self.receiver = Receiver(self.protocol)
        self.doc: Document | None = None
        self.socket = self.conn = None
        self.session_id = ""
        #: Seconds from a move's message leaving this client (serialised and written) to
        #: the server's message with the new data being read here, before this client
        #: applies it: the server's latency, without this Python client's own costs
        #: (serialising a patch and applying one against its ~400-model copy of the
        #: page take ~50 ms each here; BokehJS in a browser does them in its own process).
        self.latencies: list[float] = []
        self.drag_latencies: list[float] = []
        #: The same moves until this client had applied the data (its costs included).
        self.client_latencies: list[float] = []
        self.last_orbit_read = math.nan  # when the latest message with orbit data was read
        self.open_s = math.nan
        self.opened_at = math.nan
        #: Seconds from the page request to each step of opening (``OPEN_STEPS``).
        self.open_steps: dict[str, float] = {}
        self.busy_pages = 0  # busy pages received before the dashboard
        self.errors: list[str] = []
        self.patches = 0
        self.orbit_pushes = 0  # patches carrying the orbit's data
        #: (time, [(kind, attribute)]) of the latest patches from the server, for diagnosis.
        self.recent: collections.deque = collections.deque(maxlen=12)
        #: Ids of the models whose changes a ``watched`` replica applies.
        self.watched: set[str] = set()
        #: Seconds this client spent applying the server's patches to its copy.
        self.apply_s = 0.0
        self._outbox: list = []
        self._patched = asyncio.Event()
        self._reader: asyncio.Task | None = None
        self._closing = False

    # --------------------------------------------------------------- protocol
    async def _read(self):
        while True:
            fragment = await self.socket.read_message()
            if fragment is None:
                return None
            message = await self.receiver.consume(fragment)
            if message is not None:
                return message

    async def open(self) -> None:
        start = self.opened_at = time.perf_counter()
        while True:
            page = await AsyncHTTPClient().fetch(HTTPRequest(
                f"{self.base}/{self.app}{self.query}", request_timeout=OPEN_TIMEOUT_S,
                network_interface=self.source))
            if BUSY_TITLE not in page.body:
                break
            # The server's busy page (too many unopened pages from this address): reload
            # after a moment, as its Reload button asks; the wait counts in the open time.
            self.busy_pages += 1
            await asyncio.sleep(BUSY_RETRY_S)
        self._step("page")
        match = re.search(r'"token"\s*:\s*"([^"]+)"', page.body.decode())
        if match is None:
            raise SessionFailure("no session token in the page")
        token = match.group(1)
        self.session_id = get_session_id(token)
        url = self.base.replace("http://", "ws://", 1) + f"/{self.app}/ws"
        self.socket = await websocket_connect(HTTPRequest(url, network_interface=self.source),
                                              subprotocols=["bokeh", token],
                                              max_message_size=50 * 2**20)
        # As browsers do (Chromium sets TCP_NODELAY on every socket): without it, a
        # message's second frame waits for the server's delayed ACK of the first (~40 ms
        # on Linux), and every move would look 40 ms slower than the server is.
        self.socket.protocol.set_nodelay(True)
        self.conn = WebSocketClientConnectionWrapper(self.socket)
        ack = await self._read()
        if ack is None or ack.msgtype != "ACK":
            raise SessionFailure(f"expected ACK, got {ack and ack.msgtype}")
        request = self.protocol.create("PULL-DOC-REQ")
        await request.send(self.conn)
        while True:
            reply = await self._read()
            if reply is None:
                raise SessionFailure("connection closed while pulling the document")
            if reply.msgtype == "ERROR":
                raise SessionFailure(f"server error: {reply.content.get('text')}")
            if reply.msgtype == "PULL-DOC-REPLY":
                break
        self._step("pulled")
        self.doc = Document()
        reply.push_to_document(self.doc)
        self.doc.callbacks.on_change_dispatch_to(self)
        # BokehJS announces a rendered page; the server then sends the dashboard into
        # the light page it answered with (app.opening).
        self.doc.callbacks.send_event(DocumentReady())
        await self._flush()
        while not has_dashboard(self.doc):
            message = await self._read()
            if message is None:
                raise SessionFailure("connection closed before the dashboard arrived")
            if message.msgtype == "PATCH-DOC":
                self._step("dashboard read")
                message.apply_to_document(self.doc, self)
        self._step("dashboard applied")
        self.sliders = {name: self._find(f"ctl-{name}") for name in
                        ("theta0", "k_r", "k_theta", "F_N")}
        self.orbit = next(m for m in self.doc.models if getattr(m, "name", None) == "orbit")
        # The headline above the plots names the support's theta0 ("every support at
        # theta0 = 90°"): what every visitor sees (the folded tables are written when opened).
        # It is written in place (``app.views.live_text.LiveHTML``): its HTML lives in the
        # component's data model.
        self.readout = self._find("headline").data
        self.watched.add(self.readout.id)
        self.open_s = time.perf_counter() - start
        self._reader = asyncio.create_task(self._read_loop())

    def _step(self, name: str) -> None:
        self.open_steps[name] = time.perf_counter() - self.opened_at

    async def first_plot(self, timeout: float = UPDATE_TIMEOUT_S) -> float:
        """Seconds from the page request until the orbit was drawn with data (the page
        is built at once and fills in when the first result arrives)."""
        self.watched.add(self.orbit.id)
        deadline = time.perf_counter() + timeout
        while not len(self.orbit.data.get("x0", ())):
            left = deadline - time.perf_counter()
            if left <= 0 or self.errors:
                raise SessionFailure(f"no plot within {timeout:.0f} s of the page request"
                                     + (f" ({self.errors[-1]})" if self.errors else ""))
            self._patched.clear()
            try:
                await asyncio.wait_for(self._patched.wait(), timeout=left)
            except asyncio.TimeoutError:
                pass
        return time.perf_counter() - self.opened_at

    async def download(self, css_class: str, timeout: float = UPDATE_TIMEOUT_S):
        """Click the ``FileDownload`` button with ``css_class`` as the page does and wait
        for the file the server sends back: (seconds, the file's text)."""
        import base64

        button = self._find(css_class)
        self.watched.add(button.id)
        transfers = button._transfers
        start = time.perf_counter()
        button.clicks = button.clicks + 1
        await self._flush()
        deadline = start + timeout
        while button._transfers == transfers:
            left = deadline - time.perf_counter()
            if left <= 0 or self.errors:
                raise SessionFailure(f"no file from {css_class} within {timeout:.0f} s")
            self._patched.clear()
            try:
                await asyncio.wait_for(self._patched.wait(), timeout=left)
            except asyncio.TimeoutError:
                pass
        payload = button.data.split(",", 1)[-1]
        return time.perf_counter() - start, base64.b64decode(payload).decode("utf-8")

    async def click(self, css_class: str) -> None:
        """Press the ``Button`` with ``css_class`` as BokehJS does: a ``button_click``
        event sent to the server in a ``PATCH-DOC``."""
        from bokeh.document.events import MessageSentEvent
        from bokeh.events import ButtonClick

        button = self._find(css_class)
        event = MessageSentEvent(self.doc, "bokeh_event", ButtonClick(button))
        await self.protocol.create("PATCH-DOC", [event]).send(self.conn)

    def visible(self, css_class: str) -> bool:
        return bool(self._find(css_class).visible)

    def enabled(self, css_class: str) -> bool:
        return not self._find(css_class).disabled

    async def changed(self, timeout: float) -> None:
        """Wait for the server's next change to the page (at most ``timeout`` s)."""
        self._patched.clear()
        try:
            await asyncio.wait_for(self._patched.wait(), timeout=timeout)
        except asyncio.TimeoutError:
            pass

    def _find(self, css_class: str):
        for model in self.doc.models:
            if css_class in (getattr(model, "css_classes", None) or ()):
                return model
        raise SessionFailure(f"no model with CSS class {css_class!r} in the page")

    async def _read_loop(self) -> None:
        try:
            while True:
                message = await self._read()
                read_at = time.perf_counter()
                if message is None:
                    if not self._closing:
                        self.errors.append("the server closed the connection")
                    return
                if message.msgtype == "PATCH-DOC":
                    events = message.content.get("events", [])
                    orbit = any((e.get("model") or {}).get("id") == self.orbit.id
                                for e in events)
                    self._apply(message, events)
                    self.patches += 1
                    if orbit:
                        self.last_orbit_read = read_at
                    self.orbit_pushes += orbit
                    self.recent.append((time.perf_counter(),
                                        [(e.get("kind"), e.get("attr")) for e in events]))
                    self._patched.set()
                elif message.msgtype == "ERROR":
                    self.errors.append(f"server error: {message.content.get('text')}")
        except Exception as exc:  # noqa: BLE001 - reported, not raised
            if not self._closing:
                self.errors.append(f"reader failed: {type(exc).__name__}: {exc}")

    def _apply(self, message, events: list) -> None:
        """Apply a server patch to the copy of the page: all of it, or (``watched``) only
        the events on the watched models."""
        start = time.perf_counter()
        if self.replica == "full":
            message.apply_to_document(self.doc, self)
        else:
            mine = [e for e in events if (e.get("model") or {}).get("id") in self.watched]
            if mine:
                self.doc.apply_json_patch(Serialized({"events": mine}, message.buffers),
                                          setter=self)
        self.apply_s += time.perf_counter() - start

    def _document_patched(self, event) -> None:
        """Changes made here (not applied from the server) are sent, as BokehJS does."""
        if event.setter is not self:
            self._outbox.append(event)

    async def _flush(self) -> None:
        events, self._outbox = self._outbox, []
        if events:
            await self.protocol.create("PATCH-DOC", events).send(self.conn)

    async def close(self) -> None:
        self._closing = True
        if self.socket is not None:
            self.socket.close()
        if self._reader is not None:
            try:
                await asyncio.wait_for(self._reader, timeout=10)
            except (asyncio.TimeoutError, Exception):  # noqa: BLE001
                self._reader.cancel()

