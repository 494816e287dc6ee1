"""Load test of the dashboard: N concurrent sessions moving sliders against one server.

    python benchmarks/load_test.py [--sessions 30] [--duration 60] [--drag-duration S]
                                   [--profiles class,drag] [--profile] [--out DIR] [--quick]

``panel serve app`` is started on a loopback port (``tests/browser/serving.serve_app``)
with a short unused-session lifetime, so closed sessions are cleaned up within the run.

**Clients.** Each session is a protocol-level browser stand-in, all of them in one
asyncio loop of this process: it loads the page over HTTP (``GET /app``: the server
builds the session's document and embeds its token, as for a browser), opens the
session's websocket with that token, pulls the document (Bokeh's ``PULL-DOC``) into a
local replica and then behaves like a page: a slider move is the ``PATCH-DOC`` message
BokehJS sends (the slider model's ``value`` and ``value_throttled`` for a key press or a
drag's end, ``value`` alone for a drag's positions on the way), and every
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

**What a session does.** Two profiles, one round of ``--sessions`` each (``--profiles``):

* ``class`` (round 1, ``--duration``): a class at the controls, open loop -- every session
  moves one slider (theta0, k_r, k_theta or F_N, to a random position on the slider's
  grid) every 2-4 s (mean 3 s, a random phase per session), on its own schedule whether
  or not the previous move's data has arrived. A move's latency runs from its message
  leaving the client (serialised and written to the websocket) to the client reading the
  first server patch that carries the orbit's data, before applying it (this Python
  client's own costs -- ~50 ms to serialise a patch against its copy of the ~400-model
  page, ~55 ms to apply one -- are a browser's work in a browser; the latency until the
  client had applied the data is reported beside it) (for theta0: once the fixed-array
  readout shows the requested angle, so a stale result cannot count); a move overtaken by
  a later one before its data came counts until the later one's data arrives.
* ``drag`` (round 2, ``--drag-duration``): continuous dragging, closed loop -- move, wait
  until the server has pushed the new data, pause 0.2-0.8 s, repeat; one theta0 move in
  five is a drag (four positions 30 ms apart), timed from its last position.
* ``drags`` (``--profiles class,drags``): the same closed loop with every move a theta0
  drag, the most updates whose last position must reach the page. A last position never
  shown within ``UPDATE_TIMEOUT_S`` is an error: Panel once left a change queued until the
  page's next one (``app/edge.py``, guard 3), ~1 drag in 500 under a class's load.

(Every session first sends Bokeh's ``document_ready`` event, as BokehJS does once the page
is drawn: Panel holds a session's model updates until then.) ``--profile`` records the
server and its workers with py-spy during round 1's slider moves and adds where the time
went (``load_profile.py``).

**Reported.** p50/p95/max update latency; page open time (GET + websocket + pull; all
sessions connect from 127.0.0.1, like a class behind one address, so the server's page
gate may answer a busy page, which the client reloads after 1 s: that wait counts, and
the busy pages are counted);
errors (failed or stalled sessions, protocol errors, tracebacks in the server log);
the resident memory (RSS) of the server process and of its worker processes: at the
start (the baseline: the server is up and its worker processes have loaded the kernel),
peak during the rounds, after round 1's sessions were closed and cleaned up (the class has
left), and after round 2; and whether the server destroyed every session (its log names
each discarded session and counts the open ones). The classroom targets of issue 13
(slider -> new data p95 <= 500 ms, page open p95 <= 5 s, 0 errors, memory after the class
left <= 1.1 x the baseline) are reported as met or not.

**Memory checks.** (1) After cleanup the total RSS is within ``max(150 MB, 25 %)`` of the
baseline (the target, 1.1 x, is reported beside it). (2) The second round adds at most
``max(20 MB, 25 %)`` of what the first round's sessions took at its peak. CPython keeps the
memory of destroyed sessions in its allocator for reuse instead of returning it to the
system (measured: a session's document is freed -- counted in the server with ``gc`` -- yet
the RSS stays near its peak: its small-object arenas are freed only when wholly empty).
Once the last session ended, the server cuts its shared results down to
``IDLE_CACHE_BYTES`` and replaces its idle worker processes by fresh ones
(``app.pages.release_memory``), so what stays is the server's own heap; "after" is read
once the fresh workers have loaded, and (3) checks that the workers were replaced. So (1)
bounds what stays, and (2) tells retention from a leak: leaked sessions would add about a
round's worth again.

Writes DIR/load.md and DIR/load.json (default DIR: bench-out); exits 1 when a check
fails (errors, sessions without updates, memory not back, workers not replaced, sessions
not destroyed).
"""
from __future__ import annotations

import argparse
import asyncio
import json
import math
import os
import sys
import threading
import time
from pathlib import Path

import numpy as np

