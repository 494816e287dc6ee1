"""What opening the dashboard costs: one page at a time, in headless Chromium.

    python benchmarks/bench_page_open.py [--opens 5] [--url http://127.0.0.1:5006 ...] [--out DIR]

Without ``--url`` this checkout's dashboard is served (``panel serve app`` on a free port);
each ``--url`` is a dashboard already served on this machine (for example another
checkout's, started there with its own environment), measured as it is. A page is opened
``--opens`` times on each, each in a fresh browser context, waiting until the document is
rendered and its sources at rest (the first open, which warms the server, is not counted).
Per open: the server process's CPU (user + system, its worker processes not included) and
the wall time from navigation to the page at rest. With several ``--url`` the opens
alternate between the servers (same machine, same moment: e.g. ``main`` against a
branch's worktree).

Writes DIR/page_open.json and prints median [min-max] per checkout. Numbers measured
while other jobs run are not trustworthy: note the load average printed with them.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import time
from pathlib import Path

import psutil

from checkout import helper
from machine import loadavg
from spread import cell, spread


def _cpu_s(process: psutil.Process) -> float:
    times = process.cpu_times()
    return times.user + times.system


def _server_process(base: str) -> psutil.Process:
    port = base.rstrip("/").rsplit(":", 1)[1]
    for conn in psutil.net_connections("tcp"):
        if conn.status == psutil.CONN_LISTEN and str(conn.laddr.port) == port and conn.pid:
            return psutil.Process(conn.pid)
    raise RuntimeError(f"no process of this machine listens at {base}: give the URL of a "
                       "dashboard served here (panel serve app --port PORT)")


def run(urls: list[str], opens: int, out: Path) -> dict:
    serving, tools = helper("browser/serving"), helper("browser/page_tools")
    from playwright.sync_api import sync_playwright

    out.mkdir(parents=True, exist_ok=True)
    load0 = loadavg()
    with contextlib.ExitStack() as stack:
        if not urls:
            urls = [stack.enter_context(serving.serve_app(out / "page-open-server.log"))]
        servers = {url.rstrip("/"): _server_process(url) for url in urls}
        rows = {url: [] for url in servers}
        playwright = stack.enter_context(sync_playwright())
        browser = serving.launch_chromium(playwright)
        stack.callback(browser.close)
        for i in range(opens + 1):
            for url, process in servers.items():
                context = browser.new_context(viewport=serving.VIEWPORT)
                page = context.new_page()
                cpu0, t0 = _cpu_s(process), time.perf_counter()
                tools.wait_for_app(page, f"{url}/app?theta0_deg={20 + 7 * i}")
                tools.settle(page)
                wall, cpu = time.perf_counter() - t0, _cpu_s(process) - cpu0
                context.close()
                if i:  # the first open warms the server
                    rows[url].append({"server_cpu_s": cpu, "open_s": wall})
                time.sleep(1.0)  # the closed page's messages drained
    report = {"opens": opens, "load_average": {"start": load0, "end": loadavg()},
              "servers": {url: {key: spread(r[key] for r in got)
                                for key in ("server_cpu_s", "open_s")} | {"runs": got}
                          for url, got in rows.items()}}
    (out / "page_open.json").write_text(json.dumps(report, indent=1))
    return report


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--opens", type=int, default=5)
    ap.add_argument("--url", action="append", default=[],
                    help="a dashboard served on this machine (repeat to alternate; default: "
                         "this checkout's, served here)")
    ap.add_argument("--out", type=Path, default=Path("bench-out"))
    args = ap.parse_args()
    for url in args.url:
        if not url.startswith("http://") or not url.rstrip("/").rsplit(":", 1)[-1].isdigit():
            ap.error(f"--url {url!r}: give the server's address with its port, e.g. "
                     "http://127.0.0.1:5006")
    if args.opens < 1:
        ap.error(f"--opens {args.opens}: give at least 1")
    report = run(args.url, args.opens, args.out)
    load = report["load_average"]
    print(f"{args.opens} opens each, load average {load['start'][0]:.1f} -> {load['end'][0]:.1f}")
    for url, got in report["servers"].items():
        c, w = got["server_cpu_s"], got["open_s"]
        print(f"{url}: server CPU per open {cell(c['median'], c['min'], c['max'], lambda v: f'{v:.2f}')} s; "
              f"open -> at rest {cell(w['median'], w['min'], w['max'], lambda v: f'{v:.2f}')} s")
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    raise SystemExit(main())
