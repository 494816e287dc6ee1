"""The offline explorer's speed: one trajectory of the JavaScript kernel in Node and in
Chromium, the page's open-to-first-plot time, slider key press -> redrawn, and per regime
(F_N = 1) the polar sweep (72 orientations) and the uniform array with its
self-consistent beta at tol 1e-3, in Chromium.

    python benchmarks/bench_offline.py [--repeats 30] [--presses 40] [--array-repeats 5]
    python benchmarks/bench_offline.py --file old.html --file new.html --opens 5  # compare

The trajectory is the pendulum at theta0 = pi/2, F_N = 1 at rtol 3e-7 (its exit-state error,
7e-7,
against Python's DOP853 at rtol 1e-13 is printed). Each figure is median [min-max] over
``--repeats`` batches (time per trajectory in a batch of 50, after a warm-up of 300). The
targets (docs/offline.md): one trajectory <= 1 ms; open -> first plot <= 2 s; key press ->
redrawn <= 50 ms p95; file <= 5 MB; per regime, the polar sweep <= 100 ms and the uniform
array with its self-consistent beta <= 1 s (each median [min-max] over ``--array-repeats``
runs on the page's main thread, after the page's own first computations have finished;
the sweep with each orientation's self-consistent beta, as the page draws it, and at
beta = 1). Numbers measured while other jobs run are not
trustworthy: measure on a quiet machine (and with ``busy_core.py`` for a shared server).

Open -> first plot: Playwright's wall time from ``goto`` to the page's ``data-drawn`` (the
first contact computed and drawn), over ``--opens`` loads, and the floor: a page with the
same BokehJS inlined and one empty figure, to its first contentful paint. Key press ->
redrawn (theta0's slider, ``--presses`` presses one at a time): in the page, from the
keydown event's time stamp to the first animation frame after the support's figures
got the new contact (``explorer.keyToSupportMs``), and Playwright's round trip (press,
then wait for ``explorer.drawn``: the texts too) for comparison. With ``--file`` (given
more than once) the benchmark measures packed files instead of packing one, alternating
between them (e.g. one packed from main, one from a branch: same machine, same load),
the arrays too (one run of each regime per file in turn; the polar sweep's contacts
counted).
"""
from __future__ import annotations

import argparse
import json
import math
import shutil
import statistics
import subprocess
import tempfile
import time
from importlib import resources
from pathlib import Path

import numpy as np

CASE = dict(k_r=3.0, k_theta=0.01, F_N=1.0, theta0=math.pi / 2, rtol=3e-7)  # error 7e-7
BATCH, WARMUP = 50, 300
TIMING = """
(function (K, input, batch, warm, repeats) {
  for (let i = 0; i < warm; i++) K.simulate(input);
  const out = [];
  for (let j = 0; j < repeats; j++) {
    const t0 = performance.now();
    for (let i = 0; i < batch; i++) K.simulate(input);
    out.push((performance.now() - t0) / batch);
  }
  return out;
})"""


ARRAYS = """
(function (A, config, repeats) {
  const out = {}, thetas = config.polar_theta0;
  for (const [name, r] of Object.entries(config.regimes)) {
    const base = {k_r: r.k_r, k_theta: r.k_theta, F_N: 1, rtol: 1e-6}, t = {self: [], one: [], uniform: []};
    for (let j = 0; j < repeats; j++) {
      let t0 = performance.now();
      t.sweep_contacts = A.orientationSweep(base, thetas, "self").contacts;
      t.self.push(performance.now() - t0);
      t0 = performance.now();
      A.orientationSweep(base, thetas, 1.0);
      t.one.push(performance.now() - t0);
      t0 = performance.now();
      const u = A.uniformArray({k_r: r.k_r, k_theta: r.k_theta, F_N: 1}, {tol: config.uniform_tol});
      t.uniform.push(performance.now() - t0);
      t.contacts = u.stats.trajectories;
    }
    out[name] = t;
  }
  return out;
})"""


def spread(values, unit="ms", digits=3) -> str:
    v = sorted(values)
    return f"{statistics.median(v):.{digits}f} [{v[0]:.{digits}f}-{v[-1]:.{digits}f}] {unit}"


def exit_error() -> float:
    from model import Params, simulate_support

    kernel = resources.files("app.offline") / "node_simulate.js"
    got = json.loads(subprocess.run(["node", str(kernel)], input=json.dumps([CASE]), text=True,
                                    capture_output=True, check=True).stdout)[0]
    params = Params(**{k: v for k, v in CASE.items() if k != "rtol"})
    ref = simulate_support(params, rtol=1e-13, method="reference")
    return float(np.max(np.abs(np.array(got["state_out"]) - ref.state_out)))


def node_times(repeats: int) -> list[float]:
    kernel = str(resources.files("app.offline") / "kernel.js")
    code = (f"const K = require({json.dumps(kernel)});"
            f"console.log(JSON.stringify({TIMING}(K, {json.dumps(CASE)}, {BATCH}, {WARMUP}, {repeats})))")
    return json.loads(subprocess.run(["node", "-e", code], text=True, capture_output=True,
                                     check=True).stdout)


