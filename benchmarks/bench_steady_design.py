"""What Panel's design parameters, worked out at every property update, cost the dashboard's
server: a page build and a slider move with Panel's ``Native`` design (its default) and
with ``app.steady_design.SteadyNative`` (the served dashboard's, which works them out once
per component type and page; ``docs/upstream/design_params_per_update.py``).

    python benchmarks/bench_steady_design.py [--rounds 3] [--moves 30] [--quick] [--out DIR]

As ``bench_diagnostics.py``: the dashboard built in a Bokeh document as the server builds
it (``bench_messages.dashboard_page``), random moves of the four sliders (seeded, the same
in every round), their results applied (the first round computes them all, the measured
rounds read the cache); each round builds and moves once with each design, in alternating
order. Measured: this process's CPU time for the build and for each move (the pool's
workers not counted), and the calls of ``Design.params`` that worked the parameters out
(``Design._get_modifiers``) per move. Median [min-max]: over the rounds for the build, over
all moves for a move. Bokeh's error diagnostics are off, as in the served dashboard.
"""
from __future__ import annotations

import os
import platform
import sys
import time

from bench_diagnostics import _moves, _session, rounds_and_moves, spread_text
from bench_messages import dashboard_page
from spread import spread

#: The two designs compared: Panel's default (``pn.config.design`` unset) and the app's.
DESIGNS = ("native", "steady")


class WorkedOut:
    """Counts the design parameters worked out (``Design._get_modifiers``); also the
    tests' count (``tests/test_steady_design.py``)."""

    def __init__(self):
        from panel.theme.base import Design

        self.count, self._cls = 0, Design
        self._own = Design.__dict__["_get_modifiers"]

    def __enter__(self):
        own = self._own.__func__

        def counted(cls, *args, **kwargs):
            self.count += 1
            return own(cls, *args, **kwargs)
        self._cls._get_modifiers = classmethod(counted)
        return self

    def __exit__(self, *exc):
        self._cls._get_modifiers = self._own


def _use(design: str) -> None:
    import panel as pn

    from app.steady_design import SteadyNative

    pn.config.design = SteadyNative if design == "steady" else None


def run(rounds: int = 3, moves: int = 30, seed: int = 5) -> dict:
    import panel as pn
    from bokeh.settings import settings

    from app.jobs import work_pool

    sequence = _moves(moves, seed)
    found = {d: [] for d in DESIGNS}
    per_move = {}
    try:
        settings.perform_error_diagnostics.set_value(False)
        _use("native")
        _session(sequence)  # every result computed once: the measured rounds read the cache
        for design in DESIGNS:  # the design parameters worked out by the moves alone
            _use(design)
            _doc, page = dashboard_page()
            with WorkedOut() as worked:
                for name, value in sequence:
                    page.state.param.update(**{name: value})
            per_move[design] = worked.count / len(sequence)
        for i in range(rounds):
            for design in (DESIGNS if i % 2 == 0 else DESIGNS[::-1]):
                _use(design)
                found[design].append(_session(sequence))
    finally:
        settings.perform_error_diagnostics.unset_value()
        pn.config.design = None
        work_pool().shutdown()

    def summary(runs, design):
        return {"build_s": spread(r["build_s"] for r in runs),
                "move_ms": spread(t for r in runs for t in r["move_ms"]),
                "worked_out_per_move": per_move[design]}
    return {"rounds": rounds, "moves": moves,
            **{d: summary(found[d], d) for d in DESIGNS},
            "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores",
            "load_average": os.getloadavg()[0], "date": time.strftime("%Y-%m-%d %H:%M")}


def text(found: dict) -> str:
    f = spread_text
    lines = [f"Panel's Native design and SteadyNative, {found['rounds']} rounds of a page build "
             f"and {found['moves']} slider moves each ({found['date']}, {found['machine']}, "
             f"load {found['load_average']:.1f}); this process's CPU, median [min-max]:"]
    for design in DESIGNS:
        s = found[design]
        lines.append(f"  {design:6s}: build {f(s['build_s'], 's')}, move {f(s['move_ms'], 'ms')}, "
                     f"design parameters worked out {s['worked_out_per_move']:.1f} per move")
    return "\n".join(lines)


def main(argv=None) -> int:
    return rounds_and_moves(__doc__.splitlines()[0], argv, run, text,
                            "bench_steady_design.json", "each design")


if __name__ == "__main__":
    sys.exit(main())
