"""Work behind the page: worker processes shared by every session, served fairly.

All model work runs in worker processes, so the compiled kernel (which holds the GIL)
never stalls the server's event loop. Two *lanes* of workers serve it:

* ``interactive`` -- the single support behind the Support tab (milliseconds; what a
  slider move waits for);
* ``background`` -- orientation sweeps, uniform arrays, load curves (tens of ms to
  seconds), its processes at a lower CPU priority so they never slow the interactive lane
  or the server.

Each lane keeps one queue per session, grouped by client (the browser's address), and
takes jobs in turn: clients in turn, and each client's sessions in turn. So one session's
pile of work delays another session's next job by at most one job, and one client opening
many pages cannot starve the others. A lane's queue is bounded (``MAX_QUEUED``): beyond
it a request fails at once with ``ServerBusy`` ("busy, try again"). Every job has a time
budget (``budget_s``): a worker still busy with a job past its budget is stopped and
replaced, the job fails with ``OverBudget`` (remembered for a while), and other jobs
caught in the stop are run again. Finished results are shared by every session
(``app.result_cache``) and identical requests in flight are computed once.

Per server process: every copy of the app Bokeh builds (Panel's liveness endpoint makes
one) hands its work to the same workers, since this module is imported once.
"""
from __future__ import annotations

import concurrent.futures as cf
import itertools
import logging
import os
import threading
import time

from .lanes import DEFAULT_BUDGET_S, LANES, Job, Lane, LaneRunner
from .result_cache import CACHE_SIZE, ResultCache
from .trace import mark

__all__ = ["WorkPool", "Lane", "LANES", "ServerBusy", "OverBudget", "work_pool", "warm_up",
           "load_scale"]

log = logging.getLogger(__name__)


#: At most this many jobs wait in one lane (all sessions together).
MAX_QUEUED = 96
#: How long a request that ran over its budget is refused at once.
OVER_BUDGET_MEMORY_S = 120.0
#: How often the watchdog looks at the running jobs.
WATCH_INTERVAL_S = 0.1
class ServerBusy(RuntimeError):
    """The lane's queue is full: the request was not accepted."""


class OverBudget(RuntimeError):
    """A job took longer than its time budget and was stopped."""


