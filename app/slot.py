"""One result's lifecycle (``Slot``) and what it asks the work pool for (``Request``).

A control a result depends on changes -> the result is *stale*; if it is *needed* (its
view is on screen) a request goes to the server's ``WorkPool`` (``app.jobs``), after a
short pause for results that are expensive; at most one job per result is in flight and
only the newest waiting request is kept (newest wins); the finished result is applied with
the session's document locked, or its error is shown while the last good result stays.
When the session ends, waiting work is dropped, queued work cancelled and late results
ignored. Without a server session (tests, scripts, notebooks) requests run at once.
"""
from __future__ import annotations

import asyncio
import concurrent.futures as cf
import logging
import time
from dataclasses import dataclass
from typing import Callable

import panel as pn

from .jobs import work_pool
from .trace import mark

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Request:
    """What to compute: the worker lane, a cache key shared by every session, the call."""

    lane: str
    key: object
    fn: Callable
    args: tuple = ()
    budget_s: float = 5.0
    #: A refinement computed once this result is shown (e.g. a finer regime map).
    then: "Request | None" = None


def client_address():
    """The address of the session's browser (behind a proxy: with ``--use-xheaders``, the
    forwarded one), so the work pool serves clients in turn and the page gate counts their
    unopened pages; None without a server."""
    doc = _session_doc()
    try:
        return doc.session_context.request.remote_ip if doc is not None else None
    except Exception:  # no request (a server-side session): one anonymous client
        return None


def _session_doc():
    doc = pn.state.curdoc
    return doc if doc is not None and doc.session_context is not None else None