from app.pages import RELEASE_DELAY_S
from load_client import (CLASS_GAP_S, DRAG_PROBABILITY, OPEN_STEPS, PROFILES, REPLICAS,
                         THINK_S, UPDATE_TIMEOUT_S)
from checkout import helper
from load_class import LoopLag, drive
from load_profile import ServerProfiler, summarise
from load_report import (TARGET_MEMORY_FACTOR, leak_bound, markdown,
                         memory_bound, targets)
from load_probe import (MemorySampler, browser_pages, discarded_sessions,
                        log_failures, log_tracebacks, server_pid, settled_rss_mb, tree_cpu_s,
                        wait_for_cleanup, worker_pids)

#: The server looks for unused sessions every second and destroys those without a
#: connection for 5 s (Bokeh's default is 15 s; shorter, so cleanup happens within the run,
#: but longer than a page takes to load here, so no session is destroyed before its
#: websocket connects).
CHECK_UNUSED_MS, UNUSED_LIFETIME_MS = 1000, 5000
SERVE_ARGS = ("--check-unused-sessions", str(CHECK_UNUSED_MS),
              "--unused-session-lifetime", str(UNUSED_LIFETIME_MS),
              "--stats-log-frequency", "1000", "--log-level", "debug")
#: The allocator settings of the image (Dockerfile ENV), with which the server runs as
#: deployed; ``--allocator python`` serves with CPython's own allocator instead.
ALLOCATOR_KEYS = ("PYTHONMALLOC", "MALLOC_ARENA_MAX")


def server_env(allocator: str = "image") -> dict[str, str]:
    """The environment the server is given on top of this process's: the image's allocator
    settings (``allocator="image"``) or CPython's own (``"python"``)."""
    if allocator == "python":
        return {"PYTHONMALLOC": "pymalloc", "MALLOC_ARENA_MAX": ""}
    if allocator != "image":
        raise ValueError(f"allocator {allocator!r}: give 'image' or 'python'")
    replay = helper("dockerfile_replay")
    env = replay.image_env(replay.dockerfile())
    return {key: env[key] for key in ALLOCATOR_KEYS if key in env}


# ------------------------------------------------------------------------------ run

def percentiles(seconds) -> dict:
    a = np.asarray(seconds, dtype=float) * 1e3
    if a.size == 0:
        return {"n": 0, "p50_ms": math.nan, "p95_ms": math.nan, "max_ms": math.nan}
    return {"n": int(a.size), "p50_ms": float(np.percentile(a, 50)),
            "p95_ms": float(np.percentile(a, 95)), "max_ms": float(a.max())}


