"""The server's pages: a gate per client on pages built but not yet opened, and the
memory of ended sessions handed back to the system.

Per server process, like the work pool (``app.jobs``): ``page_gate()`` is the one gate.
"""
from __future__ import annotations

import ctypes
import os
import threading
import time

from .heap import settle

#: Pages of one client requested but not yet opened by a browser (its document_ready)
#: that a new page may join; past it the client gets a short "busy" page instead. Each
#: page request costs the server's one event loop a light page (~25-75 ms; the dashboard
#: is built only once opened, ``app.opening``), so a burst of page requests that are
#: never opened (a script fetching URLs) would still hold every session and the liveness
#: endpoint for a second per twenty; the busy page, answered before any session is made,
#: costs ~1 ms. A class behind one address (a NAT) opening at once gets some busy pages,
#: which reload themselves.
MAX_UNOPENED_PAGES = 2
#: Seconds after which a page that was never opened stops counting (a health check's
#: session, a closed tab).
UNOPENED_PAGE_S = 10.0
#: A client whose pages browsers do open earns one more unopened page for each page opened
#: in the last ``CREDIT_WINDOW_S`` seconds, up to ``MAX_CREDIT``: a class behind one
#: address (a school's NAT, a proxy) gets in within a few rounds of reloads (2, 4, 8, ...
#: pages at once), while a client that never opens its pages stays at two.
CREDIT_WINDOW_S = 120.0
MAX_CREDIT = 16


class PageGate:
    """Per client: the pages built that no browser has opened yet (``admit``, ``opened``).

    A class behind one address opens its pages soon after they are built, and each page
    opened raises the client's bound (``allowance``) for a while; a burst of page requests
    that are never opened stays at ``max_unopened``.
    """

    def __init__(self, max_unopened: int = MAX_UNOPENED_PAGES,
                 window_s: float = UNOPENED_PAGE_S, credit_window_s: float = CREDIT_WINDOW_S,
                 max_credit: int = MAX_CREDIT):
        self.max_unopened, self.window_s = max_unopened, window_s
        self.credit_window_s, self.max_credit = credit_window_s, max_credit
        self._pages: dict = {}  # client -> {page id: monotonic time built}
        self._opens: dict = {}  # client -> [monotonic times its pages were opened]
        self._lock = threading.Lock()

    def allowance(self, client) -> int:
        """How many unopened pages ``client`` may have: two, plus its recent opens."""
        now = time.monotonic()
        with self._lock:
            return self._allowance(client, now)

    def _allowance(self, client, now: float) -> int:
        opens = [t for t in self._opens.get(client, ()) if now - t < self.credit_window_s]
        if opens:
            self._opens[client] = opens[-self.max_credit:]
        else:
            self._opens.pop(client, None)
        return self.max_unopened + min(len(opens), self.max_credit)

    def admit(self, client, page) -> bool:
        """Whether ``client`` may have one more page built (then ``page`` counts)."""
        now = time.monotonic()
        with self._lock:
            pages = {p: t for p, t in self._pages.get(client, {}).items()
                     if now - t < self.window_s}
            admitted = len(pages) < self._allowance(client, now)
            if admitted:
                pages[page] = now
            if pages:
                self._pages[client] = pages
            else:
                self._pages.pop(client, None)
            return admitted

    def has_room(self, client) -> bool:
        """Whether ``admit`` would take one more page of ``client`` now (nothing counts)."""
        now = time.monotonic()
        with self._lock:
            return self._unopened(client, now) < self._allowance(client, now)

    def built(self, client, page) -> None:
        """``page`` is built: its time counts from now (a build may take long)."""
        with self._lock:
            pages = self._pages.get(client)
            if pages is not None and page in pages:
                pages[page] = time.monotonic()

    def opened(self, client, page) -> None:
        """A browser has ``page``: it no longer counts, and the client earns credit."""
        with self._lock:
            if self._forget(client, page):
                self._opens.setdefault(client, []).append(time.monotonic())

    def gone(self, client, page) -> None:
        """``page``'s session ended (opened or not): it no longer counts."""
        with self._lock:
            self._forget(client, page)

    def _forget(self, client, page) -> bool:
        pages = self._pages.get(client)
        if pages is None or page not in pages:
            return False
        del pages[page]
        if not pages:
            del self._pages[client]
        return True

    def unopened(self, client) -> int:
        now = time.monotonic()
        with self._lock:
            return self._unopened(client, now)

    def _unopened(self, client, now: float) -> int:
        return sum(now - t < self.window_s for t in self._pages.get(client, {}).values())


def settle_fraction(text: str | None) -> float:
    """``SETTLE_FRACTION`` from its setting's text (None: the default, 0.5)."""
    try:
        value = float(text) if text is not None else 0.5
    except ValueError:
        value = float("nan")
    if not 0 <= value < float("inf"):
        raise ValueError(f"MICROPILLAR_SETTLE_FRACTION={text!r}: give a number >= 0 "
                         "(0 collects at every departure; unset: 0.5)")
    return value


