"""Independent points of a sweep: serially, on a local process pool or on a dask cluster.

``run_points(func, tasks)`` returns ``[func(t) for t in tasks]`` in task order whatever
runs them, so the three ways give identical results. Points are sent out in chunks,
about four per worker, strided so that the slow corner of a parameter grid (compliant
supports creep for hundreds of tau) is shared out. ``progress(done, total)`` is called in
the calling thread after each point; once the ``cancel`` event is set, queued work is
cancelled, running workers are stopped and ``SweepCancelled`` is raised.
"""
from __future__ import annotations

import multiprocessing
import signal
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

__all__ = ["SweepCancelled", "run_points", "START_METHOD"]

#: Start method of the local pool; ``None`` chooses one (see ``_pool_context``).
START_METHOD = None
_POLL = 0.05  # seconds between checks of the cancel event while waiting for workers


class SweepCancelled(Exception):
    """The ``cancel`` event was set; ``done`` of ``total`` points had finished."""

    def __init__(self, done: int, total: int):
        super().__init__(f"sweep cancelled after {done} of {total} points")
        self.done, self.total = done, total


def run_points(func, tasks, workers: int = 1, scheduler=None, progress=None,
               cancel=None, sizes=None, on_row=None) -> list:
    """``[func(t) for t in tasks]``, on ``workers`` local processes or on ``scheduler``.

    ``func`` must be a module-level function (it is pickled by reference); ``scheduler``
    is a ``dask.distributed.Client`` or the address of a scheduler ("tcp://host:8786").
    ``sizes`` (one int per task, e.g. the points of a chain of points) makes
    ``progress`` count those instead of tasks. ``on_row(i, row)`` is called in the calling
    thread as each task's result arrives (in the order they finish).
    """
    out = _Rows(len(tasks), progress, cancel, sizes, on_row)
    out.check()
    # Tasks that are chains of points already carry enough work each: sent one by one,
    # the pool balances them (a slow chain does not hold back three others).
    one_each = sizes is not None
    if scheduler is not None:
        _run_dask(func, tasks, scheduler, out, one_each)
    elif workers > 1:
        _run_pool(func, tasks, workers, out, one_each)
    else:
        for i, task in enumerate(tasks):
            out.check()
            out.add([i], [func(task)])
    return out.rows


def _run_chunk(func, tasks) -> list:
    return [func(t) for t in tasks]


class _Rows:
    """Results in task order, with the progress callback and the cancel check."""

    def __init__(self, total, progress, cancel, sizes=None, on_row=None):
        self.on_row = on_row
        self.sizes = [1] * total if sizes is None else list(sizes)
        self.rows, self.done, self.total = [None] * total, 0, sum(self.sizes)
        self.progress, self.cancel = progress, cancel

    def add(self, indices, rows) -> None:
        for i, row in zip(indices, rows):
            self.rows[i] = row
            if self.on_row is not None:
                self.on_row(i, row)
            for _ in range(self.sizes[i]):  # one call per point, as documented
                self.done += 1
                if self.progress is not None:
                    self.progress(self.done, self.total)

    def check(self) -> None:
        if self.cancel is not None and self.cancel.is_set():
            raise SweepCancelled(self.done, self.total)


def _chunks(total: int, slots: int, one_each: bool = False) -> list:
    """Task indices in about four strided chunks per worker slot (or one per task)."""
    count = total if one_each else min(total, 4 * slots)
    return [list(range(j, total, count)) for j in range(count)]


# --------------------------------------------------------------------------- local pool

def _pool_context(module: str):
    """``fork`` from a single-threaded process (fast: the compiled kernel is inherited);
    ``forkserver`` otherwise, since forking a multi-threaded process can deadlock."""
    methods = multiprocessing.get_all_start_methods()
    method = START_METHOD or ("fork" if "fork" in methods and threading.active_count() == 1
                              else "forkserver" if "forkserver" in methods else "spawn")
    context = multiprocessing.get_context(method)
    if method == "forkserver":
        context.set_forkserver_preload([module])  # import the model once, fork from there
    return context


def _quiet_worker() -> None:
    """Pool workers leave Ctrl-C to the parent, which cancels the sweep."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _run_pool(func, tasks, workers, out, one_each=False) -> None:
    pool = ProcessPoolExecutor(workers, mp_context=_pool_context(func.__module__),
                               initializer=_quiet_worker)
    try:
        futures = {pool.submit(_run_chunk, func, [tasks[i] for i in idx]): idx
                   for idx in _chunks(len(tasks), workers, one_each)}
        pending = set(futures)
        while pending:
            out.check()
            finished, pending = wait(pending, timeout=_POLL, return_when=FIRST_COMPLETED)
            for future in finished:
                out.add(futures[future], future.result())
    except BaseException:  # cancelled, Ctrl-C or a failed point: stop the workers now
        _abandon(pool)
        raise
    pool.shutdown()


def _abandon(pool) -> None:
    """Stop the pool's workers now (not after their chunks), cancel the queued chunks and
    wait for the pool to shut down."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    for process in processes:
        process.terminate()
    for process in processes:
        process.join(timeout=5)
    # With its workers gone, the pool's manager thread ends at once; waiting for it here
    # keeps it from closing its wake-up pipe while the interpreter's exit hook writes to
    # it, which printed "OSError: Bad file descriptor" after a Ctrl-C (CPython 3.11).
    pool.shutdown(wait=True, cancel_futures=True)


# --------------------------------------------------------------------------- dask

def _run_dask(func, tasks, scheduler, out, one_each=False) -> None:
    """The chunks on a dask.distributed cluster (imported only here: optional)."""
    try:
        import distributed
    except ImportError:
        raise ImportError("a scheduler needs dask.distributed: "
                          "pip install 'micropillar-friction[cluster]'") from None
    if isinstance(scheduler, str):
        _check_address(distributed, scheduler)
        client = distributed.Client(scheduler, timeout=30, set_as_default=False)
    elif isinstance(scheduler, distributed.Client):
        client = None
    else:
        raise ValueError(f"scheduler={scheduler!r} must be a dask.distributed Client or an "
                         "address like tcp://host:8786")
    try:
        _map_dask(distributed, client or scheduler, func, tasks, out, one_each)
    finally:
        if client is not None:
            client.close()


def _check_address(distributed, address: str) -> None:
    """``ValueError`` for an address without a port or with an unknown host, checked before
    ``Client`` is built (a client that fails to start hangs in its finaliser)."""
    try:
        distributed.comm.resolve_address(address)
    except (ValueError, OSError) as error:
        raise ValueError(f"scheduler={address!r} is not a reachable address like "
                         f"tcp://host:8786 ({error})") from None


def _map_dask(distributed, client, func, tasks, out, one_each=False) -> None:
    slots = max(1, sum(client.nthreads().values()))
    chunks = _chunks(len(tasks), slots, one_each)
    futures = client.map(_run_chunk, [func] * len(chunks),
                         [[tasks[i] for i in idx] for idx in chunks], pure=False)
    index = {future.key: idx for future, idx in zip(futures, chunks)}
    queue = distributed.as_completed(futures, loop=client.loop)
    try:
        while not queue.is_empty():
            out.check()
            if not queue.has_ready():
                time.sleep(_POLL)
                continue
            for future in queue.next_batch(block=False):
                out.add(index[future.key], future.result())
    finally:
        client.cancel([f for f in futures if not f.done()])
