"""A class of protocol-level sessions (``load_client.Session``) against one server: opened
a few at a time, driven in one profile for a while, then closed (benchmarks/load_test.py)."""
from __future__ import annotations

import asyncio
import time

from load_client import OPEN_TIMEOUT_S, Session

#: Pages loading at the same time (people arrive over some seconds, not all at one instant).
OPENING_AT_ONCE = 2


class LoopLag:
    """How late this process's event loop wakes a task that asked to sleep ``PERIOD_S``:
    when the loop is saturated (every client's work runs on it), the server's answers are
    read late, and a latency measured here is this process's, not the server's."""

    PERIOD_S = 0.01

    def __init__(self):
        self.lags: list[float] = []
        self._task: asyncio.Task | None = None

    async def _run(self):
        loop = asyncio.get_running_loop()
        while True:
            asked = loop.time() + self.PERIOD_S
            await asyncio.sleep(self.PERIOD_S)
            self.lags.append(max(0.0, loop.time() - asked))

    def start(self) -> None:
        self._task = asyncio.create_task(self._run())

    def stop(self) -> list[float]:
        if self._task is not None:
            self._task.cancel()
        return self.lags


async def open_sessions(base: str, app: str, n: int, seed: int,
                        replica: str = "full") -> list[Session]:
    sessions = [Session(i, base, app, seed=seed, replica=replica) for i in range(n)]
    opening = asyncio.Semaphore(OPENING_AT_ONCE)

    async def one(s: Session):
        async with opening:
            try:
                await asyncio.wait_for(s.open(), timeout=OPEN_TIMEOUT_S)
            except Exception as exc:  # noqa: BLE001
                s.errors.append(f"open failed: {type(exc).__name__}: {exc}")
    await asyncio.gather(*(one(s) for s in sessions))
    return sessions


async def drive(base: str, app: str, n: int, duration: float, seed: int,
                on_open=None, before_close=None,
                profile: str = "drag", replica: str = "full",
                lag: LoopLag | None = None) -> tuple[list[Session], float]:
    """Open ``n`` sessions, move their sliders for ``duration`` s in ``profile`` (a key of
    ``PROFILES``), close them (``on_open()`` is called once all are open,
    ``before_close()`` just before closing); ``lag`` records the client loop's lag while
    the sliders move."""
    sessions = await open_sessions(base, app, n, seed, replica)
    if on_open is not None:
        on_open()
    started = time.perf_counter()
    live = [s for s in sessions if not s.errors]
    if lag is not None:
        lag.start()
    await asyncio.gather(*(s.run(started + duration, profile) for s in live))
    elapsed = time.perf_counter() - started
    if lag is not None:
        lag.stop()
    if before_close is not None:
        before_close()
    await asyncio.gather(*(s.close() for s in sessions))
    return sessions, elapsed
