"""Where the server's time goes during a load test (``load_test.py --profile``): py-spy
(a sampling profiler: ``pip install -e ".[bench]"``) records the ``panel serve`` process and,
with ``--subprocesses``, its worker processes, without changing them; the raw stacks are
summarised by layer (the model, the app's own code, Panel, Bokeh's serialisation,
Tornado and the websocket, the event loop waiting), by the functions that hold most
samples themselves and by the dashboard's functions with all they call (the busy samples
with the function on their stack: what the server would save without it).

    python benchmarks/load_profile.py bench-out/server-profile.txt   # summarise a record
"""
from __future__ import annotations

import collections
import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

#: The work pool's watchdog: a loop that sleeps between its checks, sampled as if busy.
WATCHDOG = "work-pool watchdog (a sleeping loop)"
#: Frames that identify a layer, tried in order on each stack from the innermost frame out.
LAYERS = (
    (WATCHDOG, re.compile(r"^WorkPool\._watch \(")),
    ("model (numerics)", re.compile(r"\((model/|numba/|scipy/)")),
    ("pickling results between processes", re.compile(r"\((multiprocessing/|concurrent/futures/process|pickle)")),
    ("Bokeh serialisation (JSON, buffers)", re.compile(
        r"\((bokeh/core/serialization|bokeh/protocol|json/|bokeh/core/json_encoder)")),
    ("Bokeh document and models", re.compile(r"\(bokeh/")),
    ("Panel", re.compile(r"\(panel/")),
    ("param", re.compile(r"\(param/")),
    ("app (dashboard code)", re.compile(r"\(app/")),
    ("Tornado, websocket, HTTP", re.compile(r"\((tornado/|asyncio/)")),
)
#: The innermost frame of a sample in which a thread waits for something to do: the event
#: loop's selector (py-spy names it with its class: ``EpollSelector.select``), the process
#: pool's manager thread polling its pipes, a thread waiting on a condition.
IDLE = re.compile(r"^(\w+\.)?(select|poll|epoll|_run_once|wait) "
                  r"\((selectors|asyncio/base_events|threading)")


class ServerProfiler:
    """``py-spy record`` on ``pid`` (and its children) until ``stop()``; raw stacks to
    ``path``. ``available`` is False (and nothing runs) without py-spy."""

    def __init__(self, pid: int, path: Path, subprocesses: bool = True, rate: int = 100):
        self.path = Path(path)
        self.exe = shutil.which("py-spy") or shutil.which(
            "py-spy", path=os.path.dirname(sys.executable))
        self.available = self.exe is not None
        self.process = None
        if self.available:
            command = [self.exe, "record", "-p", str(pid), "-o", str(self.path), "-f", "raw",
                       "-r", str(rate), "--nonblocking"]
            if subprocesses:
                command.append("--subprocesses")
            self.process = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                                            stderr=subprocess.PIPE, text=True)

    def stop(self) -> str:
        """Stop recording; '' when the record was written, else why not."""
        if self.process is None:
            return "py-spy is not installed (pip install py-spy)"
        self.process.send_signal(signal.SIGINT)
        try:
            _, err = self.process.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            self.process.kill()
            return "py-spy did not stop"
        return "" if self.path.exists() else f"py-spy wrote nothing: {err[-500:]}"


def _frames(stack: str) -> list[str]:
    return [f for f in stack.split(";") if f]


#: A frame of the dashboard's code: its function and file, without the line.
APP_FRAME = re.compile(r"^(.+) \((app/[^:]+):\d+\)$")


def summarise(path: Path, top: int = 15) -> dict:
    """Samples by process, layer (innermost matching frame) and self time of functions;
    the server's busy samples by the dashboard functions on their stack (inclusive)."""
    by_process: collections.Counter = collections.Counter()
    layers: dict = collections.defaultdict(collections.Counter)
    functions: collections.Counter = collections.Counter()
    app_functions: collections.Counter = collections.Counter()
    server_busy = 0
    total = 0
    for line in Path(path).read_text(encoding="utf-8", errors="replace").splitlines():
        stack, _, count = line.rpartition(" ")
        if not count.isdigit():
            continue
        n = int(count)
        frames = _frames(stack)
        # A worker's stack hangs below the server's "process" frame with one of its own.
        own = [i for i, f in enumerate(frames) if f.startswith("process ")]
        kind = "workers" if len(own) > 1 else "server"
        frames = frames[own[-1] + 1:] if own else frames
        by_process[kind] += n
        total += n
        inner = frames[-1] if frames else ""
        if IDLE.search(inner) or "(idle)" in stack:
            layer = "idle (waiting)"
        else:
            layer = next((name for f in reversed(frames) for name, rx in LAYERS
                          if rx.search(f)), "other")
            functions[f"{kind}: {inner}"] += n
            if kind == "server" and layer != WATCHDOG:
                server_busy += n
                on_stack = {f"{m[1]} ({m[2]})" for m in map(APP_FRAME.match, frames) if m}
                for name in on_stack:
                    app_functions[name] += n
        layers[kind][layer] += n
    return {"samples": total, "by_process": dict(by_process),
            "layers": {k: dict(v.most_common()) for k, v in layers.items()},
            "top_functions": functions.most_common(top),
            "server_busy": server_busy, "app_inclusive": app_functions.most_common(top)}


def markdown(summary: dict) -> str:
    lines = ["| process | layer (innermost frame) | samples | share of its busy time |",
             "|---|---|---:|---:|"]
    for kind, layers in summary["layers"].items():
        busy = sum(n for name, n in layers.items() if name != "idle (waiting)") or 1
        for name, n in layers.items():
            share = "" if name == "idle (waiting)" else f"{n / busy:.0%}"
            lines.append(f"| {kind} | {name} | {n} | {share} |")
    lines += ["", "| function (self samples, not waiting) | samples |", "|---|---:|"]
    lines += [f"| `{name}` | {n} |" for name, n in summary["top_functions"]]
    busy = summary.get("server_busy") or 0
    if busy and summary.get("app_inclusive"):
        lines += ["", "| dashboard function, with all it calls (server) | samples | "
                  "share of the server's busy time |", "|---|---:|---:|"]
        lines += [f"| `{name}` | {n} | {n / busy:.0%} |"
                  for name, n in summary["app_inclusive"]]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    print(markdown(summarise(Path(sys.argv[1]))))