#: Seconds after the last session ended before its memory is handed back to the system.
RELEASE_DELAY_S = 5.0
#: Closed pages are collected while others are open only once they are at least this
#: fraction of the open ones (``settle_due``): the collection pauses the event loop in
#: proportion to every object the server holds (~0.3 s with 4 pages open, up to 1.2 s with
#: 30 on a quiet 2-core machine, ``benchmarks/bench_departures.py``), so a
#: class leaving one by one no longer pauses the others at each departure, and the closed
#: pages held meanwhile are at most this fraction of the open pages' memory. 0: at every
#: departure. Set by ``MICROPILLAR_SETTLE_FRACTION`` (docs/deploying.md).
SETTLE_FRACTION = settle_fraction(os.environ.get("MICROPILLAR_SETTLE_FRACTION"))
_RELEASE_TIMER: threading.Timer | None = None
_RELEASE_LOCK = threading.Lock()
#: Sessions ended since the closed pages were last collected.
_CLOSED = 0


def settle_due(closed: int, still_open: int, fraction: float | None = None) -> bool:
    """Whether the pages of ``closed`` ended sessions are worth collecting now, with
    ``still_open`` sessions left: always when none is left (the pause meets no one),
    else once the closed pages are at least ``fraction`` (default ``SETTLE_FRACTION``)
    of the open ones."""
    fraction = SETTLE_FRACTION if fraction is None else fraction
    return still_open <= 0 or closed >= fraction * still_open


def release_memory(sessions_open=None, closed: int | None = None) -> dict:
    """Collect garbage (``app.heap.settle``: the open pages' objects are frozen out of
    the automatic collections) and hand the heap's free pages back to the system (glibc's
    ``malloc_trim``; elsewhere a no-op): CPython's allocator otherwise keeps the memory
    of ended sessions for reuse, and the server stays at its peak after a class left.

    ``closed``: the sessions ended since the last collection; with ``sessions_open``,
    nothing is done while ``settle_due`` says the closed pages are not yet worth the pause.
    When no session is open any more (``sessions_open()`` is 0) and no work is waiting,
    the shared results are cut down to ``app.result_cache.IDLE_CACHE_BYTES`` and the
    worker processes are replaced by fresh ones (``WorkPool.recycle_workers``), so the
    server and its workers are back near their size at the start. Returns what was done.
    """
    done = {"idle": False, "recycled": False, "cache_bytes": None, "settled": False}
    still_open = _count(sessions_open) if sessions_open is not None else None
    if closed is not None and still_open is not None and not settle_due(closed, still_open):
        return done
    if still_open == 0:
        from .jobs import work_pool

        pool = work_pool()
        if pool.idle():
            done["idle"] = True
            pool.cache.shrink()
            done["cache_bytes"] = pool.cache.nbytes
            done["recycled"] = pool.recycle_workers()
    settle()  # the closed pages' objects collected (app.heap)
    done["settled"] = True
    try:
        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):  # not glibc
        pass
    return done


def _count(sessions_open) -> int:
    try:
        return int(sessions_open())
    except Exception:  # the server is going away: do nothing more
        return -1


def schedule_release(sessions_open=None) -> None:
    """A session ended: ``release_memory(sessions_open, closed)`` once no session has
    ended for ``RELEASE_DELAY_S`` seconds (``closed``: the sessions ended since the
    last collection). ``sessions_open``: how many sessions the server still has (a
    callable; e.g. ``sessions_of(session_context)``)."""
    global _RELEASE_TIMER, _CLOSED
    with _RELEASE_LOCK:
        _CLOSED += 1
        if _RELEASE_TIMER is not None:
            _RELEASE_TIMER.cancel()
        _RELEASE_TIMER = threading.Timer(RELEASE_DELAY_S, _release_closed, (sessions_open,))
        _RELEASE_TIMER.daemon = True
        _RELEASE_TIMER.start()


def _release_closed(sessions_open) -> dict:
    global _CLOSED
    with _RELEASE_LOCK:
        closed = _CLOSED
    done = release_memory(sessions_open, closed)
    if done["settled"]:
        with _RELEASE_LOCK:
            _CLOSED -= closed  # those ended meanwhile count for the next time
    return done


def sessions_of(session_context):
    """A callable counting the sessions the Bokeh server of ``session_context`` still
    has (for ``schedule_release``); it keeps the server's context only, not the ended
    session's."""
    server = getattr(session_context, "server_context", None)
    if server is None:
        return None
    return lambda: len(list(server.sessions))


_GATE = PageGate()


def page_gate() -> PageGate:
    """The server process's ``PageGate``."""
    return _GATE
