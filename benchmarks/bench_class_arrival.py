"""A class arriving at once: N pages opened at the same moment, and when each is whole.

    python benchmarks/bench_class_arrival.py [--pages 10] [--rounds 3] [--chromium]
                                             [--url URL ...] [--out DIR]

Without ``--url`` this checkout's dashboard is served (``panel serve app`` on a free port,
with the load test's server options); each ``--url`` is a dashboard already served on
this machine (another checkout's, started there with its own environment), measured as it
is. Each round opens ``--pages`` protocol-level browser stand-ins (``load_client.Session``)
together on each server in turn (servers alternate, so each is measured at the same
moment of the machine): the page, its websocket, its document and the browser's
"rendered", all at once, as when a teacher gives the class the link. Per page: seconds
from its request until its dashboard had arrived and was applied (``open_s``, as in the
load test) and until its dashboard's first message was read; then every page's first
plot is awaited (its seconds from the page request reported too) and the pages closed.

With ``--chromium`` the pages are headless Chromium pages (one browser, a context each),
timed from navigation until the dashboard is in the page: what a class sees, browsers'
own work included (here on the server's cores). Each context sends an address of its own
in ``X-Forwarded-For``, as devices behind the lab's reverse proxy: the server this script
starts reads it (``--use-xheaders``); a ``--url`` server must be started with it too, or
the pages are one client to it and its page gate sends some to the busy page first.

The load test opens its class two pages at a time (people arriving over some seconds):
with a fixed number of pages in flight, the mean time a page takes is set by the server's
throughput alone, whatever order it builds them in. Here they all arrive at once, and
the order decides who waits (``app.page_lane``).

Prints per server p50, p95 and max of the pages' open times over all rounds, and each
round's median as median [min-max] over the rounds; writes DIR/class_arrival.json. Quiet
machine only: note the load average printed with them.
"""
from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import time
from pathlib import Path

import numpy as np

from app.views.page import DASHBOARD_CLASS
from checkout import helper
from load_client import OPEN_TIMEOUT_S, Session
from load_test import SERVE_ARGS
from machine import loadavg
from spread import cell, spread

#: Seconds after closing a round's pages for the server to end their sessions (the load
#: test's unused-session lifetime is 5 s) before the next round.
SETTLE_S = 8.0


async def _round(base: str, pages: int, seed: int) -> dict:
    # Each from a loopback address of its own (127.0.0.10, .11, ...): a device each, as in
    # a class on the school's network (behind one address the page gate would turn some
    # away to the busy page, and they would come back: app.pages).
    sessions = [Session(i, base, seed=seed, replica="watched", source=f"127.0.0.{10 + i}")
                for i in range(pages)]
    errors: list[str] = []
    firsts: list[float] = []

    async def one(session: Session):
        try:
            await session.open()
            firsts.append(await session.first_plot(timeout=OPEN_TIMEOUT_S))
        except Exception as exc:  # noqa: BLE001 - counted, reported
            errors.append(f"{type(exc).__name__}: {exc}")
    await asyncio.gather(*(one(s) for s in sessions))
    result = {"open_s": [s.open_s for s in sessions if s.open_s == s.open_s],
              "first_part_s": [s.open_steps["dashboard read"] for s in sessions
                               if "dashboard read" in s.open_steps],
              "first_plot_s": firsts,
              "busy_pages": sum(s.busy_pages for s in sessions),
              "errors": errors + [e for s in sessions for e in s.errors]}
    await asyncio.gather(*(s.close() for s in sessions))
    return result


