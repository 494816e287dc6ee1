"""Dashboard latency: server-side compute per view, and slider-to-redraw in a browser.

    python benchmarks/bench_dashboard.py [--quick] [--out DIR]

1. Server side, in this process (what each view's worker computes): the support view
   (``app.worker.compute_support``: fixed array with self-consistent beta + 400-sample
   trajectory) and the polar view (``orientation_table`` over the dashboard's theta0
   grid), each over random slider positions, uncached.
2. In headless Chromium (Debian's ``/usr/bin/chromium`` through Playwright, as the
   browser tests): ``panel serve app`` is started, the page load time is taken, and the
   theta0 slider is moved by key presses; each press is timed from ``keydown`` until the
   orbit data has changed (``change``) and until the next frame is painted (``paint``).

Writes DIR/dashboard.md and DIR/dashboard.json; prints the table.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
# The served app imports `model` too: the repository on the path of child processes as well.
os.environ["PYTHONPATH"] = os.pathsep.join(
    [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])

from app.compute import POLAR_THETA0  # noqa: E402
from app.worker import compute_support  # noqa: E402
from model import Params  # noqa: E402
from model.support import _simulate  # noqa: E402
from model.sweeps import orientation_table  # noqa: E402
from model.uniform import _uniform  # noqa: E402


def percentiles(samples) -> dict:
    a = np.asarray(samples, dtype=float)
    return {"n": int(a.size), "p50_ms": float(np.percentile(a, 50)), "min_ms": float(a.min()),
            "p95_ms": float(np.percentile(a, 95)), "max_ms": float(a.max())}


def random_params(rng, n):
    """Slider positions: log-uniform stiffness and load, uniform theta0."""
    for _ in range(n):
        yield Params(k_r=10 ** rng.uniform(-2, np.log10(3)), k_theta=10 ** rng.uniform(-2, np.log10(3)),
                     F_N=10 ** rng.uniform(-1, 1), theta0=rng.uniform(0, 2 * np.pi))


def server_side(n: int) -> dict:
    rng = np.random.default_rng(7)
    compute_support(Params(3.0, 0.01))  # compiled kernel loaded
    support, polar = [], []
    for p in random_params(rng, n):
        _simulate.cache_clear()
        start = time.perf_counter()
        compute_support(p)
        support.append((time.perf_counter() - start) * 1e3)
        _uniform.cache_clear()
        start = time.perf_counter()
        orientation_table(p.replace(theta0=np.pi / 2), theta0=POLAR_THETA0)
        polar.append((time.perf_counter() - start) * 1e3)
    return {"support view compute": percentiles(support), "polar view compute": percentiles(polar)}


def browser_side(presses: int, out: Path) -> dict:
    from tests.browser.page_tools import measure_slider_latency, settle, slider_handle, wait_for_app
    from tests.browser.serving import launch_chromium, serve_app
    from playwright.sync_api import sync_playwright

    with serve_app(out / "bench-panel-serve.log") as base, sync_playwright() as pw:
        browser = launch_chromium(pw)
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        load_s = wait_for_app(page, f"{base}/app")
        settle(page)
        handle = slider_handle(page, css_class="ctl-theta0")
        change, paint = [], []
        for i in range(presses):
            m = measure_slider_latency(page, handle, "ArrowRight" if i % 2 == 0 else "ArrowLeft",
                                       names=["orbit"])
            change.append(m["change_ms"])
            paint.append(m["paint_ms"])
            settle(page, quiet_ms=300)
        browser.close()
    return {"page load to rendered (s)": load_s,
            "key press -> orbit data changed": percentiles(change),
            "key press -> redrawn": percentiles(paint)}


def report(server: dict, browser: dict) -> str:
    lines = ["# Dashboard latency", "", "| measurement | n | median ms [min–max] | p95 ms |",
             "|---|---:|---|---:|"]
    for name, s in {**server, **{k: v for k, v in browser.items() if isinstance(v, dict)}}.items():
        lines.append(f"| {name} | {s['n']} | {s['p50_ms']:.1f} [{s['min_ms']:.1f}–{s['max_ms']:.1f}] | "
                     f"{s['p95_ms']:.1f} |")
    if browser:
        lines += ["", f"page load to a rendered document: {browser['page load to rendered (s)']:.2f} s "
                  "(one load)"]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer samples (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    ap.add_argument("--no-browser", action="store_true", help="server-side part only")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    server = server_side(8 if args.quick else 40)
    phases = {"server side": time.perf_counter() - start}
    start = time.perf_counter()
    browser = {} if args.no_browser else browser_side(6 if args.quick else 30, out)
    phases["browser (server start, page load, key presses)"] = time.perf_counter() - start
    text = report(server, browser)
    (out / "dashboard.md").write_text(text)
    (out / "dashboard.json").write_text(json.dumps({"server": server, "browser": browser,
                                                    "phases_wall_s": phases}, indent=1))
    print(text)


if __name__ == "__main__":
    main()
