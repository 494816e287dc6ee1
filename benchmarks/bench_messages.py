"""What encoding one slider move's message costs the server, and how much of it is Bokeh's
table of references to every model of the page (``docs/upstream/patch_doc_reference_table.py``).

    python benchmarks/bench_messages.py [--moves 40] [--repeats 5] [--quick] [--out DIR]

The dashboard is built in a Bokeh document as the server builds it (``Dashboard`` on the
One support tab), the page's models marked as sent (``flush_synced``), and random moves of
the four sliders (seeded) are made; each move's changes (its result applied, computed
without a server) are encoded into a ``PATCH-DOC`` as the server does, ``--repeats`` times
(their median kept), with Bokeh's serializer and, alternated in the same run, with the
reproducer's, which makes a model's reference when the encoder meets it. The two messages
are checked equal, and first both serializers on the cases the table is for (a model the
page has: sent as its reference; a new one: sent whole). The CPU time of this thread per
message, median [min-max] over the moves. Everything else a move costs the server (the
incoming message, Panel and param, the views, the websocket) is ``served_moves.py``'s.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import random
import statistics
import sys
import time
from pathlib import Path

from spread import spread

#: The sliders moved, each over its range (log10 for the stiffnesses and the load).
SLIDERS = {"theta0": lambda r: r.uniform(0.0, 359.0),
           "k_r": lambda r: 10 ** r.uniform(-2.0, 0.47),
           "k_theta": lambda r: 10 ** r.uniform(-2.0, 0.47),
           "F_N": lambda r: 10 ** r.uniform(-1.0, 1.0)}


#: The upstream reproducer, whose serializer (references made as met) is measured here.
REPRODUCER = Path(__file__).resolve().parents[1] / "docs" / "upstream" / \
    "patch_doc_reference_table.py"


def _as_met_serializer():
    """The reproducer's ``AsMet``: Bokeh's encoder, each synced model's reference made when
    it is met (run from this checkout's file, its ``__main__`` part not)."""
    import runpy

    return runpy.run_path(str(REPRODUCER))["AsMet"]


class _Recorder:
    def __init__(self):
        self.events = []

    def _document_patched(self, event) -> None:
        self.events.append(event)


def _content(message):
    """A message's JSON and arrays, its arrays' ids (new at each encoding) numbered."""
    content = message.content_json
    for i, buffer in enumerate(message.buffers):
        content = content.replace(str(buffer.id), f"buffer-{i}")
    return content, [bytes(buffer.data) for buffer in message.buffers]


def _encode(events, serializer, module, repeats: int):
    from bokeh.protocol import Protocol

    own = module.Serializer
    module.Serializer = serializer
    try:
        times = []
        for _ in range(repeats):
            start = time.thread_time()
            message = Protocol().create("PATCH-DOC", events)
            times.append(time.thread_time() - start)
    finally:
        module.Serializer = own
    return statistics.median(times) * 1e3, message


def check_as_met(serializer, module) -> None:
    """Both serializers encode what the table is for alike: a property set to a model the
    page has (sent as its reference) and to a new one (sent whole). (A move's own events
    name their models by reference directly: they never consult the table.)"""
    from bokeh.document import Document
    from bokeh.models import ColumnDataSource, Title
    from bokeh.plotting import figure

    for name, chosen in (("Bokeh's", module.Serializer), ("as met", serializer)):
        doc, fig = Document(), figure()
        line = fig.line([0, 1], [0, 1])
        other = ColumnDataSource({"x": [0, 1], "y": [1, 0]})
        fig.line(source=other)
        doc.add_root(fig)
        doc.models.flush_synced()  # as sent
        events = []
        doc.on_change(lambda event, events=events: events.append(event))
        line.data_source = other        # a model the page has
        fig.title = Title(text="new")   # a new model
        sent = json.loads(_encode(events, chosen, module, 1)[1].content_json)["events"]
        if sent[0]["new"] != {"id": other.id} or sent[1]["new"].get("type") != "object":
            raise AssertionError(f"{name} serializer: a known model must go as its reference "
                                 f"and a new one whole, not {sent}")


def dashboard_page():
    """The dashboard built in a Bokeh document as the server builds it, on the One support
    tab, its models marked as sent to the browser: (document, ``Dashboard``)."""
    import panel as pn
    from bokeh.document import Document

    from app.state import ExplorerState
    from app.views import Dashboard

    doc = Document()
    page = Dashboard(ExplorerState())
    doc.add_root(pn.panel(page).get_root(doc))
    doc.models.flush_synced()  # the page as sent to the browser
    return doc, page


def run(moves: int = 40, repeats: int = 5, seed: int = 3) -> dict:
    from bokeh.protocol.messages import patch_doc  # noqa: F401 (loads the module)

    from app.jobs import work_pool

    module = sys.modules["bokeh.protocol.messages.patch_doc"]
    bokeh_own, as_met = module.Serializer, _as_met_serializer()
    check_as_met(as_met, module)
    doc, page = dashboard_page()
    recorder = _Recorder()
    doc.callbacks.on_change_dispatch_to(recorder)
    rng = random.Random(seed)
    rows = []
    try:
        for i in range(moves):
            name = rng.choice(sorted(SLIDERS))
            recorder.events.clear()
            page.state.param.update(**{name: SLIDERS[name](rng)})
            events = list(recorder.events)
            if not events:
                continue
            first, second = (bokeh_own, as_met) if i % 2 == 0 else (as_met, bokeh_own)
            found = {}
            for serializer in (first, second):
                found[serializer] = _encode(events, serializer, module, repeats)
            (own_ms, own_msg), (met_ms, met_msg) = found[bokeh_own], found[as_met]
            if _content(own_msg) != _content(met_msg):
                raise AssertionError(f"move {i} ({name}): the two messages differ")
            rows.append({"slider": name, "events": len(events),
                         "buffers": len(own_msg.buffers), "json_bytes": len(own_msg.content_json),
                         "bokeh_ms": own_ms, "as_met_ms": met_ms})
    finally:
        work_pool().shutdown()
    if not rows:
        raise RuntimeError(f"none of the {moves} moves changed the page: nothing to encode")

    def of(key):
        return spread(r[key] for r in rows)
    return {"models": len(doc.models), "messages": len(rows), "repeats": repeats,
            "bokeh_ms": of("bokeh_ms"), "as_met_ms": of("as_met_ms"),
            "table_ms": spread(r["bokeh_ms"] - r["as_met_ms"] for r in rows),
            "events": of("events"), "buffers": of("buffers"),
            "json_bytes": of("json_bytes"), "rows": rows,
            "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores",
            "load_average": os.getloadavg()[0], "date": time.strftime("%Y-%m-%d %H:%M")}


def text(found: dict) -> str:
    def f(s, unit="ms", digits=2):
        return f"{s['median']:.{digits}f} [{s['min']:.{digits}f}-{s['max']:.{digits}f}] {unit}"
    return "\n".join([
        f"One slider move's PATCH-DOC, {found['messages']} moves, the page {found['models']} "
        f"models ({found['date']}, {found['machine']}, load {found['load_average']:.1f}); "
        f"CPU per message, the median of {found['repeats']}, median [min-max] over the moves:",
        f"  Bokeh's serializer:           {f(found['bokeh_ms'])}",
        f"  references made as met:       {f(found['as_met_ms'])}",
        f"  Bokeh's table of references:  {f(found['table_ms'])}",
        f"  per message: {f(found['events'], 'events', 0)}, {f(found['buffers'], 'arrays', 0)}, "
        f"JSON {f(found['json_bytes'], 'bytes', 0)}"])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=40, help="slider moves (40)")
    ap.add_argument("--repeats", type=int, default=5,
                    help="encodings of each message per serializer, their median kept (5)")
    ap.add_argument("--quick", action="store_true", help="6 moves, 2 encodings each (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args(argv)
    if args.quick:
        args.moves, args.repeats = 6, 2
    if args.moves < 1 or args.repeats < 1:
        ap.error(f"--moves {args.moves} and --repeats {args.repeats} must be at least 1")
    found = run(args.moves, args.repeats)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench_messages.json").write_text(json.dumps(found, indent=1))
    print(text(found))
    return 0


if __name__ == "__main__":
    sys.exit(main())
