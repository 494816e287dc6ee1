"""Health under abuse: uncached worst-case page requests against one server while its
health check runs and an ordinary visitor opens the page.

    python benchmarks/load_abuse.py [--requests 20] [--out DIR] [--quick]

``panel serve app`` is started on 127.0.0.1 as in the Docker image (``--liveness``,
unused sessions kept 60 s, the image's allocator settings). Once its worker processes
have started and loaded the kernel (right after a start they take both cores for a second
or two; ``workers_ready_s`` in the report), at once:

* **the abuse**: ``--requests`` plain ``GET /app?...`` from 127.0.0.3, all uncached and
  as expensive as the controls allow: half of them the hardest single support (theta0 a
  hair off the axis, soft springs, the largest load, rtol 1e-7), half the Polar tab of
  the slider regime at the largest load (a sweep), each with its own F_N so nothing is
  shared. They never open the page's websocket, as a script hammering the URL would not.
* **the health check**: ``python -m app.healthcheck`` (the Docker HEALTHCHECK command)
  runs from 127.0.0.1, as inside the container while visitors come from other
  addresses: with the burst, then every ``HEALTHCHECK_GAP_S`` s; each run must exit 0
  (it needs the real dashboard: the "busy" page of a client with too many unopened
  pages has another title).
* **a liveness probe**: ``GET /liveness`` every ``PROBE_INTERVAL_S``; each must answer 200
  within ``LIVENESS_BOUND_S``.
* **an ordinary visitor**: after ``VISITOR_DELAY_S``, a protocol-level page
  (``load_client.Session``: GET, websocket, pull, the page's ``document_ready``) with
  uncached but ordinary parameters, opened from **127.0.0.2**: another client to the
  server, so the work pool's turns between clients are what is tested (from 127.0.0.1 it
  would share the abuser's turn). Its first plot (the orbit drawn with data) must come
  within ``FIRST_PLOT_BOUND_S`` of its page request.

Afterwards the server log must hold no traceback. Writes DIR/abuse.md and
DIR/abuse.json; exits 1 when a check fails.
"""
from __future__ import annotations

import argparse
import asyncio
import json
import os
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
from tornado.httpclient import AsyncHTTPClient, HTTPRequest

from checkout import helper
from load_client import Session
from load_probe import log_failures, log_tracebacks, server_pid, settled_rss_mb
from load_test import server_env

#: As the Docker image's CMD (Dockerfile): unused sessions are kept a minute.
SERVE_ARGS = ("--check-unused-sessions", "10000", "--unused-session-lifetime", "60000")
LIVENESS_BOUND_S = 1.0
FIRST_PLOT_BOUND_S = 5.0
PROBE_INTERVAL_S = 0.2
#: Seconds between two health checks (Docker's interval is 30 s; the first starts with
#: the burst).
HEALTHCHECK_GAP_S = 5.0
#: The "Polar sweep CSV" button answers within this (never waits for the sweep) ...
DOWNLOAD_BOUND_S = 1.0
#: ... and delivers the sweep within this (its budget, 6 s, and a queue).
CSV_WITHIN_S = 30.0
VISITOR_DELAY_S = 0.5
VISITOR_SOURCE = "127.0.0.2"
ABUSER_SOURCE = "127.0.0.3"
#: Uncached but ordinary: a support of the stiff regime at a load no other request uses.
VISITOR_QUERY = "?k_r=0.8&k_theta=0.9&F_N=1.37&theta0_deg=37"
#: Worst cases (issue 13): the hardest support, and the Polar tab's sweep.
WORST_SUPPORT = "?k_r=0.0183455&k_theta=0.0962579&F_N={F_N}&rtol=1e-7&theta0_deg=179.99999999999963"
WORST_POLAR = "?regime=slider&F_N={F_N}&rtol=1e-8&theta0_deg=179.9999999999&tab=polar"


def worst_queries(n: int) -> list[str]:
    """``n`` worst-case queries, alternately support and polar, each with its own F_N."""
    return [(WORST_SUPPORT if i % 2 == 0 else WORST_POLAR).format(F_N=f"{9.99 - 0.01 * i:.2f}")
            for i in range(n)]


class Prober(threading.Thread):
    """``GET url`` every ``interval`` s until stopped: (seconds, status) of each."""

    def __init__(self, url: str, interval: float = PROBE_INTERVAL_S, timeout: float = 30.0):
        super().__init__(daemon=True)
        self.url, self.interval, self.timeout = url, interval, timeout
        self.results: list[tuple[float, int | None]] = []
        #: Wall-clock time (``time.time``) each probe was sent, to set beside the server's
        #: trace (``MICROPILLAR_TRACE``).
        self.sent: list[float] = []
        self._halt = threading.Event()

    def run(self):
        while not self._halt.is_set():
            start = time.perf_counter()
            self.sent.append(time.time())
            try:
                with urllib.request.urlopen(self.url, timeout=self.timeout) as r:
                    status = r.status
            except urllib.error.HTTPError as e:
                status = e.code
            except (urllib.error.URLError, OSError):
                status = None
            self.results.append((time.perf_counter() - start, status))
            self._halt.wait(self.interval)

    def stop(self):
        self._halt.set()
        self.join(timeout=self.timeout + 5)