class Slot:
    """The lifecycle of one result of one session (see the module docstring).

    ``make()`` builds the ``Request`` from the state (a ``ValueError`` becomes the slot's
    error); ``apply(value)`` stores a finished result; ``fail(message)`` shows an error.
    """

    def __init__(self, owner, name: str, make, apply, depends=(),
                 delay_ms: int = 0, needed: bool = True):
        self.owner, self.name = owner, name
        self._make, self._apply = make, apply
        self.depends = tuple(depends)
        self.delay_ms = delay_ms
        self.needed = needed
        self.stale = True
        self.closed = False
        self.generation = 0
        self._pending = None     # the newest request not yet started
        self._running = False
        self._future = None      # of the job in flight
        self._doc = None
        self.requested_at = None  # perf_counter of the newest request (latency statistics)
        self.applied_key = None   # the request key of the result on show

    # ------------------------------------------------------------------ triggers
    def invalidate(self, *_events) -> None:
        self.stale = True
        if not self.needed:
            self._drop()
        elif self._open:
            self.request()

    def set_needed(self, needed: bool) -> None:
        self.needed = needed
        if needed and self.stale and self._open:
            self.request()

    @property
    def _open(self) -> bool:
        """Whether the page has been opened (``SessionResults.start``): before that,
        changes only mark the result stale."""
        return getattr(self.owner, "started", True)

    def request(self) -> None:
        if self.closed:
            return
        self.stale = False
        self.requested_at = time.perf_counter()
        try:
            req = self._make()
        except ValueError as exc:
            self._drop()
            self._fail(f"Invalid parameters: {exc}")
            return
        if req is None:  # nothing to compute now (e.g. an unusable design): drop the older
            self._drop()
            return
        # A slot serves one session: once bound, its document, not the context's, which a
        # callback scheduled while another session was current can leave naming that one.
        doc = self._doc or _session_doc()
        if doc is None:
            self._run_now(req)
        elif self.delay_ms:
            self._later(req, doc)
        else:
            self._submit(req, doc)

    @property
    def current(self) -> bool:
        """Whether the result on show is the one of the present controls."""
        try:
            req = self._make()
        except ValueError:
            return False
        while req is not None and req.then is not None:
            req = req.then
        return req is not None and req.key == self.applied_key

    def cancel(self) -> None:
        """Forget the waiting request and ignore the result of the running one."""
        self.generation += 1
        self._pending = None

    def _drop(self) -> None:
        """``cancel``, and clear the busy marker a delayed request set (a running job
        clears its own when it ends)."""
        self.cancel()
        if not self._running:
            self.owner._set_busy(self.name, False)

    def close(self, *_session_context) -> None:
        """The session ended: drop the waiting request, cancel a queued job, start nothing
        more, ignore what is still running and let go of the document."""
        self.closed = True
        self.cancel()
        if self._future is not None:
            self._future.cancel()
        self._doc = None

    # ------------------------------------------------------------------ running
    def _start(self, req: Request) -> cf.Future:
        mark("job submitted", slot=self.name)
        return work_pool().submit(req.lane, req.key, req.fn, *req.args,
                                  session=self.owner.session_id,
                                  client=getattr(self.owner, "client", None),
                                  budget_s=req.budget_s)

    def _run_now(self, req: Request) -> None:
        self.generation += 1
        try:
            value, error = self._start(req).result(), None
        except Exception as exc:
            value, error = None, exc
        self._finish(req, value, error)

    def _later(self, req: Request, doc) -> None:
        self._bind(doc)
        self.generation += 1
        generation = self.generation
        # The result on show is stale from now on, not from when the delay is over.
        self.owner._set_busy(self.name, True)

        def later():
            if generation == self.generation and not self.closed:
                self._submit(req, doc)
        doc.add_timeout_callback(later, self.delay_ms)

    def _submit(self, req: Request, doc) -> None:
        self._bind(doc)
        self.generation += 1
        self._pending = req
        if not self._running:
            self._running = True
            self.owner._set_busy(self.name, True)
            first = self._take()

            async def drain():
                await self._drain(first)
            pn.state.execute(drain)

    def _take(self):
        req, self._pending = self._pending, None
        try:
            self._future = self._start(req)
        except Exception as exc:  # noqa: BLE001 - shown on the page
            future = cf.Future()
            future.set_exception(exc)
            self._future = future
        return self.generation, self._future, req

    async def _drain(self, job) -> None:
        last = None  # the final result: applied with the busy marker's clearing, one message
        try:
            while job is not None:
                generation, future, req = job
                try:
                    value, error = await asyncio.wrap_future(future), None
                except asyncio.CancelledError:
                    if not future.cancelled():  # this task itself is cancelled
                        raise
                    value, error = None, None
                except Exception as exc:
                    value, error = None, exc
                current = generation == self.generation and not future.cancelled()
                job = self._take() if self._pending is not None and not self.closed else None
                if current and job is None:
                    last = (req, value, error)
                elif current:
                    self._locked(self._finish, req, value, error)
        finally:
            self._running = False
            self._future = None
            self._locked(self._settle, last)

    def _settle(self, last) -> None:
        """Apply the final result, if any, and clear the busy marker unless a new job has
        started meanwhile (a follow-up request, or a change that came in between)."""
        if last is not None:
            self._finish(*last)
        if not self._running:
            self.owner._set_busy(self.name, False)

    def _finish(self, req: Request, value, error) -> None:
        if error is not None:
            self._fail(f"{self.owner.LABELS.get(self.name, self.name)} failed: "
                       f"{type(error).__name__}: {error}")
            return
        self.owner._set_error(self.name, "")
        self.applied_key = req.key
        self._apply(value)
        if req.then is not None and not self.closed:
            doc = self._doc or _session_doc()
            if doc is None:
                self._run_now(req.then)
            else:
                self._submit(req.then, doc)

    def _fail(self, message: str) -> None:
        self.owner._set_error(self.name, message)

    def _bind(self, doc) -> None:
        if doc is not self._doc:
            self._doc = doc
            doc.on_session_destroyed(self.close)

    def _locked(self, fn, *args) -> None:
        """Run ``fn(*args)`` on the session's document with its lock held (the event
        loop's next turn); what it changes reaches the page in one message."""
        if self.closed:
            return
        doc = self._doc
        if doc is None:
            fn(*args)
            return

        def locked():
            if self.closed:
                return
            try:
                mark("result applied", slot=self.name)
                with pn.io.hold(doc):
                    fn(*args)
                mark("result sent", slot=self.name)
            except Exception:
                log.exception("dashboard update failed")
        try:
            doc.add_next_tick_callback(locked)
        except Exception:  # the session has closed meanwhile
            log.debug("session gone; update dropped")