class WorkPool:
    """The server process's lanes of workers, queues and shared results."""

    def __init__(self, lanes=None, max_queued: int = MAX_QUEUED, cache_size: int = CACHE_SIZE):
        self._lock = threading.RLock()
        self.lanes = {name: LaneRunner(lane, self) for name, lane in (lanes or LANES).items()}
        self.max_queued = max_queued
        self.cache = ResultCache(cache_size)
        self._inflight: dict = {}
        self._over_budget: dict = {}  # key -> (monotonic time, message)
        self._ids = itertools.count()
        self._watchdog = None

    # ------------------------------------------------------------------ public
    def session_id(self) -> int:
        """A fresh identifier for a session's queue."""
        return next(self._ids)

    def submit(self, lane: str, key, fn, *args, session=None, client=None,
               budget_s: float = DEFAULT_BUDGET_S, **kwargs) -> cf.Future:
        """A future of ``fn(*args, **kwargs)`` computed in ``lane``'s workers.

        Already done on a cache hit; shared with an identical request (same ``key``) still
        in flight; else queued behind ``session``'s earlier jobs and served in turn with
        the other clients and sessions. Raises nothing: a full queue sets ``ServerBusy``
        on the future, a job past ``budget_s`` seconds ``OverBudget``. Cancelling the
        future before its job started means the job never runs.
        """
        future: cf.Future = cf.Future()
        hit = self.cache.get(key) if key is not None else None
        if hit is not None:
            future.set_result(hit)
            return future
        with self._lock:
            refused = self._refused(key)
            if refused:
                future.set_exception(OverBudget(refused))
                return future
            if key is not None and key in self._inflight:
                self._inflight[key].waiters.append(future)
                return future
            runner = self.lanes[lane]
            if runner.queued() >= self.max_queued:
                future.set_exception(ServerBusy(
                    f"The server is busy ({runner.queued()} computations are waiting); "
                    "try again in a moment."))
                return future
            job = Job(key, fn, args, kwargs, future, [], float(budget_s), client, session)
            if key is not None:
                self._inflight[key] = job
            runner.add(job)
            self._dispatch(runner)
            self._ensure_watchdog()
        return future

    def warm_up(self) -> None:
        """Start every lane's workers (each loads the compiled kernel)."""
        for runner in self.lanes.values():
            with self._lock:
                runner._executor()

    def stats(self) -> dict:
        with self._lock:
            return {name: {"queued": r.queued(), "running": len(r.running),
                           "started": r.started,
                           "workers": r.lane.workers} for name, r in self.lanes.items()} | {
                "cached": len(self.cache), "cached_bytes": self.cache.nbytes,
                "inflight": len(self._inflight)}

    def executor(self, lane: str):
        """The process pool of ``lane`` (started if needed)."""
        with self._lock:
            return self.lanes[lane]._executor()

    def idle(self) -> bool:
        """Whether no job is queued, running or in flight in any lane."""
        with self._lock:
            return not self._inflight and all(
                not r.queued() and not r.running for r in self.lanes.values())

    def recycle_workers(self) -> bool:
        """Replace every started lane's worker processes by fresh ones, if the pool is
        idle (else nothing; False). A worker keeps what a class's work left in its heap
        and the model's caches (``model.contact.support``, ``model.arrays.uniform``: tens of MB after a
        class of thirty); fresh workers load the compiled kernel from numba's cache and
        are as small as at the server's start. The old ones finish and exit; the new
        ones start at once, so the next page does not wait for them."""
        with self._lock:
            if not self.idle():
                return False
            for runner in self.lanes.values():
                if runner.executor is not None:
                    old, runner.executor = runner.executor, None
                    old.shutdown(wait=False, cancel_futures=True)
                    runner._executor()
            return True

    def shutdown(self) -> None:
        for runner in self.lanes.values():
            if runner.executor is not None:
                runner.executor.shutdown(wait=False, cancel_futures=True)
                runner.executor = None

    # ------------------------------------------------------------------ internals
    def _forget(self, job: Job) -> None:
        if job.key is not None and self._inflight.get(job.key) is job:
            del self._inflight[job.key]

    def _refused(self, key) -> str:
        """The message of a recent over-budget run of ``key``, if any."""
        if key is None or key not in self._over_budget:
            return ""
        when, message = self._over_budget[key]
        if time.monotonic() - when > OVER_BUDGET_MEMORY_S:
            del self._over_budget[key]
            return ""
        return message

    def _dispatch(self, runner: LaneRunner) -> None:
        """Hand queued jobs to free workers (called with the lock held)."""
        while len(runner.running) < runner.lane.workers:
            job = runner.next_job()
            if job is None:
                return
            try:
                executor = runner._executor()
                inner = executor.submit(job.fn, *job.args, **job.kwargs)
            except (cf.process.BrokenProcessPool, RuntimeError):
                runner.executor = None  # a dead pool: start anew
                executor = runner._executor()
                inner = executor.submit(job.fn, *job.args, **job.kwargs)
            job.started = time.monotonic()
            mark("worker starts", lane=runner.lane.name)
            runner.running[inner] = job
            runner.started += 1
            inner.add_done_callback(
                lambda f, job=job, runner=runner, ex=executor: self._done(runner, job, f, ex))

    def _ensure_watchdog(self) -> None:
        if self._watchdog is None or not self._watchdog.is_alive():
            self._watchdog = threading.Thread(target=self._watch, name="work-pool-watchdog",
                                              daemon=True)
            self._watchdog.start()

    def _watch(self) -> None:
        """Stop the workers of a lane whose job ran past its budget.

        A budget is seconds of a worker's own time: on a machine busier than its cores
        (load average above the core count) the wall-clock allowance grows in proportion,
        so a machine shared with other work does not stop ordinary jobs.
        """
        while True:
            time.sleep(WATCH_INTERVAL_S)
            now = time.monotonic()
            scale = load_scale()
            with self._lock:
                for runner in self.lanes.values():
                    late = [j for j in runner.running.values() if not j.over_budget
                            and runner.run_time(j, now) > j.budget_s * scale]
                    if not late:
                        continue
                    for job in runner.running.values():
                        job.collateral = job not in late
                    for job in late:
                        job.over_budget = True
                        log.warning("a %s job ran past its %.3g s budget; stopping its worker",
                                    runner.lane.name, job.budget_s)
                    runner.stop_workers()

    def _done(self, runner: LaneRunner, job: Job, inner: cf.Future, executor=None) -> None:
        error = inner.exception() if not inner.cancelled() else cf.CancelledError()
        mark("worker ends", lane=runner.lane.name)
        runner.note(inner, executor)
        with self._lock:
            runner.running.pop(inner, None)
            if job.over_budget:
                error = OverBudget(
                    f"this computation needs more than its {job.budget_s:g} s of the "
                    "server's time and was stopped; try a looser solver tolerance or other "
                    "parameters")
                if job.key is not None:
                    self._over_budget[job.key] = (time.monotonic(), str(error))
            elif job.collateral and error is not None and job.live():
                # Caught in the stop of another job's worker: run it again, first in line.
                job.collateral = False
                runner.add(job, front=True)
                self._dispatch(runner)
                return
            self._forget(job)
            self._dispatch(runner)
        if error is None:
            result = inner.result()
            if job.key is not None:
                self.cache.put(job.key, result)
        for future in (job.future, *job.waiters):
            if future.cancelled() or not future.set_running_or_notify_cancel():
                continue
            if error is None:
                future.set_result(result)
            else:
                future.set_exception(error)


