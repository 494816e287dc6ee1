"""Dashboard latency: server-side compute per view, and slider-to-redraw in a browser.

    python benchmarks/bench_dashboard.py [--quick] [--out DIR]

1. Server side, in this process (what each view's worker computes): the support view
   (``app.worker.compute_support``: fixed array with self-consistent beta + 400-sample
   trajectory) and the polar view (``orientation_table`` over the dashboard's theta0
   grid), each over random slider positions, uncached.
2. The server's own cost, in this process (CPU time): building one page (the dashboard,
   its Bokeh models, the document's JSON the browser pulls), and one slider move (the
   state change, the result applied to the views, the patch Bokeh sends: its JSON and
   its binary buffers -- numpy arrays travel as binary -- and their sizes), the result
   itself taken from the shared cache so the compute is not counted twice; beside it, the
   same changes serialised one message each, as Bokeh's ``unhold()`` sends them (what
   one ``pn.io.hold`` saves).
3. With ``--served K``, the same served (``served_moves.py``): ``panel serve app`` and K
   protocol-level sessions moving sliders; the server process's CPU per move, with the
   messages and binary arrays each move pushes (everything the server does for a
   browser's move: the incoming message, Panel, the results applied, the messages sent).
4. In headless Chromium (Debian's ``/usr/bin/chromium`` through Playwright, as the
   browser tests): ``panel serve app`` is started, the page load time is taken, and the
   theta0 slider is moved by key presses; each press is timed from ``keydown`` until the
   orbit data has changed (``change``) and until the next frame is painted (``paint``),
   and along the way (``timeline``): the server's trace (``app.trace``: it receives the
   event, submits the job, a worker starts and ends it, the result is applied and its
   message sent) and the page's first message after that, all on the wall clock.

Writes DIR/dashboard.md and DIR/dashboard.json; prints the table.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from app.worker import POLAR_THETA0
from app.worker import compute_support
from model import Params
from model.contact.support import _simulate
from model.runs.sweeps import orientation_table
from model.arrays.uniform import _uniform


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


def server_cost(n: int) -> dict:
    """CPU ms of a page build and of one slider move's update, and the update's payload."""
    import panel as pn
    from bokeh.document import Document
    from bokeh.protocol import Protocol

    from app.views import Dashboard

    pn.extension("mathjax", notifications=False)
    build, pull, page_kb = [], [], []
    for _ in range(n):
        doc = Document()
        start = time.process_time()
        page = Dashboard()
        doc.add_root(page.__panel__().get_root(doc))
        build.append((time.process_time() - start) * 1e3)
        start = time.process_time()
        text = json.dumps(doc.to_json(), default=str)
        pull.append((time.process_time() - start) * 1e3)
        page_kb.append(len(text) / 1e3)
    events = []

    class Recorder:
        def _document_patched(self, event):
            events.append(event)
    doc.callbacks.on_change_dispatch_to(Recorder())
    protocol = Protocol()
    rng = np.random.default_rng(3)
    moves = {"theta0": [], "k_r": []}
    for i in range(2 * n):
        name = "theta0" if i % 2 == 0 else "k_r"
        value = float(rng.integers(0, 360)) if name == "theta0" else float(
            10 ** rng.uniform(-2, np.log10(3)))
        events.clear()
        setattr(page.state, name, value)  # computed (cached after the first time)
        setattr(page.state, name, value * 0.999 + 1e-3)
        events.clear()
        start = time.process_time()
        setattr(page.state, name, value)  # the result from the shared cache
        serialise = time.process_time()
        message = protocol.create("PATCH-DOC", list(events))  # as pn.io.hold sends them
        content = message.content_json
        cpu = (time.process_time() - start) * 1e3
        one = (time.process_time() - serialise) * 1e3
        buffers = sum(len(b.to_bytes()) for b in message.buffers)
        # What Bokeh's unhold() sends instead: one message per change.
        start = time.process_time()
        for event in events:
            protocol.create("PATCH-DOC", [event]).content_json
        apart = (time.process_time() - start) * 1e3
        moves[name].append((cpu, len(content) / 1e3, buffers / 1e3, len(message.buffers),
                            len(events), apart, one))
    out = {"page build (dashboard + Bokeh models)": percentiles(build),
           "page pull (document JSON)": percentiles(pull),
           "page size kB": float(np.median(page_kb))}
    for name, rows in moves.items():
        a = np.asarray(rows)
        out[f"{name} move: update + patch"] = percentiles(a[:, 0])
        out[f"{name} move: its patch, one message"] = percentiles(a[:, 6])
        out[f"{name} move: its patch, one message per change"] = percentiles(a[:, 5])
        out[f"{name} move payload"] = {"json_kB": float(np.median(a[:, 1])),
                                       "binary_kB": float(np.median(a[:, 2])),
                                       "buffers": int(np.median(a[:, 3])),
                                       "changes": int(np.median(a[:, 4]))}
    return out


#: The stages of one key press, in order: (name, where it is read). Server stages come
#: from the server's trace (``app.trace``), browser ones from the page's clock.
STAGES = ("server receives", "job submitted", "worker starts", "worker ends",
          "result applied", "result sent", "browser receives", "data changed", "drawn")


def timeline(key_s: float, change_ms: float, paint_ms: float, trace: list,
             frames: list) -> dict:
    """Milliseconds after the key press (wall clock ``key_s``) at which each stage of
    ``STAGES`` happened first after the one before it (the interactive lane's job, the
    support result); absent stages are left out."""
    at = {"data changed": key_s + change_ms / 1e3, "drawn": key_s + paint_ms / 1e3}
    wanted = {"worker starts": {"lane": "interactive"}, "worker ends": {"lane": "interactive"},
              "job submitted": {"slot": "support"}, "result applied": {"slot": "support"},
              "result sent": {"slot": "support"}}
    found, after = {}, key_s
    for stage in STAGES:
        if stage in at:
            t = at[stage]
        elif stage == "browser receives":
            # The first frame after the result was applied: the server stamps "result
            # sent" once its write returned, and a loaded machine may deliver it before that.
            since = found.get("result applied", (after - key_s) * 1e3) / 1e3 + key_s
            t = next((f for f in frames if f >= since), None)
        else:
            t = next((e["t"] for e in trace if e["stage"] == stage and e["t"] >= after
                      and all(e.get(k) == v for k, v in wanted.get(stage, {}).items())), None)
        if t is None or t > at["drawn"]:
            continue
        found[stage] = (t - key_s) * 1e3
        after = t
    return found


#: Stamps, in the page, each Bokeh message's first frame (its header names the msgtype).
FRAME_CLOCK_JS = """(() => {
  window.__mpFrames = [];
  const Socket = window.WebSocket;
  window.WebSocket = class extends Socket {
    constructor(...args) {
      super(...args);
      this.addEventListener("message", (event) => {
        if (typeof event.data === "string" && event.data.includes('"msgtype"'))
          window.__mpFrames.push(performance.now());
      });
    }
  };
})();"""


def browser_side(presses: int, out: Path) -> dict:
    from playwright.sync_api import sync_playwright

    from checkout import helper
    tools, serving = helper("browser/page_tools"), helper("browser/serving")
    measure_slider_latency, settle = tools.measure_slider_latency, tools.settle
    slider_handle, wait_for_app = tools.slider_handle, tools.wait_for_app
    launch_chromium, serve_app = serving.launch_chromium, serving.serve_app

    trace_path = out / "bench-trace.jsonl"
    trace_path.unlink(missing_ok=True)
    with serve_app(out / "bench-panel-serve.log",
                   env={"MICROPILLAR_TRACE": str(trace_path.resolve())}) as base, \
            sync_playwright() as pw:
        browser = launch_chromium(pw)
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        # The page's own clock of each message's first frame (a Python-side event would be
        # stamped when Playwright gets round to it, late on a loaded machine).
        page.add_init_script(FRAME_CLOCK_JS)
        load_s = wait_for_app(page, f"{base}/app")
        settle(page)
        handle = slider_handle(page, css_class="ctl-theta0")
        change, paint, presses_at = [], [], []
        for i in range(presses):
            m = measure_slider_latency(page, handle, "ArrowRight" if i % 2 == 0 else "ArrowLeft",
                                       names=["orbit"])
            presses_at.append(page.evaluate("() => (performance.timeOrigin + window.__mpLastKey) / 1e3"))
            change.append(m["change_ms"])
            paint.append(m["paint_ms"])
            settle(page, quiet_ms=300)
        frames = page.evaluate(
            "() => (window.__mpFrames || []).map((t) => (performance.timeOrigin + t) / 1e3)")
        browser.close()
    trace = [json.loads(line) for line in trace_path.read_text().splitlines()] \
        if trace_path.exists() else []
    steps = [timeline(k, c, p, trace, frames) for k, c, p in zip(presses_at, change, paint)]
    stages = {f"key press -> {stage}": percentiles([s[stage] for s in steps if stage in s])
              for stage in STAGES if any(stage in s for s in steps)}
    return {"page load to rendered (s)": load_s,
            "key press -> orbit data changed": percentiles(change),
            "key press -> redrawn": percentiles(paint), **stages}


def report(server: dict, browser: dict, cost: dict | None = None,
           served: dict | None = None) -> str:
    return "# Dashboard latency\n\n" + table(server, browser, cost) + served_text(served)


def served_text(served: dict | None) -> str:
    """The served CPU per move as median [min–max] over blocks, with its payload."""
    if not served:
        return ""
    ms = np.asarray(served["ms"])
    return (f"\nServed, {served['sessions']} sessions, {len(ms)} blocks of "
            f"{served['moves per block']} moves each: the server process's CPU per move "
            f"{np.median(ms):.1f} [{ms.min():.1f}–{ms.max():.1f}] ms; per move "
            f"{np.median(served['messages per move']):.1f} messages, "
            f"{np.median(served['arrays per move']):.1f} binary arrays (load average "
            f"{served['load average'][0]:.1f} before, {served['load average'][1]:.1f} after).\n"
            + profile_text(served.get("profile")))


def profile_text(profiled: dict | None) -> str:
    """Where the served server's time went during the moves (``--served-profile``)."""
    if not profiled:
        return ""
    if "error" in profiled:
        return f"\nNo profile of the served moves: {profiled['error']}\n"
    from load_profile import markdown
    return ("\nWhere the served server's time went during the moves (py-spy samples of its "
            "threads, by the innermost frame's layer):\n\n" + markdown(profiled))