DRAWN = "document.documentElement.getAttribute('data-drawn') >= '1'"
FCP = ("new Promise((done) => new PerformanceObserver((list, obs) => { for (const e of "
       "list.getEntries()) if (e.name === 'first-contentful-paint') { obs.disconnect(); "
       "done(e.startTime); } }).observe({type: 'paint', buffered: true}))")


def floor_page(path: Path) -> None:
    """The floor of open -> first plot: BokehJS inlined as in the pack, one empty figure."""
    from bokeh.embed import file_html
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    fig = figure(width=300, height=300)
    fig.line([0, 1], [0, 1])
    path.write_text(file_html(fig, resources=INLINE, title="floor"),
                    encoding="utf-8")


def _context(browser):
    context = browser.new_context(viewport={"width": 1280, "height": 720})
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith("file:")
                  else r.abort())
    return context


def open_times(browser, path: Path, ready: str) -> float:
    """Seconds from ``goto`` to ``ready`` (a page function), in a new context."""
    context = _context(browser)
    page = context.new_page()
    t0 = time.perf_counter()
    page.goto(path.as_uri())
    page.wait_for_function(ready, timeout=60_000)
    seconds = time.perf_counter() - t0
    context.close()
    return seconds


#: Snapshot the plotted data (every ColumnDataSource's ``data``) and the ranges' bounds.
SNAPSHOT = """() => {
  const got = new Map();
  for (const m of Bokeh.documents[0].all_models) {
    if (m.data !== undefined && m.selected !== undefined) got.set(m, {data: m.data});
    else if (m.start !== undefined && m.end !== undefined && m.bounds !== undefined)
      got.set(m, {start: m.start, end: m.end});
  }
  return got;
}"""
#: The redraw floor: the two last contacts' data and ranges set again in turn, with no key,
#: no worker and no text: ms from the change to the first animation frame after it (as
#: ``explorer.keyToSupportMs`` ends), ``n`` times, 150 ms apart.
FLOOR = """async ([before, n]) => {
  const after = (%s)(), changed = [...after.keys()].filter((m) =>
    before.get(m) && (m.data !== undefined ? before.get(m).data !== after.get(m).data
                          : before.get(m).start !== after.get(m).start ||
                            before.get(m).end !== after.get(m).end));
  const times = [];
  for (let i = 0; i < n; i++) {
    const use = i %% 2 ? after : before, t0 = performance.now();
    for (const m of changed) m.setv(use.get(m));
    await new Promise((done) => requestAnimationFrame(() => {
      times.push(performance.now() - t0); done();
    }));
    await new Promise((done) => setTimeout(done, 150));
  }
  return {times, changed: changed.length};
}""" % SNAPSHOT


def key_presses(browser, path: Path, presses: int) -> dict:
    """Key press -> redrawn: in the page (``explorer.keyToSupportMs``, absent in older
    packs), Playwright's round trips, and the redraw floor (``FLOOR``: the same data and
    ranges set again without a key press or a computation)."""
    context = _context(browser)
    page = context.new_page()
    page.goto(path.as_uri())
    page.wait_for_function("explorer.drawn >= 1 && explorer.polarDrawn >= 1 && "
                           "explorer.uniformDrawn >= 1", timeout=120_000)
    handle = page.locator(".noUi-handle").nth(3)
    handle.focus()
    page.wait_for_timeout(300)
    before = page.evaluate_handle(SNAPSHOT)
    trips = []
    for i in range(presses):
        drawn = page.evaluate("explorer.drawn")
        t = time.perf_counter()
        handle.press("ArrowLeft" if i % 2 else "ArrowRight")
        page.wait_for_function(f"explorer.drawn > {drawn}", polling="raf")
        trips.append(1000 * (time.perf_counter() - t))
    page.wait_for_timeout(100)
    in_page = page.evaluate(f"explorer.keyToSupportMs ? explorer.keyToSupportMs.slice(-{presses}) : null")
    page.wait_for_timeout(1000)  # the arrays of the last state drawn
    floor = page.evaluate(FLOOR, [before, presses])
    context.close()
    return dict(trips=trips, in_page=in_page, floor=floor["times"], changed=floor["changed"])


