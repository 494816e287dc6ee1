"""What the load test (benchmarks/load_test.py) measures around the server: memory and
CPU of its process tree, real Chromium pages, and the server log (tracebacks, sessions
destroyed)."""
from __future__ import annotations

import math
import os
import random
import re
import threading
import time
from pathlib import Path

import numpy as np

from load_client import THINK_S, UPDATE_TIMEOUT_S


#: Tracebacks the server logs when a connection closed while messages were on their way
#: (a client went away; not a fault of the app), as in tests/browser/conftest.py.
CLOSED_CONNECTION_ERRORS = ("tornado.iostream.StreamClosedError",
                            "tornado.websocket.WebSocketClosedError")
#: Server log lines that report a failure without a traceback.
LOG_FAILURES = re.compile(r"dashboard update failed|Failed to run session destroy hooks|"
                          r"came back to life|dashboard worker .* stopped|"
                          r"Error running application handler|"
                          r"callback .* failed with following error")


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


def worker_pids(pid: int) -> set[int]:
    """The pids of the server's worker processes (``multiprocessing``'s: spawned, or forked
    by its fork server, which shares their command line; not the fork server itself nor
    the resource tracker)."""
    found, order, commands = set(), [pid], {}
    parent_of: dict[int, int] = {}
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                ppid = int(Path(f"/proc/{entry}/stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry))
            parent_of[int(entry)] = ppid
    for p in order:
        order.extend(children.get(p, []))
        try:
            commands[p] = cmd = Path(f"/proc/{p}/cmdline").read_bytes()
        except OSError:
            continue
        forked = b"forkserver" in cmd and b"forkserver" in commands.get(parent_of.get(p), b"")
        if p != pid and (b"spawn_main" in cmd or forked):
            found.add(p)
    return found


def settled_rss_mb(pid: int, processes: int | None = None, timeout_s: float = 60.0,
                   steady_mb: float = 2.0) -> dict:
    """``tree_rss_mb`` once the server's worker processes have started and loaded the
    kernel: the process count stays the same (and equals ``processes`` when given, its
    count at the start) and the total changes by less than ``steady_mb`` over three
    samples 1 s apart. The server starts its workers in the background, and replaces idle
    ones after the class left (``app.pages.release_memory``); fresh ones take a few seconds
    to load. After ``timeout_s`` the last reading, as it is."""
    deadline = time.monotonic() + timeout_s
    readings = [tree_rss_mb(pid)]
    while time.monotonic() < deadline:
        time.sleep(1.0)
        readings = (readings + [tree_rss_mb(pid)])[-3:]
        totals = [r["total"] for r in readings]
        counts = {r["processes"] for r in readings}
        if len(readings) == 3 and len(counts) == 1 \
                and processes in (None, readings[-1]["processes"]) \
                and max(totals) - min(totals) < steady_mb:
            break
    return readings[-1]


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




# ------------------------------------------------------------------------------ browsers

def browser_pages(url: str, n: int, duration: float, result: dict) -> None:
    """``n`` Chromium pages (one browser, a context each) pressing theta0's arrow keys."""
    try:
        from playwright.sync_api import sync_playwright

        from checkout import helper
        tools, serving = helper("browser/page_tools"), helper("browser/serving")
    except (ImportError, FileNotFoundError) as exc:
        result["errors"] = [f"browser pages unavailable: {exc}"]
        return
    result.update(latencies=[], errors=[], open_s=[], presses=0, peak_rss_mb=0.0)
    with sync_playwright() as pw:
        browser = serving.launch_chromium(pw)
        start, cpu0 = time.perf_counter(), chromium_usage()[0]
        try:
            pages = []
            for _ in range(n):
                page = browser.new_context(viewport=serving.VIEWPORT).new_page()
                page.on("pageerror", lambda e: result["errors"].append(f"page error: {e}"))
                t0 = time.perf_counter()
                tools.wait_for_app(page, url, timeout_ms=90_000)
                # The server's busy page reloads itself until the server admits it.
                busy = tools.wait_for_busy_page_to_pass(page)
                if busy:
                    result["busy_pages"] = result.get("busy_pages", 0) + busy
                    tools.wait_for_rendered(page, timeout_ms=90_000)
                opened = time.perf_counter() - t0
                result["open_s"].append(opened)
                pages.append((page, tools.slider_handle(page, css_class="ctl-theta0")))
            for page, _ in pages:
                tools.settle(page, quiet_ms=300)
            start, cpu0 = time.perf_counter(), chromium_usage()[0]  # key presses only
            until, i = time.perf_counter() + duration, 0
            while time.perf_counter() < until:
                page, handle = pages[i % n]
                key = "ArrowRight" if i % 4 < 2 else "ArrowLeft"
                m = tools.measure_slider_latency(page, handle, key, names=["orbit"],
                                                 timeout_s=UPDATE_TIMEOUT_S)
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
