"""What Bokeh's "expensive error diagnostics" cost the dashboard's server: a page build and
a slider move, with the setting on (Bokeh's default) and off (the served dashboard's,
``app.app_hooks.quiet_diagnostics``).

    python benchmarks/bench_diagnostics.py [--rounds 3] [--moves 30] [--quick] [--out DIR]

The dashboard is built in a Bokeh document as the server builds it (``Dashboard`` on the One
support tab, the page's models marked as sent; ``bench_messages.dashboard_page``) and random
moves of the four sliders (``bench_messages.SLIDERS``, seeded, the same in every round) are
made, their results applied (computed by the work
pool, without a server). A first round with the diagnostics on computes every result, so
the measured rounds read them all from the cache. Then each round builds and moves once
with the setting on and once off, in alternating order. Measured: this process's CPU time
for the build and for each move (the pool's workers not counted), and how many attributes
the page's models were asked for and lacked (``HasProps._raise_attribute_error_with_matches``,
where the diagnostics' ``difflib`` suggestions are made; ``docs/upstream/
esm_update_attribute_miss.py``). Median [min-max]: over the rounds for the build, over all
moves for a move. The incoming message, the message sent and the websocket are not in it
(``served_moves.py`` measures the served move whole).
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import random
import sys
import time
from pathlib import Path

from bench_messages import SLIDERS, dashboard_page
from spread import spread


def _moves(n: int, seed: int) -> list[tuple[str, float]]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        name = rng.choice(sorted(SLIDERS))
        out.append((name, SLIDERS[name](rng)))
    return out


class _Misses:
    """Counts the attribute reads a Bokeh model answered with ``AttributeError``."""

    def __init__(self):
        from bokeh.core.has_props import HasProps

        self.count, self._cls = 0, HasProps
        self._own = HasProps._raise_attribute_error_with_matches

    def __enter__(self):
        own = self._own

        def counted(model, name, properties):
            self.count += 1
            return own(model, name, properties)
        self._cls._raise_attribute_error_with_matches = counted
        return self

    def __exit__(self, *exc):
        self._cls._raise_attribute_error_with_matches = self._own


def _session(moves: list) -> dict:
    """One page built and moved: CPU seconds of the build, ms per move, misses per move."""
    start = time.process_time()
    _doc, page = dashboard_page()
    build_s = time.process_time() - start
    times = []
    with _Misses() as misses:
        for name, value in moves:
            start = time.process_time()
            page.state.param.update(**{name: value})
            times.append((time.process_time() - start) * 1e3)
    return {"build_s": build_s, "move_ms": times, "misses_per_move": misses.count / len(moves)}


def run(rounds: int = 3, moves: int = 30, seed: int = 5) -> dict:
    from bokeh.settings import settings

    from app.jobs import work_pool

    sequence = _moves(moves, seed)
    found = {"on": [], "off": []}
    try:
        settings.perform_error_diagnostics.set_value(True)
        _session(sequence)  # every result computed once: the measured rounds read the cache
        for i in range(rounds):
            for setting in (("on", "off") if i % 2 == 0 else ("off", "on")):
                settings.perform_error_diagnostics.set_value(setting == "on")
                found[setting].append(_session(sequence))
    finally:
        settings.perform_error_diagnostics.unset_value()
        work_pool().shutdown()

    def summary(runs):
        return {"build_s": spread(r["build_s"] for r in runs),
                "move_ms": spread(t for r in runs for t in r["move_ms"]),
                "misses_per_move": spread(r["misses_per_move"] for r in runs)}
    return {"rounds": rounds, "moves": moves, "on": summary(found["on"]),
            "off": summary(found["off"]),
            "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores",
            "load_average": os.getloadavg()[0], "date": time.strftime("%Y-%m-%d %H:%M")}


def spread_text(s: dict, unit: str, digits: int = 2) -> str:
    """``median [min-max] unit`` of a ``spread``."""
    return f"{s['median']:.{digits}f} [{s['min']:.{digits}f}-{s['max']:.{digits}f}] {unit}"


def text(found: dict) -> str:
    f = spread_text
    lines = [f"Bokeh's error diagnostics on and off, {found['rounds']} rounds of a page build "
             f"and {found['moves']} slider moves each ({found['date']}, {found['machine']}, "
             f"load {found['load_average']:.1f}); this process's CPU, median [min-max]:"]
    for setting in ("on", "off"):
        s = found[setting]
        lines.append(f"  diagnostics {setting:3s}: build {f(s['build_s'], 's')}, "
                     f"move {f(s['move_ms'], 'ms')}, "
                     f"{f(s['misses_per_move'], 'attribute misses per move', 1)}")
    return "\n".join(lines)


#: The sizes of ``--quick`` (for CI): one round of a few moves.
QUICK = {"rounds": 1, "moves": 4}


def rounds_and_moves(description: str, argv, run, text, json_name: str, each: str) -> int:
    """The command line of a benchmark of page builds and moves in rounds (this one's and
    ``bench_steady_design.py``'s): ``run(rounds=, moves=)``'s findings written to
    ``--out``/``json_name`` and printed by ``text``; ``each`` names what a round does once."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--rounds", type=int, default=3, help=f"rounds, {each} once (3)")
    ap.add_argument("--moves", type=int, default=30, help="slider moves per page (30)")
    ap.add_argument("--quick", action="store_true",
                    help=f"{QUICK['rounds']} round of {QUICK['moves']} moves (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    sizes = dict(QUICK) if args.quick else {"rounds": args.rounds, "moves": args.moves}
    for name, value in sizes.items():
        if value < 1:
            ap.error(f"--{name} {value}: give at least 1")
    found = run(**sizes)
    path = Path(args.out) / json_name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(found, indent=1))
    print(text(found))
    return 0


def main(argv=None) -> int:
    return rounds_and_moves(__doc__.splitlines()[0], argv, run, text,
                            "bench_diagnostics.json", "each setting")


if __name__ == "__main__":
    sys.exit(main())