def browser_figures(paths: list[Path], repeats: int, presses: int, array_repeats: int,
                    opens: int) -> dict:
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", headless=True,
                                    args=["--no-sandbox", "--disable-gpu"])
        floor = paths[0].parent / "floor.html"
        floor_page(floor)
        first = {path: [] for path in [*paths, floor]}
        for _ in range(opens):  # alternating: the files see the same load
            for path in paths:
                first[path].append(open_times(browser, path, DRAWN))
            first[floor].append(open_times(browser, floor, f"{FCP}.then(() => true)"))
        redraw = {path: [] for path in paths}
        for _ in range(2):  # alternating, in two halves
            for path in paths:
                got = key_presses(browser, path, (presses + 1) // 2)
                redraw[path].append(got)
        pages = {}
        for path in paths:
            page = _context(browser).new_page()
            page.goto(path.as_uri())
            page.wait_for_function("explorer.polarDrawn >= 1 && explorer.uniformDrawn >= 1",
                                   timeout=120_000)
            pages[path] = page
        times = pages[paths[-1]].evaluate(f"{TIMING}(MicropillarKernel, {json.dumps(CASE)}, "
                                          f"{BATCH}, {WARMUP}, {repeats})")
        arrays = {path: {} for path in paths}
        for _ in range(array_repeats):  # alternating, one run of each regime at a time
            for path in paths:
                got = pages[path].evaluate(f"{ARRAYS}(MicropillarArrays, JSON.parse(document."
                                           f"getElementById('mp-config').textContent), 1)")
                for name, t in got.items():
                    mine = arrays[path].setdefault(name, {"self": [], "one": [], "uniform": []})
                    for key in ("self", "one", "uniform"):
                        mine[key] += t[key]
                    mine["contacts"], mine["sweep_contacts"] = t["contacts"], t["sweep_contacts"]
        browser.close()
    return dict(first=first, floor=floor, times=times, redraw=redraw, arrays=arrays)


def p95(values) -> float:
    v = sorted(values)
    return v[min(len(v) - 1, math.ceil(0.95 * len(v)) - 1)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=30)
    parser.add_argument("--presses", type=int, default=40)
    parser.add_argument("--array-repeats", type=int, default=5,
                        help="runs of each regime's polar sweep and uniform array (0: none)")
    parser.add_argument("--opens", type=int, default=3, help="page loads per file")
    parser.add_argument("--file", type=Path, action="append", default=[],
                        help="a packed explorer to measure instead of packing one (repeat to "
                             "compare: measured alternately)")
    args = parser.parse_args()
    if shutil.which("node") is None:
        raise SystemExit("node is not installed")
    from app.offline.pack import write

    print(f"load average: {Path('/proc/loadavg').read_text().split()[:3]}")
    with tempfile.TemporaryDirectory() as folder:
        paths = [Path(folder) / f"{i}-{f.name}" for i, f in enumerate(args.file)]
        for f, path in zip(args.file, paths):
            shutil.copyfile(f, path)
        if not paths:
            paths = [Path(folder) / "explorer.html"]
            write(paths[0])
        for path in paths:
            size = path.stat().st_size
            print(f"file {path.name}: {size / 1e6:.2f} MB ({size:,} bytes)")
        print(f"exit-state error of the benchmark case: {exit_error():.1e}")
        print(f"one trajectory, Node {subprocess.run(['node', '--version'], text=True, capture_output=True).stdout.strip()}: "
              f"{spread(node_times(args.repeats))}")
        figures = browser_figures(paths, args.repeats, args.presses, args.array_repeats,
                                  args.opens)
        print(f"one trajectory, Chromium (page's main thread, {paths[-1].name}): "
              f"{spread(figures['times'])}")
        for path, seconds in figures["first"].items():
            what = ("the floor (BokehJS inlined, one empty figure) -> first contentful paint"
                    if path == figures["floor"] else f"{path.name}: open from file:// -> first plot")
            print(f"{what}: {spread(seconds, unit='s', digits=2)}")
        for path, runs in figures["redraw"].items():
            trips = [t for run in runs for t in run["trips"]]
            if runs[0]["in_page"] is not None:
                in_page = [t for run in runs for t in run["in_page"]]
                print(f"{path.name}: slider key press -> support redrawn, in the page: "
                      f"{spread(in_page, digits=1)}, p95 {p95(in_page):.1f} ms")
            print(f"{path.name}: slider key press -> everything redrawn, Playwright's round "
                  f"trips: {spread(trips, digits=1)}, p95 {p95(trips):.1f} ms")
            floor = [t for run in runs for t in run["floor"]]
            print(f"{path.name}: the redraw floor (the {runs[0]['changed']} sources and ranges a "
                  f"press changed, set again with no key, computation or text): "
                  f"{spread(floor, digits=1)}, p95 {p95(floor):.1f} ms")
    for path, regimes in figures["arrays"].items():
        for name, t in regimes.items():
            print(f"{path.name}: {name}, F_N = 1, Chromium: polar sweep (72 orientations), "
                  f"self-consistent beta ({t['sweep_contacts']} contacts) "
                  f"{spread(t['self'], digits=0)}; at beta = 1 {spread(t['one'], digits=0)}; "
                  f"uniform array with self-consistent beta, tol 1e-3 ({t['contacts']} "
                  f"contacts) {spread(t['uniform'], digits=0)}")
    print(f"load average: {Path('/proc/loadavg').read_text().split()[:3]}")
    print("Figures measured while other jobs share the machine are not trustworthy: "
          "re-measure on a quiet one.")


if __name__ == "__main__":
    main()
