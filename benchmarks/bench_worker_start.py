"""How long a lane's new worker processes take to answer, started as the server starts them
(``app.lanes.worker_context``: forked by a fork server that imported the model once) and
from fresh interpreters (``spawn``, the fallback where there is no fork server).

    python benchmarks/bench_worker_start.py [--rounds 5] [--workers 2] [--quick] [--out DIR]

Each round makes the lane's process pool anew (as after a job stopped past its budget, or
the fresh workers after a class) and waits until every worker has started, run the lane's
start-up (``_init_worker``: the compiled kernel loaded) and answered one call. The first
round with the fork server includes the fork server's own start (its imports), so it is
reported apart. Measured: the wall time to the last answer and the CPU time of the new
processes (the fork server's not counted after its first round), median [min-max]; and the
memory of all this process's children then (the workers, the fork server, the resource
tracker): resident (RSS, shared pages counted in each process) and proportional (PSS,
shared pages split among the processes sharing them: what they cost the machine).
"""
from __future__ import annotations

import argparse
import concurrent.futures as cf
import json
import multiprocessing
import time
from pathlib import Path

import psutil

from app.lanes import _init_worker, worker_context
from app.worker import ping
from spread import cell, spread


def _round(context, workers: int) -> tuple[float, float, float, float]:
    me = psutil.Process()
    before = {p.pid for p in me.children(recursive=True)}
    start = time.perf_counter()
    pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                  initializer=_init_worker, initargs=(0,))
    try:
        for future in [pool.submit(ping) for _ in range(workers)]:
            future.result(timeout=120)
        wall = time.perf_counter() - start
        children = me.children(recursive=True)
        cpu = sum(sum(p.cpu_times()[:2]) for p in children if p.pid not in before)
        memory = [p.memory_full_info() for p in children]
        rss, pss = (sum(getattr(m, k) for m in memory) / 2**20 for k in ("rss", "pss"))
    finally:
        pool.shutdown()
    return wall, cpu, rss, pss


def _columns(runs: list) -> dict:
    return {key: [r[i] for r in runs]
            for i, key in enumerate(("wall_s", "cpu_s", "rss_mb", "pss_mb"))}


def measure(rounds: int = 5, workers: int = 2) -> dict:
    out = {}
    for name, context in (("spawn", multiprocessing.get_context("spawn")),
                          ("server's (fork server)", worker_context())):
        first = _round(context, workers)
        runs = [first] + [_round(context, workers) for _ in range(rounds - 1)]
        if context.get_start_method() == "forkserver":
            out[f"{name}, first round (the fork server starts)"] = _columns([first])
            runs = runs[1:]
        out[name] = _columns(runs)
    return out


def markdown(result: dict, workers: int) -> str:
    lines = [f"# A lane's new workers ({workers}) answering", "",
             "| started by | rounds | wall time to the last answer (s) | their CPU (s) "
             "| children's RSS (MB) | children's PSS (MB) |",
             "|---|---:|---:|---:|---:|---:|"]
    formats = {"wall_s": lambda v: f"{v:.2f}", "cpu_s": lambda v: f"{v:.2f}",
               "rss_mb": lambda v: f"{v:.0f}", "pss_mb": lambda v: f"{v:.0f}"}
    for name, r in result.items():
        cells = []
        for key, fmt in formats.items():
            s = spread(r[key])
            cells.append(cell(s["median"], s["min"], s["max"], fmt))
        lines.append(f"| {name} | {len(r['wall_s'])} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="2 rounds (for the tests)")
    ap.add_argument("--out", default="bench-out")
    args = ap.parse_args()
    if args.quick:
        args.rounds = 2
    result = measure(args.rounds, args.workers)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "worker_start.json").write_text(json.dumps(result, indent=1))
    text = markdown(result, args.workers)
    (out / "worker_start.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
