"""Load test of the dashboard: N concurrent sessions moving sliders against one server.

    python benchmarks/load_test.py [--sessions 30] [--duration 60] [--out DIR] [--quick]

``panel serve app`` is started on a loopback port (``tests/browser/serving.serve_app``)
with a short unused-session lifetime, so closed sessions are cleaned up within the run.

**Clients.** Each session is a protocol-level browser stand-in, all of them in one
asyncio loop of this process: it loads the page over HTTP (``GET /app``: the server
builds the session's document and embeds its token, as for a browser), opens the
session's websocket with that token, pulls the document (Bokeh's ``PULL-DOC``) into a
local replica and then behaves like a page: a slider move is the ``PATCH-DOC`` message
BokehJS sends (the slider model's ``value`` and ``value_throttled``), and every
``PATCH-DOC`` the server pushes is applied to the replica. So the server does all the
work it does for a browser: it builds the page, runs the widget callbacks, queues the
model work in its worker processes, serialises the new plot data and pushes it over
each session's websocket. What is left out is the browser's own work: fetching the
(static, cacheable) scripts and drawing. That is why this technique was chosen:
measured with ``--browsers 6`` on this 2-core machine, a headless Chromium page of the
dashboard takes about 550 MB and 0.3 s of CPU to draw one update (6 pages: 3.3 GB,
21 s of CPU for 69 key presses), so 30 pages would need about 16 GB and, at the ten
updates a second the server delivers to 30 sessions, three cores for drawing alone --
the test would measure Chromium, not the server. The 30 protocol clients take about
40 % of one core. ``--browsers K`` adds K real pages (Debian's headless Chromium
through Playwright, one browser with a context per page), which move the theta0 slider
by key presses during the run; their latency (key press -> orbit data changed in the
page) is reported separately.

**What a session does.** Closed loop, as a person at the controls: it moves one
slider (theta0, k_r, k_theta or F_N, to a random position on the slider's grid),
waits until the server has pushed the new data, pauses 0.2-0.8 s, and repeats; one
move in five is a drag (four theta0 positions 30 ms apart), timed from its last
position. The update latency is the time from sending the change to applying the
first server patch that carries the orbit's data -- for theta0, once the fixed-array
readout also shows the requested angle, so a stale result cannot count. (Every
session first sends Bokeh's ``document_ready`` event, as BokehJS does once the page is
drawn: Panel holds a session's model updates until then.)

**Reported.** p50/p95/max update latency; page open time (GET + websocket + pull);
errors (failed or stalled sessions, protocol errors, tracebacks in the server log);
the resident memory (RSS) of the server process and of its worker processes: at the
start (the baseline: the server is up and has built one page, for its health check),
peak during the run, after every session was closed and cleaned up, and after a second,
shorter round of as many sessions; and whether the server destroyed every session (its
log names each discarded session and counts the open ones).

**Memory checks.** (1) After cleanup the total RSS is within ``max(150 MB, 25 %)`` of
the baseline. (2) The second round adds at most ``max(20 MB, 25 %)`` of what the first
round's sessions took at its peak. CPython keeps the memory of destroyed sessions in
its allocator for reuse instead of returning it to the system (measured: a session's
document is freed -- counted in the server with ``gc`` -- yet the RSS stays near its
peak), and the result caches shared by all sessions fill up to their bounds
(app/compute.py, the model's LRU caches); so (1) bounds what stays, and (2) tells
retention from a leak: leaked sessions would add about a round's worth again.

Writes DIR/load.md and DIR/load.json (default DIR: bench-out); exits 1 when a check
fails (errors, sessions without updates, memory not back, sessions not destroyed).
"""
from __future__ import annotations

import argparse
import asyncio
import collections
import json
import math
import os
import random
import re
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
import panel  # noqa: E402,F401  (registers Panel's Bokeh models for the replicas)
from bokeh.client.websocket import WebSocketClientConnectionWrapper  # noqa: E402
from bokeh.document import Document  # noqa: E402
from bokeh.events import DocumentReady  # noqa: E402
from bokeh.protocol import Protocol  # noqa: E402
from bokeh.protocol.receiver import Receiver  # noqa: E402
from bokeh.util.token import get_session_id  # noqa: E402
from tornado.httpclient import AsyncHTTPClient  # noqa: E402
from tornado.websocket import websocket_connect  # noqa: E402

