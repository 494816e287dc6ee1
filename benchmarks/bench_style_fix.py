"""What BokehJS's rewrite of unchanged ``<style>`` elements costs the browser at each slider
key press in the served dashboard, with the page's fix (``app/offline/bokeh_fix.js``,
applied by ``app.edge.page_js``) and with BokehJS's own method put back.

    python benchmarks/bench_style_fix.py [--rounds 4] [--presses 6] [--quick] [--url URL]
                                         [--out DIR]

The dashboard is served (``panel serve app``; ``--url``: the one served there) and opened
once in Debian's headless Chromium (1280x720, the One support tab). Its θ₀ slider is then
pressed right and left in turn (the server answers from its cache after the first two:
what is measured is the browser's work). Each round makes ``--presses`` presses with the
fix and as many with BokehJS's own method, in alternating order. For each press: the
page's renderer time from Chrome's performance counters (``Performance.getMetrics``: all
its tasks, its scripts, its style recalculations and layouts) from the key press until the
page's data has been still for 0.3 s, and the page's ``<style>`` rewrites with their own
text and with another. Median [min-max] over the presses of each arm.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import sys
import time
from pathlib import Path

from checkout import helper
from machine import loadavg, machine
from spread import spread

#: Chrome's counters read (seconds, summed over the page's renderer), and their names here.
COUNTERS = {"TaskDuration": "task_ms", "ScriptDuration": "script_ms",
            "RecalcStyleDuration": "style_ms", "LayoutDuration": "layout_ms"}
ARMS = ("fix", "own")
#: The sizes of ``--quick`` (for CI): one round of two presses per arm.
QUICK = {"rounds": 1, "presses": 2}


def _counters(cdp) -> dict:
    found = {m["name"]: m["value"] for m in cdp.send("Performance.getMetrics")["metrics"]}
    return {key: found[name] * 1e3 for name, key in COUNTERS.items()}


def _press(page, cdp, handle, key: str, tools, watch: dict) -> dict:
    """One key press on ``handle``: the renderer's milliseconds and the style rewrites."""
    page.evaluate(watch["WATCH"])
    before, counted = tools.data_sources(page), _counters(cdp)
    handle.press(key)
    if not tools.wait_for_data_change(page, before):
        raise RuntimeError(f"the page's data did not change after {key} on θ₀")
    tools.settle(page, quiet_ms=300)
    after = _counters(cdp)
    writes = page.evaluate("window.styleWrites")
    return {**{k: after[k] - counted[k] for k in counted},
            "same_writes": writes["same"], "changed_writes": writes["changed"]}


def run(rounds: int = 4, presses: int = 6, out: Path | str = "bench-out",
        url: str | None = None) -> dict:
    serving, tools = helper("browser/serving"), helper("browser/page_tools")
    watch = vars(helper("browser/style_watch"))
    from playwright.sync_api import sync_playwright

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    load0 = loadavg()
    found = {arm: [] for arm in ARMS}
    with contextlib.ExitStack() as stack:
        base = url.rstrip("/") if url else stack.enter_context(
            serving.serve_app(out / "style-fix-server.log"))
        playwright = stack.enter_context(sync_playwright())
        browser = serving.launch_chromium(playwright)
        try:
            context = browser.new_context(viewport=serving.VIEWPORT)
            page = context.new_page()
            tools.wait_for_app(page, f"{base}/app")
            tools.settle(page)
            fix = page.evaluate("({applied: MicropillarBokehFix.applied, "
                                "reason: MicropillarBokehFix.reason})")
            if not fix["applied"]:
                raise RuntimeError(f"the page's BokehJS fix is not applied: {fix['reason']}")
            cdp = context.new_cdp_session(page)
            cdp.send("Performance.enable")
            handle = tools.slider_handle(page, css_class="ctl-theta0")
            handle.focus()
            keys = ("ArrowRight", "ArrowLeft")
            for arm in ARMS:  # both states of θ₀ computed, and each arm's code warmed
                page.evaluate(watch["USE"], arm == "own")
                for key in keys:
                    _press(page, cdp, handle, key, tools, watch)
            for i in range(rounds):
                for arm in (ARMS if i % 2 == 0 else ARMS[::-1]):
                    page.evaluate(watch["USE"], arm == "own")
                    for j in range(presses):
                        found[arm].append(_press(page, cdp, handle, keys[j % 2], tools, watch))
            context.close()
        finally:
            browser.close()
    report = {"rounds": rounds, "presses": presses,
              **{arm: {key: spread(p[key] for p in found[arm]) for key in found[arm][0]}
                 for arm in ARMS},
              "runs": found, "machine": machine(),
              "load_average": {"start": load0, "end": loadavg()},
              "date": time.strftime("%Y-%m-%d %H:%M")}
    (out / "bench_style_fix.json").write_text(json.dumps(report, indent=1))
    return report


def text(found: dict) -> str:
    def f(s, digits=1):
        return f"{s['median']:.{digits}f} [{s['min']:.{digits}f}-{s['max']:.{digits}f}]"
    load = found["load_average"]
    lines = [f"A θ₀ key press in the served dashboard, {found['rounds']} rounds of "
             f"{found['presses']} presses per arm ({found['date']}, load {load['start'][0]:.1f}"
             f"-{load['end'][0]:.1f}); the renderer's ms per press, median [min-max]:",
             "| arm | all tasks | scripts | style recalculation | layout "
             "| <style> rewrites, same text | changed text |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for arm, label in (("fix", "with the page's fix"), ("own", "BokehJS's own method")):
        s = found[arm]
        lines.append(f"| {label} | {f(s['task_ms'])} | {f(s['script_ms'])} | "
                     f"{f(s['style_ms'])} | {f(s['layout_ms'])} | {f(s['same_writes'], 0)} | "
                     f"{f(s['changed_writes'], 0)} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=4, help="rounds, each arm once (4)")
    ap.add_argument("--presses", type=int, default=6, help="key presses per arm and round (6)")
    ap.add_argument("--quick", action="store_true",
                    help=f"{QUICK['rounds']} round of {QUICK['presses']} presses (for CI)")
    ap.add_argument("--url", default=None,
                    help="a dashboard already served, e.g. http://127.0.0.1:5006 (default: "
                         "serve this checkout's app)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    if args.url is not None and not args.url.startswith(("http://", "https://")):
        ap.error(f"--url {args.url!r}: give the server's address, e.g. http://127.0.0.1:5006")
    sizes = dict(QUICK) if args.quick else {"rounds": args.rounds, "presses": args.presses}
    for name, value in sizes.items():
        if value < 1:
            ap.error(f"--{name} {value}: give at least 1")
    found = run(**sizes, out=args.out, url=args.url)
    print(text(found))
    return 0


if __name__ == "__main__":
    sys.exit(main())