async def _chromium_round(base: str, pages: int) -> dict:
    from playwright.async_api import async_playwright
    serving = helper("browser/serving")
    selector = f".{DASHBOARD_CLASS}"
    errors: list[str] = []
    async with async_playwright() as pw:
        browser = await pw.chromium.launch(executable_path=serving.CHROMIUM,
                                           args=serving.CHROMIUM_FLAGS, headless=True)
        # A device each behind the lab's proxy: its address in X-Forwarded-For, which the
        # server reads with --use-xheaders (as behind the reverse proxy: docs/deploying.md).
        tabs = [await (await browser.new_context(
            viewport=serving.VIEWPORT,
            extra_http_headers={"X-Forwarded-For": f"10.0.0.{10 + i}"})).new_page()
            for i in range(pages)]
        busy = []  # the busy page shown (the page gate took them for one client)
        for tab in tabs:
            tab.on("framenavigated", lambda frame: busy.append(frame.url)
                   if "/static/busy.html" in frame.url else None)
        start = time.perf_counter()

        async def one(tab):
            try:
                await tab.goto(f"{base}/app", timeout=OPEN_TIMEOUT_S * 1e3)
                await tab.wait_for_selector(selector, state="attached",
                                            timeout=OPEN_TIMEOUT_S * 1e3)
                return time.perf_counter() - start
            except Exception as exc:  # noqa: BLE001 - counted, reported
                errors.append(f"{type(exc).__name__}: {exc}"[:300])
                return None
        opened = await asyncio.gather(*(one(tab) for tab in tabs))
        await browser.close()
    return {"open_s": [t for t in opened if t is not None], "first_part_s": [],
            "first_plot_s": [], "busy_pages": len(busy), "errors": errors}


def run(urls: list[str], pages: int, rounds: int, chromium: bool = False) -> dict:
    load0 = loadavg()
    runs: dict[str, list[dict]] = {url: [] for url in urls}
    for r in range(rounds):
        for url in urls:
            runs[url].append(asyncio.run(_chromium_round(url, pages) if chromium
                                         else _round(url, pages, seed=r)))
            time.sleep(SETTLE_S)
    report = {"pages": pages, "rounds": rounds, "chromium": chromium,
              "load_average": {"start": load0, "end": loadavg()}, "servers": {}}
    for url, rows in runs.items():
        opens = np.concatenate([r["open_s"] for r in rows])
        firsts = np.concatenate([r["first_plot_s"] for r in rows])  # none in --chromium
        report["servers"][url] = {
            "open_p50_s": float(np.percentile(opens, 50)),
            "open_p95_s": float(np.percentile(opens, 95)),
            "open_max_s": float(opens.max()),
            "round_median_open_s": spread(float(np.median(r["open_s"])) for r in rows),
            "round_max_open_s": spread(max(r["open_s"]) for r in rows),
            "first_plot_p50_s": float(np.percentile(firsts, 50)) if firsts.size else None,
            "rounds": rows, "errors": [e for r in rows for e in r["errors"]]}
    return report


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pages", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--chromium", action="store_true",
                    help="headless Chromium pages, from one address (default: protocol-level "
                         "stand-ins, an address each)")
    ap.add_argument("--url", action="append", default=[],
                    help="a dashboard served on this machine (repeat to compare)")
    ap.add_argument("--out", type=Path, default=Path("bench-out"))
    args = ap.parse_args()
    if not 1 <= args.pages <= 240 or args.rounds < 1:
        ap.error(f"--pages {args.pages} --rounds {args.rounds}: give 1-240 pages (one "
                 "loopback address each) and at least one round")
    args.out.mkdir(parents=True, exist_ok=True)
    with contextlib.ExitStack() as stack:
        urls = list(args.url)
        if not urls:
            serve_app = helper("browser/serving").serve_app
            urls = [stack.enter_context(serve_app(args.out / "class-arrival-serve.log",
                                                  extra_args=(*SERVE_ARGS, "--use-xheaders")))]
        report = run(urls, args.pages, args.rounds, args.chromium)
    (args.out / "class_arrival.json").write_text(json.dumps(report, indent=1))
    la = report["load_average"]
    kind = "Chromium pages" if args.chromium else "pages"
    print(f"{args.pages} {kind} opened at once, {args.rounds} rounds; load average "
          f"{la['start'][0]:.2f} at the start, {la['end'][0]:.2f} at the end")
    for url, s in report["servers"].items():
        med, top = s["round_median_open_s"], s["round_max_open_s"]
        first = s["first_plot_p50_s"]
        plot = f" (first plot p50 {first:.2f} s)" if first is not None else ""
        busy = f"; busy pages {sum(r['busy_pages'] for r in s['rounds'])}"
        print(f"{url}: page open p50 {s['open_p50_s']:.2f} s, p95 {s['open_p95_s']:.2f} s, "
              f"max {s['open_max_s']:.2f} s{plot}; a round's median "
              f"{cell(med['median'], med['min'], med['max'])} s, its last page "
              f"{cell(top['median'], top['min'], top['max'])} s{busy}; "
              f"errors {len(s['errors'])}")


if __name__ == "__main__":
    main()