class HealthChecks(threading.Thread):
    """``python -m app.healthcheck base`` in a loop: (seconds, exit code, stderr)."""

    def __init__(self, base: str):
        super().__init__(daemon=True)
        self.base = base
        self.results: list[tuple[float, int, str]] = []
        self._halt = threading.Event()

    def run(self):
        while not self._halt.is_set():
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-m", "app.healthcheck", self.base,
                                   "--timeout", "25"], capture_output=True,
                                  text=True, timeout=120)
            self.results.append((time.perf_counter() - start, done.returncode,
                                 done.stderr.strip()[-300:]))
            self._halt.wait(HEALTHCHECK_GAP_S)

    def stop(self):
        self._halt.set()
        self.join(timeout=150)


async def _abuse_and_visit(base: str, queries: list[str]) -> dict:
    client = AsyncHTTPClient(max_clients=len(queries) + 4)

    async def get(query: str):
        start = time.perf_counter()
        try:
            r = await client.fetch(HTTPRequest(f"{base}/app{query}", request_timeout=120,
                                               network_interface=ABUSER_SOURCE),
                                   raise_error=False)
            busy = b"The server is busy" in (r.body or b"") or b"(busy)" in (r.body or b"")
            return time.perf_counter() - start, f"{r.code} busy page" if busy else r.code
        except Exception as exc:  # noqa: BLE001 - reported
            return time.perf_counter() - start, f"{type(exc).__name__}: {exc}"

    async def visit():
        await asyncio.sleep(VISITOR_DELAY_S)
        visitor = Session(0, base, query=VISITOR_QUERY, source=VISITOR_SOURCE)
        out = {"first_plot_s": None, "open_s": None, "compute_answer_s": None,
               "downloads": [], "error": ""}
        try:
            await visitor.open()
            out["open_s"] = visitor.open_s
            out["first_plot_s"] = await visitor.first_plot()
            # The polar CSV while the abuse goes on. Off its tab the sweep is not computed
            # by itself: its button asks for it ("Compute polar sweep CSV"), and must answer
            # at once (the download button shows "computing…"); the file comes once the
            # sweep is there.
            if visitor.visible("download-polar-compute"):
                start = time.perf_counter()
                await visitor.click("download-polar-compute")
                while visitor.visible("download-polar-compute") and (
                        time.perf_counter() - start < CSV_WITHIN_S):
                    await visitor.changed(CSV_WITHIN_S)
                out["compute_answer_s"] = time.perf_counter() - start
            deadline = time.perf_counter() + CSV_WITHIN_S
            while not visitor.enabled("download-polar") and time.perf_counter() < deadline:
                await visitor.changed(deadline - time.perf_counter())
            seconds, text = await visitor.download("download-polar")
            rows = [l for l in text.splitlines() if l and not l.startswith("#")]
            out["downloads"].append({"seconds": seconds, "rows": max(0, len(rows) - 1),
                                     "note": "" if rows else text.strip()[:120]})
        except Exception as exc:  # noqa: BLE001 - reported
            out["error"] = f"{type(exc).__name__}: {exc}"
        finally:
            await visitor.close()
        return out

    results = await asyncio.gather(visit(), *(get(q) for q in queries))
    return {"visitor": results[0], "abuse": [{"query": q, "seconds": s, "status": c}
                                             for q, (s, c) in zip(queries, results[1:])]}