from tests.browser.serving import serve_app  # noqa: E402

#: The server looks for unused sessions every second and destroys those without a
#: connection for 5 s (Bokeh's default is 15 s; shorter, so cleanup happens within the run,
#: but longer than a page takes to load here, so no session is destroyed before its
#: websocket connects).
CHECK_UNUSED_MS, UNUSED_LIFETIME_MS = 1000, 5000
SERVE_ARGS = ("--check-unused-sessions", str(CHECK_UNUSED_MS),
              "--unused-session-lifetime", str(UNUSED_LIFETIME_MS),
              "--stats-log-frequency", "1000", "--log-level", "debug")
UPDATE_TIMEOUT_S = 30.0
OPEN_TIMEOUT_S = 120.0
#: Pages loading at the same time (people arrive over some seconds, not all at one instant).
OPENING_AT_ONCE = 2
THINK_S = (0.2, 0.8)
DRAG_PROBABILITY, DRAG_STEPS, DRAG_GAP_S = 0.2, 4, 0.03
MEMORY_BOUND_MB, MEMORY_BOUND_FRACTION = 150.0, 0.25
LEAK_BOUND_MB, LEAK_BOUND_FRACTION = 20.0, 0.25
#: Tracebacks the server logs when a connection closed while messages were on their way
#: (a client went away; not a fault of the app), as in tests/browser/conftest.py.
CLOSED_CONNECTION_ERRORS = ("tornado.iostream.StreamClosedError",
                            "tornado.websocket.WebSocketClosedError")
#: Server log lines that report a failure without a traceback.
LOG_FAILURES = re.compile(r"dashboard update failed|Failed to run session destroy hooks|"
                          r"came back to life|dashboard worker .* stopped|"
                          r"Error running application handler")


# ------------------------------------------------------------------------------ memory

def tree_rss_mb(pid: int) -> dict:
    """RSS in MB of the process ``pid`` and of each of its descendants (worker processes)."""
    try:
        import psutil
    except ImportError:
        return _tree_rss_proc(pid)
    root = psutil.Process(pid)
    procs = [root] + root.children(recursive=True)
    out = {"server": 0.0, "workers": 0.0, "processes": 0}
    for p in procs:
        try:
            rss = p.memory_info().rss / 2**20
        except psutil.NoSuchProcess:
            continue
        out["server" if p.pid == pid else "workers"] += rss
        out["processes"] += 1
    out["total"] = out["server"] + out["workers"]
    return out


