"""The server's pages: a gate per client on pages built but not yet opened, and the
memory of ended sessions handed back to the system.

Per server process, like the work pool (``app.jobs``): ``page_gate()`` is the one gate.
"""
from __future__ import annotations

import ctypes
import gc
import threading
import time

#: Pages of one client built but not yet opened by a browser (its document_ready) that a
#: new page may join; past it the client gets a short "busy" page instead. A page build
#: holds the server's one event loop for a few tenths of a second, so a burst of page
#: requests that are never opened (a script fetching URLs) would stall every session and
#: the liveness endpoint; two bound that to about a second. A class behind one address
#: (a NAT) opening at once gets some busy pages and reloads them.
MAX_UNOPENED_PAGES = 2
#: Seconds after which a page that was never opened stops counting (a health check's
#: session, a closed tab).
UNOPENED_PAGE_S = 10.0


class PageGate:
    """Per client: the pages built that no browser has opened yet (``admit``, ``opened``).

    A class behind one address opens its pages one after another, each soon after it
    was built, so it stays under the bound; a burst of page requests that are never
    opened does not.
    """

    def __init__(self, max_unopened: int = MAX_UNOPENED_PAGES,
                 window_s: float = UNOPENED_PAGE_S):
        self.max_unopened, self.window_s = max_unopened, window_s
        self._pages: dict = {}  # client -> {page id: monotonic time built}
        self._lock = threading.Lock()

    def admit(self, client, page) -> bool:
        """Whether ``client`` may have one more page built (then ``page`` counts)."""
        now = time.monotonic()
        with self._lock:
            pages = {p: t for p, t in self._pages.get(client, {}).items()
                     if now - t < self.window_s}
            admitted = len(pages) < self.max_unopened
            if admitted:
                pages[page] = now
            if pages:
                self._pages[client] = pages
            else:
                self._pages.pop(client, None)
            return admitted

    def built(self, client, page) -> None:
        """``page`` is built: its time counts from now (a build may take long)."""
        with self._lock:
            pages = self._pages.get(client)
            if pages is not None and page in pages:
                pages[page] = time.monotonic()

    def opened(self, client, page) -> None:
        """A browser has ``page`` (or it is gone): it no longer counts."""
        with self._lock:
            pages = self._pages.get(client)
            if pages is not None:
                pages.pop(page, None)
                if not pages:
                    del self._pages[client]

    def unopened(self, client) -> int:
        now = time.monotonic()
        with self._lock:
            return sum(now - t < self.window_s for t in self._pages.get(client, {}).values())


#: Seconds after the last session ended before its memory is handed back to the system.
RELEASE_DELAY_S = 5.0
_RELEASE_TIMER: threading.Timer | None = None
_RELEASE_LOCK = threading.Lock()


def release_memory() -> None:
    """Collect garbage and hand the heap's free pages back to the system (glibc's
    ``malloc_trim``; elsewhere a no-op): CPython's allocator otherwise keeps the memory
    of ended sessions for reuse, and the server stays at its peak after a class left."""
    gc.collect()
    try:
        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):  # not glibc
        pass


def schedule_release() -> None:
    """``release_memory`` once no session has ended for ``RELEASE_DELAY_S`` seconds."""
    global _RELEASE_TIMER
    with _RELEASE_LOCK:
        if _RELEASE_TIMER is not None:
            _RELEASE_TIMER.cancel()
        _RELEASE_TIMER = threading.Timer(RELEASE_DELAY_S, release_memory)
        _RELEASE_TIMER.daemon = True
        _RELEASE_TIMER.start()


_GATE = PageGate()


def page_gate() -> PageGate:
    """The server process's ``PageGate``."""
    return _GATE
