"""Background work for the dashboard: shared executors and a newest-wins job runner.

All model work runs in worker processes -- the single support (a few ms, but seconds in
hard cases), orientation sweeps (Fig. 11), uniform arrays (Figs. 5, 6) -- so the compiled
kernel (which holds the GIL) never stalls the server's event loop and the sliders stay
responsive. Executors and result caches are per server process, shared by
all sessions; runners are per session.

``LatestOnly`` gives the issue's "a newer request supersedes an older one": at most one
job of a runner is in flight; while it runs, only the newest request waits; results of
superseded requests are dropped. When its session is destroyed (the browser went away),
a runner drops its waiting job, cancels its job if still queued, ignores a late result
and lets go of the session's document.
"""
from __future__ import annotations

import asyncio
import concurrent.futures as cf
import logging
import multiprocessing
import sys
import threading
from collections import OrderedDict
from pathlib import Path

import panel as pn

from model import mu0

log = logging.getLogger(__name__)

#: Process pools, one worker each, so slow work of one kind never holds up another:
#: "support" the single support (Support tab), "sweep" the polar plots, "array" the
#: uniform arrays.
POOL_NAMES = ("support", "sweep", "array")


#: ``app/worker.py`` is loaded under this name in the server and in every worker, so its
#: functions and result classes pickle by reference in both directions (the server's
#: own package name, ``bokeh_app_<id>``, cannot be imported by a worker).
WORKER_MODULE = "micropillar_dashboard_worker"
_BOOT = f"""
import importlib.util, sys
if {WORKER_MODULE!r} not in sys.modules:
    spec = importlib.util.spec_from_file_location(
        {WORKER_MODULE!r}, {str(Path(__file__).with_name("worker.py"))!r})
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
"""


def worker_module():
    """``app/worker.py``, loaded once under ``WORKER_MODULE``."""
    if WORKER_MODULE not in sys.modules:
        exec(_BOOT, {})
    return sys.modules[WORKER_MODULE]


def _registry() -> tuple[dict, threading.Lock]:
    """The server process's pools and their lock, kept on the worker module (loaded once
    per process under a fixed name): Bokeh may load this package more than once in a
    server (Panel's liveness endpoint builds the app in a copy of its own), and a copy
    must not start workers of its own."""
    names = vars(worker_module())
    # dict.setdefault is atomic: two copies racing here still share one registry.
    return names.setdefault("_SERVER_POOLS", {}), names.setdefault("_SERVER_POOL_LOCK",
                                                                    threading.Lock())


def process_pool(name: str) -> cf.Executor:
    """The worker process ``name`` (started on first use, restarted if it died); it loads
    ``app/worker.py`` and the compiled kernel when it starts."""
    pools, lock = _registry()
    with lock:
        pool = pools.get(name)
        if pool is None or getattr(pool, "_broken", False):
            if pool is not None:
                log.warning("dashboard worker %r stopped (%s); starting a new one", name,
                            pool._broken)
            pool = cf.ProcessPoolExecutor(
                max_workers=1, mp_context=multiprocessing.get_context("spawn"),
                initializer=exec, initargs=(_BOOT + f"sys.modules[{WORKER_MODULE!r}].warm()\n",))
            pools[name] = pool
        return pool


def warm_up() -> None:
    """Load the compiled kernel here and start the worker processes (each loads it too)."""
    worker_module().warm()
    for name in POOL_NAMES:
        process_pool(name).submit(mu0)  # spawns the worker, which runs its initializer


class ResultCache:
    """A bounded LRU of finished results, shared by all sessions of the server process."""

    def __init__(self, maxsize: int = 128):
        self._data: OrderedDict = OrderedDict()
        self._lock = threading.Lock()
        self.maxsize = maxsize

    def get(self, key):
        with self._lock:
            if key in self._data:
                self._data.move_to_end(key)
                return self._data[key]
        return None

    def put(self, key, value) -> None:
        with self._lock:
            self._data[key] = value
            self._data.move_to_end(key)
            while len(self._data) > self.maxsize:
                self._data.popitem(last=False)


def cached_submit(cache: ResultCache, key, executor: cf.Executor, fn, *args, **kwargs):
    """A future of ``fn(*args, **kwargs)``: already done on a cache hit, else submitted."""
    hit = cache.get(key)
    if hit is not None:
        done = cf.Future()
        done.set_result(hit)
        return done
    try:
        future = executor.submit(fn, *args, **kwargs)
    except (cf.process.BrokenProcessPool, RuntimeError):  # a dead worker: start anew
        pools, lock = _registry()
        for name, pool in list(pools.items()):
            if pool is executor:
                with lock:
                    pools.pop(name, None)
                executor = process_pool(name)
        future = executor.submit(fn, *args, **kwargs)
    future.add_done_callback(
        lambda f: f.cancelled() or f.exception() is not None or cache.put(key, f.result()))
    return future


