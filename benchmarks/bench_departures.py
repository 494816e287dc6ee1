"""What the visitors still there see while others leave one by one.

A class rarely leaves at once: in a lab, visitors close their pages one after another
while others keep working. The server collects a closed page's memory with one full
collection (``app.heap.settle``), a pause of the event loop in proportion to every page
still open. ``app.pages.settle_due`` defers it while the closed pages are few against the
open ones (``MICROPILLAR_SETTLE_FRACTION``, default 0.5); the alternative measured in the
same run is the collection at every departure (the setting 0).

For each setting the dashboard is served as the load test serves it (its short
unused-session lifetime, so a closed page's session ends within seconds; the image's
allocator settings), ``--sessions``
protocol-level pages (``load_client.Session``) are opened and, ``--leave`` times, one
page closes and the others wait until its memory would have been collected (the session's
end plus ``RELEASE_DELAY_S``), while one remaining page moves a slider every 0.5 s and
``/liveness`` is asked every 50 ms. Reported per setting: the liveness answers and the
slider moves (new data pushed), median [min-max], the answers slower than 0.25 s, and the
server's resident memory at the end (what the deferred pages still hold).

    python benchmarks/bench_departures.py                 # 30 pages, 3 leave, ~3 min
    python benchmarks/bench_departures.py --quick         # 4 pages, 1 leaves (for CI)
"""
from __future__ import annotations

import argparse
import asyncio
import json
import sys
import time
import urllib.request
from pathlib import Path

from checkout import helper
from load_client import Session
from load_probe import server_pid
from load_test import CHECK_UNUSED_MS, SERVE_ARGS, UNUSED_LIFETIME_MS, server_env
from machine import loadavg, machine
from spread import spread

from app.pages import RELEASE_DELAY_S

#: The settings compared: the default and a collection at every departure.
SETTINGS = {"deferred (0.5)": "0.5", "at every departure (0)": "0"}
#: An answer slower than this counts as a pause a visitor notices (s).
SLOW_S = 0.25
QUICK = {"sessions": 4, "leave": 1}


async def _liveness(base: str, stop: asyncio.Event, answers: list) -> None:
    loop = asyncio.get_running_loop()

    def ask() -> None:
        with urllib.request.urlopen(f"{base}/liveness", timeout=30) as reply:
            reply.read()
    while not stop.is_set():
        start = time.perf_counter()
        await loop.run_in_executor(None, ask)
        answers.append(time.perf_counter() - start)
        await asyncio.sleep(0.05)


async def _departures(base: str, sessions: int, leave: int) -> dict:
    pages = [Session(i, base, "app", seed=i) for i in range(sessions)]
    for page in pages:
        await page.open()
        await page.first_plot()
    await asyncio.sleep(2.0)
    stop, answers, moves = asyncio.Event(), [], []
    asking = asyncio.create_task(_liveness(base, stop, answers))
    worker = pages[-1]  # stays to the end
    wait_s = (UNUSED_LIFETIME_MS + CHECK_UNUSED_MS) / 1e3 + RELEASE_DELAY_S + 2.0
    try:
        for page in pages[:leave]:
            await page.close()
            end = time.monotonic() + wait_s
            while time.monotonic() < end:
                before = len(worker.latencies)
                await worker.move(drags=False)
                moves.extend(worker.latencies[before:])
                await asyncio.sleep(0.5)
    finally:
        stop.set()
        await asking
    for page in pages[leave:]:
        await page.close()
    return {"liveness_s": answers, "moves_s": moves}


def _rss_mb(pid: int) -> float:
    import psutil
    return psutil.Process(pid).memory_info().rss / 2**20


def run(sessions: int = 30, leave: int = 3, out: Path = Path("bench-out")) -> dict:
    """Each setting served in turn, the same departures; the findings per setting."""
    serve_app = helper("browser/serving").serve_app
    found = {"sessions": sessions, "leave": leave, "machine": machine(),
             "load_average": loadavg()[0], "settings": {}}
    for name, value in SETTINGS.items():
        log = out / f"departures-{value}.log"
        with serve_app(log, extra_args=SERVE_ARGS,
                       env={**server_env(), "MICROPILLAR_SETTLE_FRACTION": value}) as base:
            pid = server_pid(int(base.rsplit(":", 1)[1]))
            seen = asyncio.run(_departures(base, sessions, leave))
            seen["rss_mb"] = _rss_mb(pid)
        live, moves = seen["liveness_s"], seen["moves_s"]
        found["settings"][name] = {
            "liveness": spread(live), "moves": spread(moves) if moves else None,
            "slow_answers": sum(x > SLOW_S for x in live),
            "slow_moves": sum(x > SLOW_S for x in moves), "rss_mb": seen["rss_mb"]}
    return found


def text(found: dict) -> str:
    def ms(s: dict | None) -> str:
        if not s:
            return "none"
        return f"{1e3 * s['median']:.0f} [{1e3 * s['min']:.0f}-{1e3 * s['max']:.0f}] ms"
    lines = [f"{found['leave']} of {found['sessions']} pages leaving one by one "
             f"({found['machine']['date']}, {found['machine']['cpu']}, "
             f"{found['machine']['cores']} cores, load {found['load_average']:.1f} at the "
             "start); median [min-max]:"]
    for name, s in found["settings"].items():
        lines.append(
            f"  collected {name}: /liveness {ms(s['liveness'])} ({s['liveness']['n']} asked, "
            f"{s['slow_answers']} over {1e3 * SLOW_S:.0f} ms); slider -> new data "
            f"{ms(s['moves'])} ({s['slow_moves']} over {1e3 * SLOW_S:.0f} ms); server "
            f"{s['rss_mb']:.0f} MB at the end")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sessions", type=int, default=30, help="pages open (30)")
    ap.add_argument("--leave", type=int, default=3, help="pages that leave, one by one (3)")
    ap.add_argument("--quick", action="store_true",
                    help=f"{QUICK['sessions']} pages, {QUICK['leave']} leaves (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    sizes = dict(QUICK) if args.quick else {"sessions": args.sessions, "leave": args.leave}
    if sizes["sessions"] < 2 or not 1 <= sizes["leave"] < sizes["sessions"]:
        ap.error(f"--sessions {sizes['sessions']} --leave {sizes['leave']}: give at least "
                 "2 pages and leave at least 1, fewer than the pages")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    found = run(**sizes, out=out)
    (out / "bench_departures.json").write_text(json.dumps(found, indent=1))
    print(text(found))
    return 0


if __name__ == "__main__":
    sys.exit(main())
