"""The players of the served dashboard in headless Chromium: frames shown per second.

    python benchmarks/bench_served_player.py [--tab array] [--size 1280x720] [--query ""]
        [--repeats 3] [--seconds 5]

``panel serve app`` is started (as in the browser tests), the page opened on ``--tab``
(``array``: the Array tab's player; ``support``: the One-support player with its live
energy bars) and its player started; the page counts the frames the player hands to the
figures (changes of its ``PlayerFrame``) over ``--seconds`` and how far the frame index
moved (the player skips frames to keep the motion in real time when it cannot draw them
all). The standalone pages' ceilings are in ``bench_animation.py``. Run it also under
``benchmarks/busy_core.py --`` for a machine with one core taken. Prints median [min-max]
over ``--repeats`` windows. To compare two checkouts in the same conditions, run this
script alternately with ``PYTHONPATH`` set to each (the server imports ``app`` from there).
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
from pathlib import Path

_HAS_MODEL_JS = """(name) => Bokeh.documents.some((d) => [...d.all_models]
  .some((m) => m.name === name))"""
_COUNT_JS = """async ([prefix, ms]) => {
  let play = null;
  for (const d of Bokeh.documents) for (const m of d.all_models)
    if (m.name === prefix + "_play") play = m;
  // Every player's frame changes; the first to change is the one this button plays.
  const frames = [];
  for (const d of Bokeh.documents) for (const m of d.all_models)
    if (m.type && m.type.endsWith("PlayerFrame")) m.connect(m.properties.value.change,
      () => frames.push([m.id, performance.now(), m.value]));
  play.active = true;
  await new Promise((r) => setTimeout(r, ms));
  play.active = false;
  const mine = frames.filter((f) => f[0] === (frames[0] || [null])[0]);
  if (mine.length < 2) return {shown_per_s: 0, index_per_s: 0};
  const s = (mine[mine.length - 1][1] - mine[0][1]) / 1000;
  return {shown_per_s: (mine.length - 1) / s,
          index_per_s: Math.abs(mine[mine.length - 1][2] - mine[0][2]) / s};
}"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tab", default="array", choices=["array", "support"])
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--query", default="", help="more of the page address, e.g. '&projector=1'")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--seconds", type=float, default=5.0)
    args = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright

    from checkout import helper
    tools, serving = helper("browser/page_tools"), helper("browser/serving")

    width, height = (int(v) for v in args.size.split("x"))
    load0 = os.getloadavg()
    runs = []
    out = Path("bench-out")
    out.mkdir(exist_ok=True)
    with serving.serve_app(out / "served-player.log") as base, sync_playwright() as pw:
        browser = serving.launch_chromium(pw)
        page = browser.new_page(viewport={"width": width, "height": height})
        tools.wait_for_app(page, f"{base}/app?tab={args.tab}{args.query}")
        # The Array tab's player comes with its computed motion, after the page.
        page.wait_for_function(_HAS_MODEL_JS, arg=f"{args.tab}_player_play", timeout=180_000)
        tools.settle(page)
        page.wait_for_timeout(2000)
        for _ in range(args.repeats):
            runs.append(page.evaluate(_COUNT_JS, [f"{args.tab}_player", args.seconds * 1e3]))
            page.wait_for_timeout(500)
        browser.close()

    def spread(key):
        v = [r[key] for r in runs]
        return f"{statistics.median(v):.1f} [{min(v):.1f}-{max(v):.1f}]"
    print(f"{args.tab} player, {args.size}{' ' + args.query if args.query else ''}; load average "
          f"{load0[0]:.1f} at the start, {os.getloadavg()[0]:.1f} at the end; median [min-max] "
          f"of {args.repeats} windows of {args.seconds:g} s:")
    print(f"  frames shown per second        {spread('shown_per_s')}")
    print(f"  frame index advanced per second {spread('index_per_s')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
