"""Pages built one at a time, whole, the first opened first (``PageLane``).

A page's build is a few steps, each one turn of the server's event loop, with other
requests answered in between (``app.opening``). Each step scheduled on a timer of its own,
the steps of pages opened together took turns: with two pages opening, both were complete
only when both were, after about twice one page's build; with a class of thirty arriving
at once, every page came at the end, after thirty builds. In one lane the first page comes
after one build, the next after two: the same total work, and the average visitor waits
about half as long (the last one no longer).

Clients take turns as in the work pool (``app.jobs``): the next page built is the oldest
of the next client in turn (by address), so a client that opens many pages at once does
not hold up another's one. The server process has one lane (``app.opening.LANE``): a step
of the page being built runs ``gap_ms`` after the previous step of any page, on that
page's document (its lock held, as Bokeh runs a session's callbacks; Panel's current
document set to it, ``set_curdoc``). A page whose session
ends leaves the lane; a step that raises ends its page's build (the step itself shows the
visitor what went wrong). A waiting page is told how many pages will be built before it
and about how long that takes (``note``), so a visitor knows the page is coming and does
not reload it (a reloaded page goes to the end of the lane).
"""
from __future__ import annotations

import logging
import statistics
import time
from collections import deque
from typing import Callable, Hashable, Iterator

from panel.io.state import set_curdoc

log = logging.getLogger(__name__)

_DONE = object()


class _Page:
    __slots__ = ("doc", "steps", "client", "note", "told", "started")

    def __init__(self, doc, steps, client, note):
        self.doc, self.steps, self.client, self.note = doc, steps, client, note
        self.told = None      # the number of pages ahead it was last told
        self.started = None   # time.monotonic() when its build started


def _take(waiting: dict, last) -> _Page:
    """Remove from ``waiting`` the page built next and return it: the oldest page of the
    first client in turn other than ``last`` (the client of the page built before), whose
    next page then waits for the client's next turn."""
    client = next((c for c in waiting if c != last), last)
    pages = waiting.pop(client)
    page = pages.popleft()
    if pages:
        waiting[client] = pages
    return page


class PageLane:
    """Builds pages' steps one at a time: a page whole, then the oldest page of the next
    client in turn.

    ``add(doc, steps, client, note)``: each ``next(steps)`` runs one step of the page of
    ``doc`` (a generator that yields between steps); ``client`` is the visitor's address
    (None: one anonymous client); ``note(ahead, seconds)``, if given, is called while the
    page waits, each time the number of pages to be built before it changes, with the
    seconds that will take (from the latest builds; None before any)."""

    #: Builds whose seconds make the waiting pages' estimate (the median of the latest).
    RECENT = 5

    def __init__(self, gap_ms: int):
        self.gap_ms = gap_ms
        #: client -> its pages not started, oldest first; clients in turn, next first.
        self._waiting: dict[Hashable, deque] = {}
        self._current: _Page | None = None  # the page being built
        self._scheduled = False   # whether its next step waits for its timer
        self._last = None         # the client of the page built last
        self._seconds: deque = deque(maxlen=self.RECENT)  # the latest pages' builds

    def __len__(self) -> int:
        return sum(map(len, self._waiting.values())) + (self._current is not None)

    def add(self, doc, steps: Iterator[None], client: Hashable = None,
            note: Callable[[int, float | None], None] | None = None) -> None:
        page = _Page(doc, steps, client, note)
        self._waiting.setdefault(client, deque()).append(page)
        doc.on_session_destroyed(lambda _context: self._leave(page))
        self._next()

    def order(self) -> list:
        """The documents of the pages waiting, in the order they will be built."""
        return [page.doc for page in self._order()]

    def _order(self) -> list[_Page]:
        waiting = {client: deque(pages) for client, pages in self._waiting.items()}
        order = []
        while waiting:
            order.append(_take(waiting, order[-1].client if order else self._last))
        return order

    def _next(self) -> None:
        while not self._scheduled and (self._current is not None or self._waiting):
            if self._current is None:
                self._current = _take(self._waiting, self._last)
                self._last, self._current.started = self._current.client, time.monotonic()
            page = self._current
            try:
                page.doc.add_timeout_callback(lambda: self._step(page), self.gap_ms)
                self._scheduled = True
            except Exception:  # noqa: BLE001 - the session has ended meanwhile
                log.debug("a page left the lane before its next step")
                self._current = None
        self._tell()

    def _step(self, page: _Page) -> None:
        if page is not self._current:  # the page left the lane meanwhile
            return
        self._scheduled = False
        try:
            # On the page's own document: a timer runs in the context it was set in, and a
            # page's next step is set by the step of the page built before it, whose
            # document Panel would otherwise take for the current one (its address, its
            # callbacks: the second of three pages opened together showed the first's θ₀).
            with set_curdoc(page.doc):
                more = next(page.steps, _DONE) is not _DONE
        except Exception:  # noqa: BLE001 - logged; the lane goes on with the next page
            log.exception("a step of a page's build failed")
            more = False
        if not more:
            self._current = None
            self._seconds.append(time.monotonic() - page.started)
        self._next()

    def _tell(self) -> None:
        """Tell each waiting page how many pages will be built before it, and how long
        that should take, when the number has changed."""
        each = statistics.median(self._seconds) if self._seconds else None
        for i, page in enumerate(self._order(), start=self._current is not None):
            if page.note is None or page.told == i:
                continue
            page.told = i
            try:
                page.note(i, None if each is None else i * each)
            except Exception:  # noqa: BLE001 - a note is not worth stopping the lane for
                log.debug("a waiting page could not be told its place", exc_info=True)

    def _leave(self, page: _Page) -> None:
        """The page's session ended: its build stops; if it was being built (a timer of
        a session that ended never fires), the next page's step is scheduled."""
        if page is self._current:
            self._current, self._scheduled = None, False
            self._next()
            return
        pages = self._waiting.get(page.client)
        if pages is not None and page in pages:
            pages.remove(page)
            if not pages:
                del self._waiting[page.client]
            self._tell()
