"""Frame rate of the browser-side animations in headless Chromium.

Builds the standalone array page (``app.figures.animation_page``, ~100 supports) and the
single-support page with its live energy bars, opens them in headless Chromium (Debian's
/usr/bin/chromium, --no-sandbox --disable-gpu, 1280x720) and measures inside the page:

* ``1x``: the player playing at speed 1x (30 frames/s asked): distinct frames shown per
  second (frames the player handed to the figures) and animation frames per second;
* ``ceiling``: a requestAnimationFrame loop that moves one frame per animation frame:
  the most frames per second the page can draw (main thread and canvas painting);
* ``main thread ms per frame``: Chrome's TaskDuration over the ceiling run per frame
  drawn (1000 / this is the frame rate a free core would allow);
* ``ceiling, all every frame``: the same page with its text readouts, the slider and the
  live N_c/F_T,x panel updated on every frame (``ui_ms=0``) -- the straightforward
  alternative to throttling them, measured in the same run.

Each number is the median [min-max] over ``--repeats`` windows of ``--seconds``.

    python benchmarks/bench_animation.py [--regime pendulum] [--repeats 5] [--seconds 3]
        [--out benchmarks/results/animation.json]
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from model import REGIMES
from app.figures.animation_page import array_document, page_html, support_document

CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--no-sandbox", "--disable-gpu"]
VIEWPORT = {"width": 1280, "height": 720}

_PLAY_JS = """async ([name, ms]) => {
  const d = Bokeh.documents[0];
  const frame = d.get_model_by_name(name + "_frame"), play = d.get_model_by_name(name + "_play");
  const st = window.__mpf_players[frame.id];
  let ticks = 0, run = true;
  const count = () => { ticks += 1; if (run) requestAnimationFrame(count); };
  requestAnimationFrame(count);
  const drawn0 = st.drawn, t0 = performance.now();
  play.active = true;
  await new Promise((r) => setTimeout(r, ms));
  play.active = false; run = false;
  const s = (performance.now() - t0) / 1000;
  return {frames_per_s: (st.drawn - drawn0) / s, animation_frames_per_s: ticks / s};
}"""

_CEILING_JS = """async ([name, ms]) => {
  const d = Bokeh.documents[0];
  const frame = d.get_model_by_name(name + "_frame"), slider = d.get_model_by_name(name + "_slider");
  const st = window.__mpf_players[frame.id];
  let n = 0, start = null;
  await new Promise((res) => {
    const tick = (now) => {
      if (start === null) start = now;
      if (now - start > ms) return res();
      st.show((frame.value + 1) % (slider.end + 1), false);
      n += 1;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  return {frames_per_s: n / (ms / 1000)};
}"""


def _spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "runs": values}


def _fmt(s):
    return f"{s['median']:.1f} [{s['min']:.1f}–{s['max']:.1f}]"


def _task_seconds(cdp) -> float:
    """Main-thread busy time of the page so far (Chrome's TaskDuration metric)."""
    metrics = cdp.send("Performance.getMetrics")["metrics"]
    return next(m["value"] for m in metrics if m["name"] == "TaskDuration")


def measure(page, url, name, repeats, seconds):
    page.goto(url)
    page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0 && window.__mpf_players")
    page.wait_for_timeout(800)
    cdp = page.context.new_cdp_session(page)
    cdp.send("Performance.enable")
    ms = int(seconds * 1000)
    played = [page.evaluate(_PLAY_JS, [name, ms]) for _ in range(repeats)]
    ceiling, busy = [], []
    for _ in range(repeats):
        before = _task_seconds(cdp)
        fps = page.evaluate(_CEILING_JS, [name, ms])["frames_per_s"]
        frames = fps * ms / 1000
        ceiling.append(fps)
        # Busy milliseconds per drawn frame: what a frame costs the page's main thread,
        # less sensitive than frames/s to other work on a shared machine.
        busy.append(1000 * (_task_seconds(cdp) - before) / max(frames, 1))
    return {"1x": _spread([p["frames_per_s"] for p in played]),
            "1x_animation_frames": _spread([p["animation_frames_per_s"] for p in played]),
            "ceiling": _spread(ceiling), "busy_ms_per_frame": _spread(busy)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--regime", default="pendulum", choices=sorted(REGIMES))
    parser.add_argument("--supports", type=int, default=100)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args(argv)
    if not Path(CHROMIUM).exists():
        print(f"{CHROMIUM} is missing", file=sys.stderr)
        return 2
    from playwright.sync_api import sync_playwright

    params = REGIMES[args.regime]
    results = {"regime": args.regime, "viewport": VIEWPORT, "flags": FLAGS,
               "repeats": args.repeats, "seconds": args.seconds,
               "load_average_before": os.getloadavg()}
    with tempfile.TemporaryDirectory() as tmp:
        pages = {}
        t = time.perf_counter()
        doc, motion, _ = array_document(params, n_supports=args.supports)
        results["array"] = {"supports": motion.n_supports, "frames": motion.n_frames,
                            "build_s": time.perf_counter() - t}
        pages["array"] = page_html(doc)
        doc, _, _ = array_document(params, n_supports=args.supports, ui_ms=0)
        pages["array_dom_every_frame"] = page_html(doc)
        doc, _, player = support_document(params)
        results["support"] = {"frames": player.n_frames}
        pages["support"] = page_html(doc)
        urls = {}
        for key, html in pages.items():
            path = Path(tmp) / f"{key}.html"
            path.write_text(html, encoding="utf-8")
            urls[key] = path.as_uri()
            results[key + "_html_mb"] = len(html.encode()) / 1e6
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
            page = browser.new_page(viewport=VIEWPORT)
            results["array"].update(measure(page, urls["array"], "array_player",
                                            args.repeats, args.seconds))
            results["array_dom_every_frame"] = measure(page, urls["array_dom_every_frame"],
                                                       "array_player", args.repeats, args.seconds)
            results["support"].update(measure(page, urls["support"], "support_player",
                                              args.repeats, args.seconds))
            browser.close()
    results["load_average_after"] = os.getloadavg()
    a, b, s = results["array"], results["array_dom_every_frame"], results["support"]
    print("load average (1, 5, 15 min) before: %.1f %.1f %.1f, after: %.1f %.1f %.1f"
          % (*results["load_average_before"], *results["load_average_after"]))
    print(f"array ({a['supports']} supports, {a['frames']} frames, {results['array_html_mb']:.1f} MB "
          f"page, built in {a['build_s']:.2f} s), frames/s, median [min-max] of {args.repeats}:")
    print(f"  playing at 1x (30 asked)      {_fmt(a['1x'])}")
    print(f"  ceiling                       {_fmt(a['ceiling'])}   "
          f"(main thread {_fmt(a['busy_ms_per_frame'])} ms per frame)")
    print(f"  ceiling, all every frame      {_fmt(b['ceiling'])}   "
          f"(main thread {_fmt(b['busy_ms_per_frame'])} ms per frame)")
    print(f"support + live energy ({s['frames']} frames):")
    print(f"  playing at 1x (30 asked)      {_fmt(s['1x'])}")
    print(f"  ceiling                       {_fmt(s['ceiling'])}   "
          f"(main thread {_fmt(s['busy_ms_per_frame'])} ms per frame)")
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