def _tree_rss_proc(pid: int) -> dict:
    """``tree_rss_mb`` from /proc, where psutil is missing."""
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                ppid = int(Path(f"/proc/{entry}/stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry))
    order, out = [pid], {"server": 0.0, "workers": 0.0, "processes": 0}
    for p in order:
        order.extend(children.get(p, []))
        try:
            fields = dict(line.split(":", 1) for line in
                          Path(f"/proc/{p}/status").read_text().splitlines() if ":" in line)
            rss = int(fields["VmRSS"].split()[0]) / 1024
        except (OSError, KeyError, ValueError):
            continue
        out["server" if p == pid else "workers"] += rss
        out["processes"] += 1
    out["total"] = out["server"] + out["workers"]
    return out


def server_pid(port: int) -> int:
    """The pid of our ``panel serve`` child listening on ``port``."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            cmd = Path(f"/proc/{entry}/cmdline").read_bytes().split(b"\0")
            stat = Path(f"/proc/{entry}/stat").read_text()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        if ppid == os.getpid() and b"serve" in cmd and str(port).encode() in cmd:
            return int(entry)
    raise RuntimeError(f"no panel serve process of ours on port {port}")


class MemorySampler(threading.Thread):
    """Samples the server's tree RSS every ``interval`` s in a thread; keeps the peak."""

    def __init__(self, pid: int, interval: float = 0.25):
        super().__init__(daemon=True)
        self.pid, self.interval = pid, interval
        self.peak: dict | None = None
        self.samples = 0
        self._halt = threading.Event()

    def run(self):
        while not self._halt.wait(self.interval):
            now = tree_rss_mb(self.pid)
            self.samples += 1
            if self.peak is None or now["total"] > self.peak["total"]:
                self.peak = now

    def stop(self) -> dict | None:
        self._halt.set()
        self.join(timeout=5)
        return self.peak


def tree_cpu_s(pid: int) -> np.ndarray:
    """CPU seconds (user + system) used so far by ``pid`` and by its descendants."""
    try:
        import psutil
    except ImportError:
        return np.array([math.nan, math.nan])
    total = np.zeros(2)
    root = psutil.Process(pid)
    for proc in [root] + root.children(recursive=True):
        try:
            t = proc.cpu_times()
            total[int(proc.pid != pid)] += t.user + t.system
        except psutil.Error:
            continue
    return total


# ------------------------------------------------------------------------------ sessions

class SessionFailure(Exception):
    """A session could not open, stalled or lost its connection."""


class Session:
    """One browser stand-in (see the module doc): a replica of the page's document."""

    def __init__(self, index: int, base: str, app: str = "app", seed: int = 0):
        self.index, self.base, self.app = index, base, app
        self.rng = random.Random(seed * 1000 + index)
        self.protocol = Protocol()
        self.receiver = Receiver(self.protocol)
        self.doc: Document | None = None
        self.socket = self.conn = None
        self.session_id = ""
        self.latencies: list[float] = []
        self.drag_latencies: list[float] = []
        self.open_s = math.nan
        self.errors: list[str] = []
        self.patches = 0
        self.orbit_pushes = 0  # patches carrying the orbit's data
        #: (time, [(kind, attribute)]) of the latest patches from the server, for diagnosis.
        self.recent: collections.deque = collections.deque(maxlen=12)
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
        start = time.perf_counter()
        page = await AsyncHTTPClient().fetch(f"{self.base}/{self.app}",
                                             request_timeout=OPEN_TIMEOUT_S)
        match = re.search(r'"token"\s*:\s*"([^"]+)"', page.body.decode())
        if match is None:
            raise SessionFailure("no session token in the page")
        token = match.group(1)
        self.session_id = get_session_id(token)
        url = self.base.replace("http://", "ws://", 1) + f"/{self.app}/ws"
        self.socket = await websocket_connect(url, subprotocols=["bokeh", token],
                                              max_message_size=50 * 2**20)
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
        self.doc = Document()
        reply.push_to_document(self.doc)
        self.doc.callbacks.on_change_dispatch_to(self)
        self.sliders = {name: self._find(f"ctl-{name}") for name in
                        ("theta0", "k_r", "k_theta", "F_N")}
        self.orbit = next(m for m in self.doc.models if getattr(m, "name", None) == "orbit")
        self.readout = self._find("readout-fixed")
        # BokehJS announces a rendered page; Panel holds model updates until it has.
        self.doc.callbacks.send_event(DocumentReady())
        await self._flush()
        self.open_s = time.perf_counter() - start
        self._reader = asyncio.create_task(self._read_loop())

    def _find(self, css_class: str):
        for model in self.doc.models:
            if css_class in (getattr(model, "css_classes", None) or ()):
                return model
        raise SessionFailure(f"no model with CSS class {css_class!r} in the page")

    async def _read_loop(self) -> None:
        try:
            while True:
                message = await self._read()
                if message is None:
                    if not self._closing:
                        self.errors.append("the server closed the connection")
                    return
                if message.msgtype == "PATCH-DOC":
                    message.apply_to_document(self.doc, self)
                    self.patches += 1
                    events = message.content.get("events", [])
                    self.orbit_pushes += any((e.get("model") or {}).get("id") == self.orbit.id
                                             for e in events)
                    self.recent.append((time.perf_counter(),
                                        [(e.get("kind"), e.get("attr")) for e in events]))
                    self._patched.set()
                elif message.msgtype == "ERROR":
                    self.errors.append(f"server error: {message.content.get('text')}")
        except Exception as exc:  # noqa: BLE001 - reported, not raised
            if not self._closing:
                self.errors.append(f"reader failed: {type(exc).__name__}: {exc}")

    def _document_patched(self, event) -> None:
        """Changes made here (not applied from the server) are sent, as BokehJS does."""
        if event.setter is not self:
            self._outbox.append(event)

    async def _flush(self) -> None:
        events, self._outbox = self._outbox, []
        if events:
            await self.protocol.create("PATCH-DOC", events).send(self.conn)

    # --------------------------------------------------------------- behaviour
    def _readout_shows(self, degrees: float) -> bool:
        return f"θ₀ = {degrees:g}°" in (self.readout.text or "")

    async def _set(self, name: str, value: float) -> None:
        slider = self.sliders[name]
        slider.value = value
        slider.set_from_json("value_throttled", value)  # read-only in Python, as BokehJS sets it
        await self._flush()

    def _position(self, name: str) -> float:
        s = self.sliders[name]
        steps = int(round((s.end - s.start) / s.step))
        value = s.start + self.rng.randint(0, steps) * s.step
        if abs(value - s.value) < 0.5 * s.step:  # a move, not the same position
            value = s.start + ((round((value - s.start) / s.step) + 1) % (steps + 1)) * s.step
        return round(value, 6)

    async def move(self) -> None:
        """One slider move (or drag) and the wait for its update."""
        name = self.rng.choice(list(self.sliders))
        drag = name == "theta0" and self.rng.random() < DRAG_PROBABILITY
        self._patched.clear()
        for step in range(DRAG_STEPS if drag else 1):
            if step:
                await asyncio.sleep(DRAG_GAP_S)
            value = self._position(name)
            sent, pushes = time.perf_counter(), self.orbit_pushes
            await self._set(name, value)

        def done() -> bool:
            # New orbit data was pushed (not necessarily different: on the axis, k_theta
            # does not change the motion); for theta0 it must be the requested angle's.
            if self.orbit_pushes == pushes:
                return False
            return name != "theta0" or self._readout_shows(value)

        deadline = sent + UPDATE_TIMEOUT_S
        while not done():
            left = deadline - time.perf_counter()
            if left <= 0 or self.errors:
                raise SessionFailure(f"no update within {UPDATE_TIMEOUT_S:.0f} s after "
                                     f"{name} = {value}" + (f" ({self.errors[-1]})"
                                                            if self.errors else "")
                                     + "; " + self._diagnosis(sent))
            self._patched.clear()
            try:
                await asyncio.wait_for(self._patched.wait(), timeout=left)
            except asyncio.TimeoutError:
                pass
        (self.drag_latencies if drag else self.latencies).append(time.perf_counter() - sent)

    def _diagnosis(self, sent: float) -> str:
        values = {k: round(m.value, 4) for k, m in self.sliders.items()}
        recent = [f"{t - sent:+.1f}s {events}" for t, events in self.recent]
        return f"sliders {values}; latest patches (time after the change): {recent}"

    async def run(self, until: float) -> None:
        try:
            while time.perf_counter() < until:
                await self.move()
                await asyncio.sleep(self.rng.uniform(*THINK_S))
        except Exception as exc:  # noqa: BLE001 - counted as a session failure
            self.errors.append(f"{type(exc).__name__}: {exc}")

    async def close(self) -> None:
        self._closing = True
        if self.socket is not None:
            self.socket.close()
        if self._reader is not None:
            try:
                await asyncio.wait_for(self._reader, timeout=10)
            except (asyncio.TimeoutError, Exception):  # noqa: BLE001
                self._reader.cancel()


async def open_sessions(base: str, app: str, n: int, seed: int) -> list[Session]:
    sessions = [Session(i, base, app, seed=seed) for i in range(n)]
    opening = asyncio.Semaphore(OPENING_AT_ONCE)

    async def one(s: Session):
        async with opening:
            try:
                await asyncio.wait_for(s.open(), timeout=OPEN_TIMEOUT_S)
            except Exception as exc:  # noqa: BLE001
                s.errors.append(f"open failed: {type(exc).__name__}: {exc}")
    await asyncio.gather(*(one(s) for s in sessions))
    return sessions


async def drive(base: str, app: str, n: int, duration: float, seed: int,
                on_open=None, before_close=None) -> tuple[list[Session], float]:
    """Open ``n`` sessions, move their sliders for ``duration`` s, close them
    (``on_open()`` is called once all are open, ``before_close()`` just before closing)."""
    sessions = await open_sessions(base, app, n, seed)
    if on_open is not None:
        on_open()
    started = time.perf_counter()
    live = [s for s in sessions if not s.errors]
    await asyncio.gather(*(s.run(started + duration) for s in live))
    elapsed = time.perf_counter() - started
    if before_close is not None:
        before_close()
    await asyncio.gather(*(s.close() for s in sessions))
    return sessions, elapsed


# ------------------------------------------------------------------------------ browsers

def browser_pages(url: str, n: int, duration: float, result: dict) -> None:
    """``n`` Chromium pages (one browser, a context each) pressing theta0's arrow keys."""
    try:
        from playwright.sync_api import sync_playwright

        from tests.browser.page_tools import (measure_slider_latency, settle, slider_handle,
                                              wait_for_app)
        from tests.browser.serving import VIEWPORT, launch_chromium
    except ImportError as exc:
        result["errors"] = [f"browser pages unavailable: {exc}"]
        return
    result.update(latencies=[], errors=[], open_s=[], presses=0, peak_rss_mb=0.0)
    with sync_playwright() as pw:
        browser = launch_chromium(pw)
        start, cpu0 = time.perf_counter(), chromium_usage()[0]
        try:
            pages = []
            for _ in range(n):
                page = browser.new_context(viewport=VIEWPORT).new_page()
                page.on("pageerror", lambda e: result["errors"].append(f"page error: {e}"))
                result["open_s"].append(wait_for_app(page, url, timeout_ms=90_000))
                pages.append((page, slider_handle(page, css_class="ctl-theta0")))
            for page, _ in pages:
                settle(page, quiet_ms=300)
            start, cpu0 = time.perf_counter(), chromium_usage()[0]  # key presses only
            until, i = time.perf_counter() + duration, 0
            while time.perf_counter() < until:
                page, handle = pages[i % n]
                m = measure_slider_latency(page, handle, "ArrowRight" if i % 4 < 2 else "ArrowLeft",
                                           names=["orbit"], timeout_s=UPDATE_TIMEOUT_S)
                if math.isfinite(m["change_ms"]):
                    result["latencies"].append(m["change_ms"] / 1e3)
                else:
                    result["errors"].append("a browser page got no update")
                i += 1
                result["presses"] = i
                result["peak_rss_mb"] = max(result["peak_rss_mb"], chromium_usage()[1])
                time.sleep(random.uniform(*THINK_S) / n)
        except Exception as exc:  # noqa: BLE001
            result["errors"].append(f"browser pages failed: {type(exc).__name__}: {exc}")
        finally:
            result["cpu_s"] = chromium_usage()[0] - cpu0
            result["wall_s"] = time.perf_counter() - start
            browser.close()


def chromium_usage() -> tuple[float, float]:
    """CPU seconds and RSS (MB) of the Chromium processes this process started."""
    try:
        import psutil
    except ImportError:
        return math.nan, math.nan
    cpu = rss = 0.0
    for proc in psutil.Process().children(recursive=True):
        try:
            if "chrom" in proc.name():
                times = proc.cpu_times()
                cpu += times.user + times.system
                rss += proc.memory_info().rss / 2**20
        except psutil.Error:
            continue
    return cpu, rss


# ------------------------------------------------------------------------------ server log

def log_tracebacks(text: str) -> list[str]:
    """The last line of each traceback in the log (closed-connection ones left out)."""
    lines, found = text.splitlines(), []
    for i, line in enumerate(lines):
        if line.startswith("Traceback"):
            last = next((l for l in lines[i + 1:] if l and not l[0].isspace()), line)
            if not last.startswith(CLOSED_CONNECTION_ERRORS):
                found.append(last.strip())
    return found


def log_failures(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if LOG_FAILURES.search(line)]


def discarded_sessions(text: str) -> set[str]:
    return set(re.findall(r"Discarding session '([^']+)'", text))


def open_session_counts(text: str, app: str = "app") -> list[int]:
    return [int(n) for n in re.findall(rf"/{app} has (\d+) sessions", text)]


def wait_for_cleanup(log_path: Path, ids: set[str], timeout_s: float, app: str = "app") -> dict:
    """Wait until the server's log shows every session in ``ids`` discarded and, after
    that, a count of zero open sessions."""
    deadline = time.monotonic() + timeout_s
    start = time.monotonic()
    while True:
        text = log_path.read_text(encoding="utf-8", errors="replace")
        gone = discarded_sessions(text) & ids
        after = text[max(text.rfind(f"Discarding session '{i}'") for i in ids):] if (
            ids and gone == ids) else ""
        counts = open_session_counts(after, app)
        if (gone == ids and counts and counts[-1] == 0) or time.monotonic() > deadline:
            return {"sessions": len(ids), "destroyed": len(gone),
                    "open_after": counts[-1] if counts else None,
                    "seconds": time.monotonic() - start}
        time.sleep(0.5)


# ------------------------------------------------------------------------------ run

def percentiles(seconds) -> dict:
    a = np.asarray(seconds, dtype=float) * 1e3
    if a.size == 0:
        return {"n": 0, "p50_ms": math.nan, "p95_ms": math.nan, "max_ms": math.nan}
    return {"n": int(a.size), "p50_ms": float(np.percentile(a, 50)),
            "p95_ms": float(np.percentile(a, 95)), "max_ms": float(a.max())}


def memory_bound(baseline_mb: float) -> float:
    return baseline_mb + max(MEMORY_BOUND_MB, MEMORY_BOUND_FRACTION * baseline_mb)


def leak_bound(baseline_mb: float, peak_mb: float) -> float:
    """How much a second round may add to what the first left: a quarter of what the
    first round's sessions took at their peak (at least 20 MB of allocator noise)."""
    return max(LEAK_BOUND_MB, LEAK_BOUND_FRACTION * (peak_mb - baseline_mb))


def run(sessions: int = 30, duration: float = 60.0, out: Path | str = "bench-out",
        browsers: int = 0, seed: int = 1, cleanup_timeout: float = 60.0,
        app_dir: str = "app", repeat_duration: float | None = None) -> dict:
    """Serve the app, drive it, and return (and write) the report as a dict."""
    if repeat_duration is None:
        repeat_duration = max(5.0, duration / 3)
    app = Path(app_dir).name
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    log_path = out / "load-panel-serve.log"
    # The checkout under test, whatever is installed.
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    client_cpu0 = time.process_time()
    t0, phases = time.perf_counter(), {}

    def phase(name: str) -> None:
        phases[name] = round(time.perf_counter() - t0, 1)
    with serve_app(log_path, app_dir=app_dir, extra_args=SERVE_ARGS) as base:
        phase("server up")
        pid = server_pid(int(base.rsplit(":", 1)[1]))
        time.sleep(1.0)
        # The server has built one page already (its /liveness check builds a session).
        baseline = tree_rss_mb(pid)
        log_start = log_path.stat().st_size

        sampler = MemorySampler(pid)
        sampler.start()
        browser: dict = {}
        thread = None
        if browsers:
            thread = threading.Thread(target=browser_pages,
                                      args=(f"{base}/{app}", browsers, duration, browser),
                                      daemon=True)
            thread.start()
        load0 = os.getloadavg()
        closing: dict = {}
        moving: dict = {}
        driven, elapsed = asyncio.run(drive(
            base, app, sessions, duration, seed,
            on_open=lambda: moving.update(cpu=tree_cpu_s(pid), client=time.process_time()),
            before_close=lambda: closing.update(
                offset=log_path.stat().st_size, load=os.getloadavg(),
                cpu=tree_cpu_s(pid) - moving["cpu"],
                client=time.process_time() - moving["client"])))
        if thread is not None:
            thread.join(timeout=duration + 300)
        peak = sampler.stop()
        server_cpu = dict(zip(("server", "workers"), closing["cpu"].tolist()))
        client_cpu = closing["client"] / max(elapsed, 1e-9)
        during_samples = sampler.samples

        phase("first round done")
        ids = {s.session_id for s in driven if s.session_id}
        cleanup = wait_for_cleanup(log_path, ids, cleanup_timeout, app)
        time.sleep(1.0)
        after = tree_rss_mb(pid)
        phase("first round cleaned up")
        # The same again, shorter: memory that the first round left behind must not grow
        # by a round's worth (a leak of sessions would), and its sessions must go too.
        again, _ = asyncio.run(drive(base, app, sessions, repeat_duration, seed + 1))
        again_ids = {s.session_id for s in again if s.session_id}
        again_cleanup = wait_for_cleanup(log_path, again_ids, cleanup_timeout, app)
        time.sleep(1.0)
        after_again = tree_rss_mb(pid)
        phase("second round cleaned up")
        raw = log_path.read_bytes()
        text = raw[log_start:].decode("utf-8", errors="replace")
        early = discarded_sessions(
            raw[log_start:closing["offset"]].decode("utf-8", errors="replace")) & ids
    client_cpu_total = time.process_time() - client_cpu0
    phase("server stopped")

    lat = [x for s in driven for x in s.latencies]
    drag = [x for s in driven for x in s.drag_latencies]
    session_errors = [f"session {s.index} ({s.session_id[:8]}): {e}" for s in driven
                      for e in s.errors] + [
        f"second round, session {s.index} ({s.session_id[:8]}): {e}" for s in again
        for e in s.errors]
    tracebacks = log_tracebacks(text)
    failures = log_failures(text)
    errors = session_errors + [f"server: {t}" for t in tracebacks + failures] + [
        f"browser: {e}" for e in browser.get("errors", [])]
    updated = sum(1 for s in driven if s.latencies or s.drag_latencies)
    bound = memory_bound(baseline["total"])
    growth_bound = leak_bound(baseline["total"], (peak or baseline)["total"])
    report = {
        "settings": {"sessions": sessions, "duration_s": duration, "browsers": browsers,
                     "seed": seed, "think_s": THINK_S, "drag_probability": DRAG_PROBABILITY,
                     "update_timeout_s": UPDATE_TIMEOUT_S, "serve_args": list(SERVE_ARGS),
                     "cpus": os.cpu_count()},
        "elapsed_s": elapsed,
        "updates": {"move": percentiles(lat), "drag": percentiles(drag),
                    "all": percentiles(lat + drag),
                    "per_session_min": min((len(s.latencies) + len(s.drag_latencies)
                                            for s in driven), default=0),
                    "rate_per_s": (len(lat) + len(drag)) / max(elapsed, 1e-9)},
        "open": percentiles([s.open_s for s in driven if math.isfinite(s.open_s)]),
        "sessions_with_updates": updated,
        "errors": errors,
        "n_errors": len(errors),
        "memory_mb": {"baseline": baseline, "peak": peak, "after": after,
                      "after_second_round": after_again, "bound_total": bound,
                      "second_round_growth_bound": growth_bound,
                      "samples_during": during_samples},
        "second_round": {"sessions": sessions, "duration_s": repeat_duration,
                         "updates": sum(len(s.latencies) + len(s.drag_latencies) for s in again),
                         "cleanup": again_cleanup},
        "cleanup": cleanup,
        "destroyed_before_close": len(early),
        "load_average": {"start": load0, "end": closing["load"]},
        "client_cpu_fraction": client_cpu,
        "server_cpu_s": server_cpu,
        "client_cpu_s": client_cpu_total,
        "phases_s": phases,
        "browser": {k: (percentiles(v) if k in ("latencies", "open_s") else v)
                    for k, v in browser.items()},
    }
    report["checks"] = {
        "no errors": not errors,
        "every session got updates": updated == sessions,
        "memory back near baseline": after["total"] <= bound and after_again["total"] <= bound,
        "no growth from a second round": after_again["total"] - after["total"] <= growth_bound,
        "every session destroyed": (cleanup["destroyed"] == sessions
                                    and cleanup["open_after"] == 0
                                    and again_cleanup["destroyed"] == sessions
                                    and again_cleanup["open_after"] == 0),
    }
    report["passed"] = all(report["checks"].values())
    (out / "load.json").write_text(json.dumps(report, indent=1, default=float))
    (out / "load.md").write_text(markdown(report))
    return report


def markdown(r: dict) -> str:
    s, u, m = r["settings"], r["updates"], r["memory_mb"]
    peak = m["peak"] or m["baseline"]
    lines = [
        "# Dashboard load test", "",
        f"{s['sessions']} sessions for {r['elapsed_s']:.0f} s against one `panel serve app` "
        f"on {s['cpus']} cores (closed loop: move a slider, wait for the pushed data, pause "
        f"{s['think_s'][0]}-{s['think_s'][1]} s; one theta0 move in five is a "
        f"{DRAG_STEPS}-position drag).", "",
        "| update latency | n | p50 ms | p95 ms | max ms |", "|---|---:|---:|---:|---:|"]
    for name, key in (("slider move -> new data pushed", "move"),
                      ("drag (last position) -> its data pushed", "drag"), ("all", "all")):
        p = u[key]
        lines.append(f"| {name} | {p['n']} | {p['p50_ms']:.1f} | {p['p95_ms']:.1f} | "
                     f"{p['max_ms']:.1f} |")
    o = r["open"]
    lines.append(f"| page open (GET + websocket + pull) | {o['n']} | {o['p50_ms']:.0f} | "
                 f"{o['p95_ms']:.0f} | {o['max_ms']:.0f} |")
    b = r.get("browser") or {}
    if b.get("latencies"):
        p = b["latencies"]
        lines.append(f"| Chromium page: key press -> orbit data changed | {p['n']} | "
                     f"{p['p50_ms']:.1f} | {p['p95_ms']:.1f} | {p['max_ms']:.1f} |")
    lines += [
        "", f"Updates: {u['rate_per_s']:.1f} per second in all; every session got at least "
        f"{u['per_session_min']} ({r['sessions_with_updates']}/{s['sessions']} sessions got "
        "updates).", "",
        "| server RSS (MB) | server | workers | total | processes |",
        "|---|---:|---:|---:|---:|"]
    for name, key in (("baseline (server up, one page built)", "baseline"),
                      ("peak during the run", "peak"), ("after close and cleanup", "after"),
                      (f"after a second round ({r['second_round']['duration_s']:.0f} s)",
                       "after_second_round")):
        x = m[key] if m[key] is not None else peak
        lines.append(f"| {name} | {x['server']:.0f} | {x['workers']:.0f} | {x['total']:.0f} | "
                     f"{x['processes']} |")
    c = r["cleanup"]
    n_updates = max(u["all"]["n"], 1)
    cpu_per_update = 1e3 * r["server_cpu_s"]["server"] / n_updates
    cpu_per_update_w = 1e3 * r["server_cpu_s"]["workers"] / n_updates
    lines += [
        "", f"Memory bound after cleanup: baseline + max({MEMORY_BOUND_MB:.0f} MB, "
        f"{MEMORY_BOUND_FRACTION:.0%}) = {m['bound_total']:.0f} MB; the second round may add "
        f"at most {m['second_round_growth_bound']:.0f} MB (max({LEAK_BOUND_MB:.0f} MB, "
        f"{LEAK_BOUND_FRACTION:.0%} of the first round's peak above the baseline)).", "",
        f"Sessions destroyed by the server: {c['destroyed']}/{c['sessions']} "
        f"({c['seconds']:.1f} s after close); open sessions afterwards: {c['open_after']}; "
        f"destroyed before their websocket connected: {r['destroyed_before_close']}.", "",
        f"Second round: {r['second_round']['updates']} updates; sessions destroyed "
        f"{r['second_round']['cleanup']['destroyed']}/{r['second_round']['cleanup']['sessions']}"
        f", open afterwards: {r['second_round']['cleanup']['open_after']}.",
        "", f"CPU during the {r['elapsed_s']:.0f} s of slider moves: the clients (this process) "
        f"{r['client_cpu_fraction']:.0%} of one core; the server process "
        f"{r['server_cpu_s']['server']:.0f} s, worker processes "
        f"{r['server_cpu_s']['workers']:.0f} s ({cpu_per_update:.0f} ms and "
        f"{cpu_per_update_w:.0f} ms per update). "
        "Load average (1 min) of the machine: "
        f"{r['load_average']['start'][0]:.1f} at the start of the run, "
        f"{r['load_average']['end'][0]:.1f} at its end.", "", f"Errors: {r['n_errors']}"]
    if b.get("cpu_s") is not None:
        lines[-1:-1] = [f"Chromium ({s['browsers']} pages): {b['cpu_s']:.0f} s of CPU in "
                        f"{b['wall_s']:.0f} s ({b['cpu_s'] / max(b['wall_s'], 1e-9):.0%} of one "
                        f"core), peak RSS {b['peak_rss_mb']:.0f} MB, {b['presses']} key "
                        "presses.", ""]
    lines += [f"- {e}" for e in r["errors"][:50]]
    lines += ["", "| check | result |", "|---|---|"]
    lines += [f"| {k} | {'pass' if v else 'FAIL'} |" for k, v in r["checks"].items()]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sessions", type=int, default=30, help="concurrent sessions (30)")
    ap.add_argument("--duration", type=float, default=60.0, help="seconds of slider moves (60)")
    ap.add_argument("--browsers", type=int, default=0,
                    help="also drive this many headless Chromium pages (0)")
    ap.add_argument("--quick", action="store_true", help="6 sessions for 15 s (for the tests)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--app", default="app", help="the app folder to serve (default app)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    if args.quick:
        args.sessions, args.duration = 6, 15.0
    report = run(args.sessions, args.duration, args.out, browsers=args.browsers, seed=args.seed,
                 app_dir=args.app)
    print(markdown(report))
    return 0 if report["passed"] else 1


if __name__ == "__main__":
    sys.exit(main())