def run(sessions: int = 30, duration: float = 60.0, out: Path | str = "bench-out",
        browsers: int = 0, seed: int = 1, cleanup_timeout: float = 60.0,
        app_dir: str = "app", drag_duration: float | None = None,
        profiles: tuple[str, ...] = ("class", "drag"), profile: bool = False,
        allocator: str = "image", replica: str = "watched") -> dict:
    """Serve the app, drive a round of ``sessions`` per profile in ``profiles`` (the first
    for ``duration`` s, the next for ``drag_duration``, default ``duration``; one profile
    alone is repeated for a third of the time), and return (and write) the report."""
    if len(profiles) == 1:
        profiles = (profiles[0], profiles[0])
        drag_duration = drag_duration or max(5.0, duration / 3)
    durations = (duration, drag_duration or duration)
    app = Path(app_dir).name
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    log_path = out / "load-panel-serve.log"
    client_cpu0 = time.process_time()
    t0, phases = time.perf_counter(), {}

    def phase(name: str) -> None:
        phases[name] = round(time.perf_counter() - t0, 1)
    rounds = []
    extra_env = server_env(allocator)
    serve_app = helper("browser/serving").serve_app
    with serve_app(log_path, app_dir=app_dir, extra_args=SERVE_ARGS, env=extra_env) as base:
        phase("server up")
        pid = server_pid(int(base.rsplit(":", 1)[1]))
        # The server is up, its workers started and loaded the kernel; no page built yet.
        baseline = settled_rss_mb(pid)
        log_start = log_path.stat().st_size
        browser: dict = {}
        for i, (name, seconds) in enumerate(zip(profiles, durations)):
            rounds.append(_round(base, app, pid, baseline["processes"], log_path, name,
                                 sessions, seconds, seed + i,
                                 cleanup_timeout, replica=replica,
                                 browsers=browsers if i == 0 else 0,
                                 browser=browser, profile_path=(
                                     out / "server-profile.txt" if profile and i == 0
                                     else None)))
            phase(f"round {i + 1} ({name}) cleaned up")
        raw = log_path.read_bytes()
        text = raw[log_start:].decode("utf-8", errors="replace")
        first = rounds[0]
        early = discarded_sessions(
            raw[log_start:first.pop("log_offset")].decode("utf-8", errors="replace")) & set(
            first["ids"])
        rounds[1].pop("log_offset")
    client_cpu_total = time.process_time() - client_cpu0
    phase("server stopped")

    session_errors = [f"round {i + 1} ({r['profile']}), {e}"
                      for i, r in enumerate(rounds) for e in r.pop("errors")]
    tracebacks = log_tracebacks(text)
    failures = log_failures(text)
    errors = session_errors + [f"server: {t}" for t in tracebacks + failures] + [
        f"browser: {e}" for e in browser.get("errors", [])]
    after, after_again = rounds[0]["memory_after"], rounds[1]["memory_after"]
    peak = max((r["memory_peak"] for r in rounds if r["memory_peak"]),
               key=lambda m: m["total"], default=None)
    bound = memory_bound(baseline["total"])
    growth_bound = leak_bound(baseline["total"], (rounds[0]["memory_peak"] or baseline)["total"])
    report = {
        "settings": {"sessions": sessions, "durations_s": list(durations),
                     "profiles": list(profiles),
                     "profile_descriptions": {p: PROFILES[p] for p in profiles},
                     "browsers": browsers, "seed": seed, "think_s": THINK_S,
                     "class_gap_s": CLASS_GAP_S, "drag_probability": DRAG_PROBABILITY,
                     "update_timeout_s": UPDATE_TIMEOUT_S, "serve_args": list(SERVE_ARGS),
                     "allocator": allocator, "server_env": extra_env,
                     "replica": replica, "replica_description": REPLICAS[replica],
                     "cpus": os.cpu_count()},
        "rounds": rounds,
        "errors": errors,
        "n_errors": len(errors),
        "memory_mb": {"baseline": baseline, "peak": peak, "after": after,
                      "after_second_round": after_again, "bound_total": bound,
                      "target_total": TARGET_MEMORY_FACTOR * baseline["total"],
                      "second_round_growth_bound": growth_bound},
        "destroyed_before_close": len(early),
        "client_cpu_s": client_cpu_total,
        "phases_s": phases,
        "browser": {k: (percentiles(v) if k in ("latencies", "open_s") else v)
                    for k, v in browser.items()},
    }
    report["checks"] = {
        "no errors": not errors,
        "every session got updates": all(r["sessions_with_updates"] == sessions
                                         for r in rounds),
        "memory back near baseline": after["total"] <= bound and after_again["total"] <= bound,
        "no growth from a second round": after_again["total"] - after["total"] <= growth_bound,
        "fresh workers after each round": all(r["workers_replaced"] for r in rounds),
        "every session destroyed": all(r["cleanup"]["destroyed"] == sessions
                                       and r["cleanup"]["open_after"] == 0 for r in rounds),
    }
    report["passed"] = all(report["checks"].values())
    report["targets"] = targets(report, [r for r in rounds if r["profile"] == "class"])
    (out / "load.json").write_text(json.dumps(report, indent=1, default=float))
    (out / "load.md").write_text(markdown(report))
    return report


