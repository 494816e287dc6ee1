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
page's document (its lock held, as Bokeh runs a session's callbacks). A page whose session
ends leaves the lane; a step that raises ends its page's build (the step itself shows the
visitor what went wrong).
"""
from __future__ import annotations

import logging
from collections import deque
from typing import Hashable, Iterator

log = logging.getLogger(__name__)

_DONE = object()


class PageLane:
    """Builds pages' steps one at a time: a page whole, then the oldest page of the next
    client in turn.

    ``add(doc, steps, client)``: each ``next(steps)`` runs one step of the page of
    ``doc`` (a generator that yields between steps); ``client`` is the visitor's address
    (None: one anonymous client)."""

    def __init__(self, gap_ms: int):
        self.gap_ms = gap_ms
        #: client -> its pages not started, oldest first; clients in turn, next first.
        self._waiting: dict[Hashable, deque] = {}
        self._current = None      # [doc, steps, client] of the page being built
        self._scheduled = False   # whether its next step waits for its timer
        self._last = None         # the client of the page built last

    def __len__(self) -> int:
        return sum(map(len, self._waiting.values())) + (self._current is not None)

    def add(self, doc, steps: Iterator[None], client: Hashable = None) -> None:
        entry = [doc, steps, client]
        self._waiting.setdefault(client, deque()).append(entry)
        doc.on_session_destroyed(lambda _context: self._leave(entry))
        self._next()

    def _next(self) -> None:
        while not self._scheduled and (self._current is not None or self._waiting):
            if self._current is None:
                client = next((c for c in self._waiting if c != self._last), self._last)
                self._last = client
                pages = self._waiting.pop(client)
                self._current = pages.popleft()
                if pages:  # the client's next page waits for its next turn
                    self._waiting[client] = pages
            entry = self._current
            try:
                entry[0].add_timeout_callback(lambda: self._step(entry), self.gap_ms)
                self._scheduled = True
            except Exception:  # noqa: BLE001 - the session has ended meanwhile
                log.debug("a page left the lane before its next step")
                self._current = None

    def _step(self, entry) -> None:
        if entry is not self._current:  # the page left the lane meanwhile
            return
        self._scheduled = False
        try:
            more = next(entry[1], _DONE) is not _DONE
        except Exception:  # noqa: BLE001 - logged; the lane goes on with the next page
            log.exception("a step of a page's build failed")
            more = False
        if not more:
            self._current = None
        self._next()

    def _leave(self, entry) -> None:
        """The page's session ended: its build stops; if it was being built (a timer of
        a session that ended never fires), the next page's step is scheduled."""
        if entry is self._current:
            self._current, self._scheduled = None, False
            self._next()
            return
        pages = self._waiting.get(entry[2])
        if pages is not None and entry in pages:
            pages.remove(entry)
            if not pages:
                del self._waiting[entry[2]]
