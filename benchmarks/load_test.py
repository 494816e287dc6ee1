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
import json
import math
import os
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from tests.browser.serving import serve_app  # noqa: E402
from load_client import (DRAG_PROBABILITY, DRAG_STEPS, THINK_S, UPDATE_TIMEOUT_S,  # noqa: E402
                         drive)
from load_probe import (MemorySampler, browser_pages, discarded_sessions,  # noqa: E402
                        log_failures, log_tracebacks, server_pid, tree_cpu_s, tree_rss_mb,
                        wait_for_cleanup)

#: The server looks for unused sessions every second and destroys those without a
#: connection for 5 s (Bokeh's default is 15 s; shorter, so cleanup happens within the run,
#: but longer than a page takes to load here, so no session is destroyed before its
#: websocket connects).
CHECK_UNUSED_MS, UNUSED_LIFETIME_MS = 1000, 5000
SERVE_ARGS = ("--check-unused-sessions", str(CHECK_UNUSED_MS),
              "--unused-session-lifetime", str(UNUSED_LIFETIME_MS),
              "--stats-log-frequency", "1000", "--log-level", "debug")
MEMORY_BOUND_MB, MEMORY_BOUND_FRACTION = 150.0, 0.25
LEAK_BOUND_MB, LEAK_BOUND_FRACTION = 20.0, 0.25


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