def load_scale() -> float:
    """How much slower than its cores the machine runs now: load average / cores, >= 1."""
    try:
        return max(1.0, os.getloadavg()[0] / (os.cpu_count() or 1))
    except OSError:  # no load average on this system
        return 1.0


_POOL: WorkPool | None = None
_POOL_LOCK = threading.Lock()


def work_pool() -> WorkPool:
    """The server process's ``WorkPool`` (made on first use)."""
    global _POOL
    with _POOL_LOCK:
        if _POOL is None:
            _POOL = WorkPool()
        return _POOL


_SOLVER_READY = threading.Event()


def solver_ready() -> bool:
    """Whether this server process has the compiled kernel (``warm_up`` finished)."""
    return _SOLVER_READY.is_set()


def warm_up() -> None:
    """Load the compiled kernel here and start every worker (each loads it too)."""
    from .worker import warm
    warm()
    _SOLVER_READY.set()
    work_pool().warm_up()


def compile_in_a_process(timeout_s: float = 600.0) -> bool:
    """Fill numba's cache with the kernel in a separate process (``python -m model
    warmup``); True if it succeeded. The compile holds the GIL most of the time, so in a
    thread of the server it slowed every page the server built meanwhile (the first page
    of a first start 3.3 s instead of 2.3 s)."""
    import subprocess
    import sys

    try:
        # At a lower CPU priority: pages come first.
        done = subprocess.run([sys.executable, "-m", "model", "warmup"], timeout=timeout_s,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                              preexec_fn=_lower_priority)
    except (OSError, subprocess.TimeoutExpired) as exc:
        log.warning("compiling the solver in a separate process failed (%s); compiling here",
                    exc)
        return False
    if done.returncode != 0:
        log.warning("compiling the solver in a separate process failed (exit %s: %s); "
                    "compiling here", done.returncode, done.stderr.strip()[-500:])
        return False
    return True


def _lower_priority() -> None:
    try:
        os.nice(10)
    except OSError:
        pass


def _compile_then_warm_up() -> None:
    compile_in_a_process()  # if it failed, warm_up compiles in this process instead
    warm_up()


def start_warm_up() -> bool:
    """``warm_up`` at once when numba's cache holds the kernel (about a second), else in
    the background, so a first start after installing (a compile of ~15-20 s) serves pages
    at once; they say the solver is being prepared. The compile runs in a process of its
    own (``compile_in_a_process``), then the kernel is loaded from the cache it filled.
    True if in the background."""
    from model._kernel import COLD_COMPILE_SECONDS, cache_is_cold

    if not cache_is_cold():
        warm_up()
        return False
    log.warning("preparing the solver (first start: compiling, ~%d s); pages are served "
                "meanwhile", COLD_COMPILE_SECONDS)
    threading.Thread(target=_compile_then_warm_up, name="solver-warm-up", daemon=True).start()
    return True
