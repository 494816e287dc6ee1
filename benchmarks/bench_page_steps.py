"""How long each step of a page's build holds the server's event loop, first page and next.

    python benchmarks/bench_page_steps.py [--servers 3] [--pages 5] [--out DIR]

Starts ``panel serve app`` ``--servers`` times (``MICROPILLAR_TRACE`` set: the server
writes a timestamp at each step of a page's build, ``app.opening``) and opens ``--pages``
pages one after another on each, as a browser stand-in (``load_client.Session``: the page,
its websocket, the document, ``document_ready``), until each page's first plot. Per page:
its Python objects (``page build starts`` -> ``page objects built``) and its models and
their messages (``page models start`` -> ``page sent``; with a page sent in two parts,
each part). A step is one callback: a request that comes meanwhile (a liveness probe,
another visitor's move) waits for it. Also the server's start, from launching it to its
liveness endpoint answering (its workers warmed and the dashboard rehearsed).

Prints median [min-max] of each step for the servers' first page and for the pages after
it; writes DIR/page_steps.json. Quiet machine only: note the load average printed.
"""
from __future__ import annotations

import argparse
import asyncio
import json
import time
from pathlib import Path

from checkout import helper
from load_client import Session
from machine import loadavg
from spread import cell, spread

#: (name, first stage, last stage) of each step; a step whose stages are missing from a
#: page's trace (a build in one part) is left out for that page.
STEPS = (("objects", "page build starts", "page objects built"),
         ("models, part 1", "page models start", "page first part sent"),
         ("models, part 2", "page rest starts", "page sent"),
         ("models, whole", "page models start", "page sent"))


def page_steps(trace: list[dict]) -> list[dict]:
    """The steps' seconds of each page in a server's trace, in the order built."""
    pages, current = [], None
    for row in trace:
        stage = row["stage"]
        if stage == "page build starts":
            current = {}
            pages.append(current)
        if current is not None and stage.startswith("page"):
            current[stage] = row["t"]
    out = []
    for marks in pages:
        got = {name: marks[b] - marks[a] for name, a, b in STEPS if a in marks and b in marks}
        if "models, part 1" in got:
            got.pop("models, whole")
        out.append(got)
    return out


async def _open_pages(base: str, pages: int) -> None:
    for i in range(pages):
        session = Session(i, base, replica="watched", query=f"?F_N={1 + 0.01 * i:.2f}")
        await session.open()
        await session.first_plot()
        await session.close()
        await asyncio.sleep(1.5)  # the page's results drained


def run(servers: int, pages: int, out: Path) -> dict:
    serve_app = helper("browser/serving").serve_app
    out.mkdir(parents=True, exist_ok=True)
    load0 = loadavg()
    starts, firsts, nexts = [], [], []
    for k in range(servers):
        trace = out / f"trace-{k}.jsonl"
        trace.unlink(missing_ok=True)
        t0 = time.perf_counter()
        with serve_app(out / f"server-{k}.log", env={"MICROPILLAR_TRACE": str(trace)}) as base:
            starts.append(time.perf_counter() - t0)
            asyncio.run(_open_pages(base, pages))
        steps = page_steps([json.loads(line) for line in trace.read_text().splitlines()])
        firsts += steps[:1]
        nexts += steps[1:]

    def summary(rows):
        return {name: spread(r[name] for r in rows if name in r)
                for name, *_ in STEPS if any(name in r for r in rows)}
    report = {"servers": servers, "pages": pages,
              "load_average": {"start": load0, "end": loadavg()},
              "server_start_s": spread(starts), "first_page": summary(firsts),
              "next_pages": summary(nexts)}
    (out / "page_steps.json").write_text(json.dumps(report, indent=1))
    return report


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--servers", type=int, default=3)
    ap.add_argument("--pages", type=int, default=5)
    ap.add_argument("--out", type=Path, default=Path("bench-out"))
    args = ap.parse_args()
    report = run(args.servers, args.pages, args.out)
    la = report["load_average"]
    print(f"load average {la['start'][0]:.2f} at the start, {la['end'][0]:.2f} at the end")
    print(f"server start to liveness answered: {_cell(report['server_start_s'], 1, 's')}")
    for which in ("first_page", "next_pages"):
        for name, value in report[which].items():
            print(f"{which.replace('_', ' ')}: {name}: {_cell(value, 1e3, 'ms')}")


def _cell(value: dict, scale: float, unit: str) -> str:
    return cell(value["median"] * scale, value["min"] * scale, value["max"] * scale,
                fmt=lambda v: f"{v:.3g}") + f" {unit} (n={value['n']})"


if __name__ == "__main__":
    main()
