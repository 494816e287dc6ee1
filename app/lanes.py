"""Lanes of worker processes: what a lane is, its process pool and its queues, one per
client and session, served in turn (used by ``app.jobs.WorkPool``)."""
from __future__ import annotations

import collections
import concurrent.futures as cf
import logging
import multiprocessing
import os
import time
from collections import OrderedDict
from dataclasses import dataclass

log = logging.getLogger("app.jobs")

#: Seconds of one worker a job may take, by default.
DEFAULT_BUDGET_S = 5.0
#: Seconds new worker processes may take to start (fork, imports, the compiled kernel)
#: before their jobs' budgets run anyway; until they answer, no job's clock runs, so a
#: restart after a stopped job does not eat the budgets of the jobs run again.
STARTUP_BUDGET_S = 60.0



@dataclass(frozen=True)
class Lane:
    """A group of worker processes: how many, and how nice (lower CPU priority) they are."""

    name: str
    workers: int
    nice: int
    doc: str


def _workers_for_background() -> int:
    """One background worker per core beyond the one the server and the interactive lane
    share (at least one)."""
    return max(1, (os.cpu_count() or 2) - 1)


LANES = {
    "interactive": Lane("interactive", 1, 0, "the single support (Support tab)"),
    "background": Lane("background", _workers_for_background(), 10,
                       "sweeps, uniform arrays, load curves"),
}
#: The module a lane's worker processes run, imported once per server by the process they
#: are forked from (``worker_context``).
WORKER_MODULE = "app.worker"


def worker_context():
    """How a lane's worker processes start: forked from a process that imported the model
    once (``forkserver``, preloading ``WORKER_MODULE``), so a lane's new workers -- after a
    job ran past its budget, or the fresh ones after a class -- answer in ~0.2 s instead of
    the ~1.1 s (and ~1.1 s of CPU each) a fresh interpreter takes to import numpy, scipy,
    numba and the model (``spawn``, the fallback where there is no forkserver). Never plain
    ``fork``: the server is multi-threaded."""
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload([WORKER_MODULE])
    return context


def _init_worker(nice: int) -> None:
    """Worker start: lower the CPU priority, load the compiled kernel."""
    if nice:
        try:
            os.nice(nice)
        except OSError:  # not permitted: run at normal priority
            pass
    from . import worker
    worker.warm()


@dataclass
class Job:
    key: object
    fn: object
    args: tuple
    kwargs: dict
    future: cf.Future          # handed to the caller
    waiters: list              # futures of identical requests, resolved with this one
    budget_s: float = DEFAULT_BUDGET_S
    client: object = None
    session: object = None
    started: float = 0.0       # monotonic time the job was handed to a worker
    over_budget: bool = False
    collateral: bool = False   # stopped with another job's worker: run again

    def live(self) -> bool:
        return not self.future.cancelled() or any(not w.cancelled() for w in self.waiters)


class LaneRunner:
    """One lane: its process pool, per-session queues served in turn, its running jobs.
    ``pool`` is the ``WorkPool`` it belongs to (told when a dropped job is forgotten)."""

    def __init__(self, lane: Lane, pool):
        self.lane, self.pool = lane, pool
        #: client -> session -> waiting jobs; both levels are served in turn.
        self.queues: OrderedDict[object, OrderedDict] = OrderedDict()
        self.running: dict = {}  # inner future -> job
        self.executor = None
        self.broken = None        # why the pool's workers stopped (BrokenProcessPool)
        self.processes: set = set()  # the pool's worker processes
        self.started = 0  # jobs handed to the executor (statistics)
        self.created_at = 0.0     # monotonic time the current workers were started
        self.ready_at = None      # ... and the time the first of them answered

    def _executor(self):
        if self.executor is None or self.broken is not None:
            if self.executor is not None:
                log.warning("dashboard workers of lane %r stopped (%s); starting new ones",
                            self.lane.name, self.broken)
                self.executor.shutdown(wait=False, cancel_futures=True)
            before = set(multiprocessing.active_children())
            self.executor = cf.ProcessPoolExecutor(
                max_workers=self.lane.workers, mp_context=worker_context(),
                initializer=_init_worker, initargs=(self.lane.nice,))
            self.broken = None
            self.created_at, self.ready_at = time.monotonic(), None
            self._ping(self.executor)
            # The pool starts a process per submitted ping while none is idle: these.
            self.processes = set(multiprocessing.active_children()) - before
        return self.executor

    def note(self, future: cf.Future, executor) -> None:
        """Note a finished future of a job or ping sent to ``executor``: if that is this
        lane's pool and a worker of it died, it is replaced at the next job
        (``BrokenProcessPool``, the pool's own word for it)."""
        if executor is self.executor and not future.cancelled() \
                and isinstance(future.exception(), cf.process.BrokenProcessPool):
            self.broken = future.exception()

    def _ping(self, executor) -> None:
        """Start every worker at once; note when the first one answers."""
        from .worker import ping

        def answered(future):
            self.note(future, executor)
            if self.executor is executor and self.ready_at is None:
                self.ready_at = time.monotonic()
        for _ in range(self.lane.workers):
            executor.submit(ping).add_done_callback(answered)

    def run_time(self, job: "Job", now: float) -> float:
        """Seconds ``job`` has had a working worker: its budget's clock. It starts when
        the job was handed over or when the workers answered, whichever is later."""
        if self.ready_at is None:
            return max(0.0, now - self.created_at - STARTUP_BUDGET_S)
        return now - max(job.started, self.ready_at)

    def queued(self) -> int:
        return sum(len(q) for sessions in self.queues.values() for q in sessions.values())

    def add(self, job: Job, front: bool = False) -> None:
        sessions = self.queues.setdefault(job.client, OrderedDict())
        queue = sessions.setdefault(job.session, collections.deque())
        (queue.appendleft if front else queue.append)(job)
        if front:
            self.queues.move_to_end(job.client, last=False)
            sessions.move_to_end(job.session, last=False)

    def next_job(self) -> Job | None:
        """The first live job of the next client's next session in turn (both move to
        the back of their lines)."""
        while self.queues:
            client, sessions = next(iter(self.queues.items()))
            session, queue = next(iter(sessions.items()))
            job = None
            while queue and job is None:
                candidate = queue.popleft()
                if candidate.live():
                    job = candidate
                else:
                    self.pool._forget(candidate)
            del sessions[session]
            if queue:
                sessions[session] = queue  # back of the client's line
            del self.queues[client]
            if sessions:
                self.queues[client] = sessions  # back of the line of clients
            if job is not None:
                return job
        return None

    def stop_workers(self) -> None:
        """Stop every worker process of this lane (it is started anew on the next job)."""
        executor, self.executor = self.executor, None
        self.created_at, self.ready_at = time.monotonic(), None
        if executor is None:
            return
        for process in self.processes:
            try:
                process.kill()
            except Exception:  # already gone
                pass
        self.processes = set()
        executor.shutdown(wait=False, cancel_futures=True)