def _round(base, app, pid, processes, log_path, profile, sessions, duration, seed,
           cleanup_timeout, replica="watched",
           browsers=0, browser=None, profile_path=None) -> dict:
    """One round: ``sessions`` open, move sliders in ``profile`` for ``duration`` s and
    close; the server's memory, CPU and log are read around it."""
    sampler = MemorySampler(pid)
    sampler.start()
    workers_before = worker_pids(pid)
    thread = None
    if browsers:
        thread = threading.Thread(target=browser_pages,
                                  args=(f"{base}/{app}", browsers, duration, browser),
                                  daemon=True)
        thread.start()
    load0 = os.getloadavg()
    profiler = None
    closing: dict = {}
    moving: dict = {}
    lag = LoopLag()

    def opened():
        nonlocal profiler
        moving.update(cpu=tree_cpu_s(pid), client=time.process_time())
        if profile_path:  # the slider moves only, not the page opens
            profiler = ServerProfiler(pid, profile_path)
    driven, elapsed = asyncio.run(drive(
        base, app, sessions, duration, seed, profile=profile, replica=replica, lag=lag,
        on_open=opened,
        before_close=lambda: closing.update(
            offset=log_path.stat().st_size, load=os.getloadavg(),
            cpu=tree_cpu_s(pid) - moving["cpu"],
            client=time.process_time() - moving["client"])))
    if thread is not None:
        thread.join(timeout=duration + 300)
    peak = sampler.stop()
    profiled = None
    if profiler is not None:
        problem = profiler.stop()
        profiled = {"error": problem} if problem else summarise(profiler.path)
    ids = [s.session_id for s in driven if s.session_id]
    cleanup = wait_for_cleanup(log_path, set(ids), cleanup_timeout, app)
    # The server hands the ended sessions' memory back RELEASE_DELAY_S after the last one
    # ended (app.pages.schedule_release) and replaces its idle workers: memory "after" is
    # read once that has happened and the fresh workers have loaded.
    time.sleep(RELEASE_DELAY_S + 2.0)
    after = settled_rss_mb(pid, processes)
    workers_after = worker_pids(pid)
    lat = [x for s in driven for x in s.latencies]
    drag = [x for s in driven for x in s.drag_latencies]
    return {
        "profile": profile, "description": PROFILES[profile], "duration_s": duration,
        "elapsed_s": elapsed,
        "updates": {"move": percentiles(lat), "drag": percentiles(drag),
                    "all": percentiles(lat + drag),
                    # ... and until the Python client had applied the data (its costs)
                    "client": percentiles([x for s in driven for x in s.client_latencies]),
                    "per_session_min": min((len(s.latencies) + len(s.drag_latencies)
                                            for s in driven), default=0),
                    "rate_per_s": (len(lat) + len(drag)) / max(elapsed, 1e-9)},
        "open": percentiles([s.open_s for s in driven if math.isfinite(s.open_s)]),
        "open_steps": {k: percentiles([s.open_steps[k] for s in driven if k in s.open_steps])
                       for k in OPEN_STEPS},
        "busy_pages": sum(s.busy_pages for s in driven),
        "sessions_with_updates": sum(1 for s in driven if s.latencies or s.drag_latencies),
        "errors": [f"session {s.index} ({s.session_id[:8]}): {e}" for s in driven
                   for e in s.errors],
        "ids": ids,
        "log_offset": closing["offset"],
        "cleanup": cleanup,
        "memory_peak": peak, "memory_after": after,
        # The server replaces its idle workers once the last session ended.
        "workers_replaced": bool(workers_before) and not workers_before & workers_after,
        "memory_samples": sampler.samples,
        "load_average": {"start": load0, "end": closing["load"]},
        "client_cpu_fraction": closing["client"] / max(elapsed, 1e-9),
        # The clients' event loop: how late it woke a 10 ms sleep while the sliders
        # moved, and the CPU its copies of the page took to apply the server's patches.
        "client_loop_lag": percentiles(lag.lags),
        "client_apply_s": sum(s.apply_s for s in driven),
        "server_cpu_s": dict(zip(("server", "workers"), closing["cpu"].tolist())),
        "server_profile": profiled,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sessions", type=int, default=30, help="concurrent sessions (30)")
    ap.add_argument("--duration", type=float, default=60.0,
                    help="seconds of slider moves in the first round (60)")
    ap.add_argument("--drag-duration", type=float, default=None,
                    help="seconds of the second round (default: --duration)")
    ap.add_argument("--profiles", default="class,drag",
                    help=f"rounds, comma-separated, of {sorted(PROFILES)} (class,drag)")
    ap.add_argument("--browsers", type=int, default=0,
                    help="also drive this many headless Chromium pages (0)")
    ap.add_argument("--quick", action="store_true",
                    help="6 sessions, 15 s of class and 6 s of drag (for the tests)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--profile", action="store_true",
                    help="record the server and its workers with py-spy during round 1 "
                         "(DIR/server-profile.txt) and summarise where the time goes")
    ap.add_argument("--app", default="app", help="the app folder to serve (default app)")
    ap.add_argument("--allocator", choices=("image", "python"), default="image",
                    help="the server's memory allocator: the image's settings (Dockerfile "
                         "ENV PYTHONMALLOC, MALLOC_ARENA_MAX; default) or CPython's own")
    ap.add_argument("--replica", choices=sorted(REPLICAS), default="watched",
                    help="how much of each server patch a client applies to its copy of "
                         "the page: " + "; ".join(f"{k}: {v}" for k, v in REPLICAS.items())
                         + " (default watched)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    profiles = tuple(p.strip() for p in args.profiles.split(",") if p.strip())
    unknown = [p for p in profiles if p not in PROFILES] or ([] if 1 <= len(profiles) <= 2
                                                             else ["(one or two)"])
    if unknown:
        ap.error(f"--profiles {args.profiles!r}: unknown {unknown}; "
                 f"give one or two of {sorted(PROFILES)}")
    if args.quick:
        args.sessions, args.duration = 6, 15.0
        args.drag_duration = args.drag_duration or 6.0
    report = run(args.sessions, args.duration, args.out, browsers=args.browsers, seed=args.seed,
                 app_dir=args.app, drag_duration=args.drag_duration, profiles=profiles,
                 profile=args.profile, allocator=args.allocator, replica=args.replica)
    print(markdown(report))
    return 0 if report["passed"] else 1


if __name__ == "__main__":
    sys.exit(main())