def run(requests: int = 20, out: Path | str = "bench-out", settle_s: float = 5.0) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    log_path = out / "abuse-panel-serve.log"
    load0 = os.getloadavg()
    serve_app = helper("browser/serving").serve_app
    with serve_app(log_path, extra_args=SERVE_ARGS, env=server_env()) as base:
        # The burst comes once the server's worker processes have started and loaded the
        # kernel (seconds after a start, when they take both cores for ~1-2 s).
        ready = time.perf_counter()
        settled_rss_mb(server_pid(int(base.rsplit(":", 1)[1])))
        ready = time.perf_counter() - ready
        log_start = log_path.stat().st_size
        checks = HealthChecks(base)
        probe = Prober(f"{base}/liveness")
        probe.start()
        checks.start()
        start = time.perf_counter()
        driven = asyncio.run(_abuse_and_visit(base, worst_queries(requests)))
        burst_s = time.perf_counter() - start
        time.sleep(settle_s)  # the probes go on while the queued work drains
        probe.stop()
        checks.stop()
        text = log_path.read_bytes()[log_start:].decode("utf-8", errors="replace")
    liveness = [s for s, _ in probe.results]
    bad_liveness = [(round(s, 2), c) for s, c in probe.results
                    if c != 200 or s > LIVENESS_BOUND_S]
    visitor = driven["visitor"]
    server_errors = log_tracebacks(text) + log_failures(text)
    report = {
        "settings": {"requests": requests, "visitor_query": VISITOR_QUERY,
                     "abuser_source": ABUSER_SOURCE,
                     "visitor_source": VISITOR_SOURCE, "serve_args": list(SERVE_ARGS),
                     "cpus": os.cpu_count(), "load_average_start": load0,
                     "load_average_end": os.getloadavg()},
        "burst_s": burst_s, "workers_ready_s": ready,
        "abuse": driven["abuse"],
        "visitor": visitor,
        "liveness": {"n": len(liveness), "max_s": max(liveness, default=float("nan")),
                     "p95_s": float(np.percentile(liveness, 95)) if liveness else float("nan"),
                     "seconds": [round(x, 4) for x in liveness],
                     "sent_at": [round(t, 3) for t in probe.sent],
                     "over_bound_or_failed": bad_liveness},
        "healthchecks": [{"seconds": s, "exit": c, "stderr": e} for s, c, e in checks.results],
        "server_errors": server_errors,
    }
    report["checks"] = {
        "health check green": bool(checks.results) and all(c == 0 for _, c, _ in checks.results),
        f"/liveness within {LIVENESS_BOUND_S:g} s": bool(liveness) and not bad_liveness,
        f"ordinary visitor's first plot within {FIRST_PLOT_BOUND_S:g} s": (
            visitor["first_plot_s"] is not None
            and visitor["first_plot_s"] <= FIRST_PLOT_BOUND_S),
        f"polar CSV buttons answer within {DOWNLOAD_BOUND_S:g} s": bool(
            visitor["downloads"]) and all(d["seconds"] <= DOWNLOAD_BOUND_S
                                          for d in visitor["downloads"]) and (
            visitor["compute_answer_s"] is None
            or visitor["compute_answer_s"] <= DOWNLOAD_BOUND_S),
        "polar CSV delivered with its rows": bool(visitor["downloads"]) and (
            visitor["downloads"][-1]["rows"] > 0),
        "no server errors": not server_errors,
    }
    report["passed"] = all(report["checks"].values())
    (out / "abuse.json").write_text(json.dumps(report, indent=1, default=str))
    (out / "abuse.md").write_text(markdown(report))
    return report


def markdown(r: dict) -> str:
    s, v, lv = r["settings"], r["visitor"], r["liveness"]
    statuses: dict = {}
    for a in r["abuse"]:
        statuses[str(a["status"])] = statuses.get(str(a["status"]), 0) + 1
    slowest = max((a["seconds"] for a in r["abuse"]), default=float("nan"))
    hc = r["healthchecks"]
    lines = [
        "# Health under abuse", "",
        f"{s['requests']} uncached worst-case `GET /app?...` at once (half the hardest "
        "support, half the Polar tab's sweep, each with its own F_N), from 127.0.0.3, on "
        f"{s['cpus']} cores (load average {s['load_average_start'][0]:.1f} at the start, "
        f"{s['load_average_end'][0]:.1f} at the end).", "",
        f"- abusive requests answered: {statuses} (the slowest in {slowest:.2f} s); the burst "
        f"took {r['burst_s']:.1f} s; it began once the workers were ready "
        f"({r.get('workers_ready_s', float('nan')):.1f} s after the server answered)",
        f"- `/liveness`: {lv['n']} probes, slowest {lv['max_s']:.2f} s, p95 "
        f"{lv.get('p95_s', float('nan')):.2f} s; over "
        f"{LIVENESS_BOUND_S:g} s or failed: {lv['over_bound_or_failed'] or 'none'}",
        f"- health check (`python -m app.healthcheck`): {len(hc)} runs, exit codes "
        f"{[h['exit'] for h in hc]}, slowest {max((h['seconds'] for h in hc), default=0):.1f} s"
        + "".join(f"; {h['stderr']}" for h in hc if h["exit"]),
        f"- ordinary visitor from {s['visitor_source']} (`{s['visitor_query']}`): page open "
        + (f"{v['open_s']:.2f} s" if v["open_s"] is not None else "none") + ", first plot "
        + (f"{v['first_plot_s']:.2f} s" if v["first_plot_s"] is not None else "none")
        + (f" ({v['error']})" if v["error"] else ""),
        "- its polar CSV: 'Compute' answered in "
        + (f"{v['compute_answer_s']:.2f} s" if v.get("compute_answer_s") is not None
           else "- (not asked)") + "; the download: "
        + ("; ".join(f"{d['seconds']:.2f} s -> " + (f"{d['rows']} rows" if d["rows"]
                                                      else repr(d["note"][:60]))
                     for d in v["downloads"]) or "no answer"),
        f"- server errors: {r['server_errors'] or 'none'}", "",
        "| check | result |", "|---|---|"]
    lines += [f"| {k} | {'pass' if ok else 'FAIL'} |" for k, ok in r["checks"].items()]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--requests", type=int, default=20, help="worst-case GETs (20)")
    ap.add_argument("--quick", action="store_true", help="8 requests (for the tests)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    report = run(8 if args.quick else args.requests, args.out)
    print(markdown(report))
    return 0 if report["passed"] else 1


if __name__ == "__main__":
    sys.exit(main())