def _session_doc():
    doc = pn.state.curdoc
    return doc if doc is not None and doc.session_context is not None else None


class LatestOnly:
    """Runs the newest submitted job; older waiting jobs are dropped, stale results ignored.

    ``apply(result, error)`` receives the outcome of the newest job (``error`` is the
    exception or None) with the document locked, so it may update models directly.
    ``busy(flag)`` is told when work starts and when the runner falls idle. Without a
    server session (tests, scripts) jobs run immediately and synchronously. Once the
    session is destroyed (``close``), nothing is started or applied any more.
    """

    def __init__(self, apply, busy=None):
        self._apply = apply
        self._busy = busy
        self._pending = None
        self._running = False
        self._doc = None
        self._future = None  # of the job in flight
        self.closed = False
        self.generation = 0

    def submit(self, start) -> None:
        """Queue ``start``: a callable returning a ``concurrent.futures.Future``."""
        if self.closed:
            return
        self.generation += 1
        self._pending = start
        doc = _session_doc()
        if doc is None:
            self._run_now()
            return
        self._bind(doc)
        if not self._running:
            self._running = True
            self._call(self._busy, True)
            first = self._start()  # at once: the work overlaps the rest of this event

            async def drain():
                await self._drain(first)
            pn.state.execute(drain)

    def submit_later(self, start, delay_ms: int) -> None:
        """``submit(start)`` once nothing newer was asked for during ``delay_ms`` (so
        background work waits until a slider stops moving)."""
        if self.closed:
            return
        self.generation += 1
        doc = _session_doc()
        if doc is None:
            self.submit(start)
            return
        self._bind(doc)
        generation = self.generation

        def later():
            if generation == self.generation:
                self.submit(start)
        doc.add_timeout_callback(later, delay_ms)

    def cancel(self) -> None:
        """Forget the waiting job and ignore the result of the running one."""
        self.generation += 1
        self._pending = None

    def close(self, *_session_context) -> None:
        """The session ended: forget the waiting job, cancel the job in flight if it has
        not started yet (a running one cannot be stopped; its result is ignored), start
        nothing more and drop the document."""
        self.closed = True
        self.cancel()
        if self._future is not None:
            self._future.cancel()
        self._doc = None

    def _bind(self, doc) -> None:
        """Work for ``doc``'s session, and stop when that session is destroyed."""
        if doc is not self._doc:
            self._doc = doc
            doc.on_session_destroyed(self.close)

    def _run_now(self) -> None:
        start, self._pending = self._pending, None
        try:
            result, error = start().result(), None
        except Exception as exc:  # shown by ``apply``: the page stays usable
            result, error = None, exc
        self._apply(result, error)

    def _start(self):
        """Start the waiting job: (its generation, its future or the exception it raised)."""
        start, self._pending = self._pending, None
        try:
            self._future = start()
            return self.generation, self._future
        except Exception as exc:
            return self.generation, exc

    async def _drain(self, job) -> None:
        try:
            while job is not None:
                generation, future = job
                try:
                    if isinstance(future, Exception):
                        raise future
                    result, error = await asyncio.wrap_future(future), None
                except asyncio.CancelledError:
                    if not future.cancelled():  # this task itself is cancelled
                        raise
                    result, error = None, None  # cancelled by ``close``: nothing to show
                except Exception as exc:
                    result, error = None, exc
                if generation == self.generation:
                    self._call(self._apply, result, error)
                job = self._start() if self._pending is not None else None
        finally:
            self._running = False
            self._future = None
            self._call(self._busy, False)

    def _call(self, fn, *args) -> None:
        """Run ``fn(*args)`` on the session's document with its lock held."""
        if fn is None or self.closed:
            return
        if self._doc is None:
            fn(*args)
            return
        doc = self._doc

        def locked():
            # Bokeh's own hold: the changes leave through Bokeh's locked write path when
            # it is released. Left to pn.io.hold alone, Panel 1.9 writes them itself and,
            # under load, can leave a session's last update unsent (its _dispatch_msgs
            # clears the write block of messages queued meanwhile).
            if self.closed:
                return
            held = doc.callbacks.hold_value
            if not held:
                doc.hold("combine")
            try:
                fn(*args)
            except Exception:
                log.exception("dashboard update failed")
            finally:
                if not held:
                    doc.unhold()
        try:
            doc.add_next_tick_callback(locked)
        except Exception:  # the session has closed meanwhile
            log.debug("session gone; update dropped")