def table(server: dict, browser: dict, cost: dict | None = None) -> str:
    """Each measurement's median [min–max] and p95 in ms, the payloads and the page load."""
    lines = ["| measurement | n | median ms [min–max] | p95 ms |",
             "|---|---:|---|---:|"]
    timings = {k: v for k, v in (cost or {}).items() if isinstance(v, dict) and "n" in v}
    for name, s in {**server, **{f"server CPU: {k}": v for k, v in timings.items()},
                    **{k: v for k, v in browser.items() if isinstance(v, dict)}}.items():
        lines.append(f"| {name} | {s['n']} | {s['p50_ms']:.1f} [{s['min_ms']:.1f}–{s['max_ms']:.1f}] | "
                     f"{s['p95_ms']:.1f} |")
    if cost:
        lines += ["", f"Page: {cost['page size kB']:.0f} kB of document JSON."] + [
            f"{k}: {v['changes']} changes, {v['json_kB']:.1f} kB JSON + {v['binary_kB']:.1f} kB "
            f"in {v['buffers']} binary buffers, sent as one message (``pn.io.hold``)."
            for k, v in cost.items() if isinstance(v, dict) and "json_kB" in v]
    if browser:
        lines += ["", f"page load to a rendered document: {browser['page load to rendered (s)']:.2f} s "
                  "(one load)"]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer samples (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    ap.add_argument("--no-browser", action="store_true", help="server-side part only")
    ap.add_argument("--served", type=int, default=0, metavar="K",
                    help="also serve the app and measure its CPU per move with K sessions")
    ap.add_argument("--served-profile", action="store_true",
                    help="with --served: where the served server's time goes during the "
                         "moves (py-spy; pip install -e \".[bench]\")")
    args = ap.parse_args()
    if args.served_profile and not args.served:
        ap.error("--served-profile needs --served K (the sessions whose moves are profiled)")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    server = server_side(8 if args.quick else 40)
    phases = {"server side": time.perf_counter() - start}
    start = time.perf_counter()
    cost = server_cost(3 if args.quick else 10)
    phases["server cost per page and update"] = time.perf_counter() - start
    served = None
    if args.served:
        from served_moves import served_cost
        start = time.perf_counter()
        served = served_cost(out, sessions=args.served, moves=3 if args.quick else 10,
                             blocks=2 if args.quick else 5, profile=args.served_profile)
        phases["served moves"] = time.perf_counter() - start
    start = time.perf_counter()
    browser = {} if args.no_browser else browser_side(6 if args.quick else 30, out)
    phases["browser (server start, page load, key presses)"] = time.perf_counter() - start
    text = report(server, browser, cost, served)
    (out / "dashboard.md").write_text(text)
    (out / "dashboard.json").write_text(json.dumps({"server": server, "browser": browser,
                                                    "server_cost": cost,
                                                    "served": served,
                                                    "phases_wall_s": phases}, indent=1))
    print(text)


if __name__ == "__main__":
    main()
