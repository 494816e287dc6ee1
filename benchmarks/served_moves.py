"""The served server's own CPU per slider move (``bench_dashboard.py --served K``).

``panel serve app`` is started (``tests/browser/serving.serve_app``) and K protocol-level
sessions (``load_client.Session``: the page's document, pulled and patched as BokehJS
does) are opened on the One-support tab. In each block every session moves a random
slider and waits for its new plot data, then rests ``REST_S`` (the uniform array's and the
address's debounced updates leave meanwhile), ``moves`` times; the server process's CPU
time (user + system, its workers not counted) over the block is divided by the moves. So
everything the server does for a browser's move is counted -- the incoming message, Panel
and param, the results applied, every message pushed -- and the model's work is not (its
results come from the shared cache after the first blocks, and run in the workers).
Reported per block (median [min-max]), with the messages and binary arrays pushed per move.
"""
from __future__ import annotations

import asyncio
import os
import time
from pathlib import Path

from checkout import helper
from load_client import Session
from load_probe import server_pid

#: Seconds a session rests after each move's data arrived.
REST_S = 0.6


class CountingSession(Session):
    """A session that counts the binary arrays of the messages the server pushes."""

    buffers = 0

    async def _read(self):
        message = await super()._read()
        if message is not None and message.msgtype == "PATCH-DOC":
            self.buffers += len(message.buffers)
        return message


def _cpu_s(pid: int) -> float:
    import psutil
    t = psutil.Process(pid).cpu_times()
    return t.user + t.system


async def _drive(base: str, pid: int, sessions: int, moves: int, blocks: int,
                 profile_path: Path | None = None) -> dict:
    opened = [CountingSession(i, base, "app", seed=11) for i in range(sessions)]
    for s in opened:
        await s.open()
        await s.first_plot()
    await asyncio.gather(*(s.move(drags=False) for s in opened))  # warm
    await asyncio.sleep(2 * REST_S)

    async def run(s: Session) -> None:
        for _ in range(moves):
            await s.move(drags=False)
            await asyncio.sleep(REST_S)
    per_move, patches, buffers = [], [], []
    profiler = None
    if profile_path is not None:  # the blocks' moves only, not the opening
        from load_profile import ServerProfiler
        profiler = ServerProfiler(pid, profile_path, subprocesses=False)
    try:
        for _ in range(blocks):
            cpu, n_patches = _cpu_s(pid), sum(s.patches for s in opened)
            n_buffers = sum(s.buffers for s in opened)
            await asyncio.gather(*(run(s) for s in opened))
            n = sessions * moves
            per_move.append((_cpu_s(pid) - cpu) / n * 1e3)
            patches.append((sum(s.patches for s in opened) - n_patches) / n)
            buffers.append((sum(s.buffers for s in opened) - n_buffers) / n)
    finally:  # py-spy stops with the blocks, whatever happened in them
        problem = profiler.stop() if profiler is not None else None
    profiled = None
    if profiler is not None:
        from load_profile import summarise
        profiled = {"error": problem} if problem else summarise(profile_path)
    for s in opened:
        await s.close()
    return {"ms": per_move, "messages per move": patches, "arrays per move": buffers,
            "profile": profiled}


def served_cost(out: Path, sessions: int = 3, moves: int = 10, blocks: int = 5,
                profile: bool = False) -> dict:
    """Server-process CPU ms per move over ``blocks`` blocks of ``sessions`` x ``moves``
    moves; the load average before and after. ``profile``: the server process recorded
    by py-spy during the blocks (``out/served-profile.txt``; ``pip install -e ".[bench]"``),
    summarised by layer and function under ``"profile"`` (``load_profile.summarise``)."""
    serve_app = helper("browser/serving").serve_app
    load = [os.getloadavg()[0]]
    start = time.perf_counter()
    with serve_app(out / "bench-served-moves.log") as base:
        pid = server_pid(int(base.rsplit(":", 1)[1]))
        found = asyncio.run(_drive(base, pid, sessions, moves, blocks,
                                   out / "served-profile.txt" if profile else None))
    load.append(os.getloadavg()[0])
    return {**found, "sessions": sessions, "moves per block": moves,
            "load average": load, "wall_s": time.perf_counter() - start}
