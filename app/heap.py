"""The server's heap: the objects of open pages kept out of Python's automatic collections.

A page is ~100 000 Python objects (Panel and param objects, Bokeh models, their
properties) that live as long as its session. Python's cyclic garbage collector traverses
every tracked object at each full collection, and one comes each time the heap has grown
by a quarter: while a class opens its pages, each page makes the next full collection
longer. Measured with ``gc.callbacks`` on a 2-core server during
``benchmarks/load_test.py --sessions 30``: 0.4 s with a few pages open, 1.8 s with
thirty, 6 s in all while the pages opened, every one a pause of the event loop that
the pages in flight waited for (``docs/performance-record.md``).

So, with Python's public ``gc.freeze``:

* ``page_built()``: once a page is built and sent, everything alive is frozen (moved to
  the permanent generation, which collections do not traverse): later collections look
  only at what was made since.
* ``session_ended()``: when pages close, their objects must be collectable again (their
  reference cycles are freed only by a collection): ``SETTLE_S`` after the last page
  closed, everything is unfrozen, collected once, and what lives is frozen again. Panel
  already collects after sessions end (the same full collection, debounced 5 s); this
  one takes its place, and Panel's then finds only what was made since.

Without a running event loop (tests, scripts, notebooks) ``session_ended`` settles at once.
"""
from __future__ import annotations

import asyncio
import gc
import logging
import time

log = logging.getLogger(__name__)

#: Seconds after the last page closed before the heap is collected: pages of a class
#: close over some seconds; one collection for all of them.
SETTLE_S = 3.0

_pending: asyncio.TimerHandle | None = None


def page_built() -> None:
    """A page is built and sent: freeze what lives now (``gc.freeze``)."""
    gc.freeze()


def settle() -> float:
    """Unfreeze, collect once (the closed pages' reference cycles), freeze what lives;
    the seconds the collection took."""
    global _pending
    _pending = None
    start = time.perf_counter()
    gc.unfreeze()
    gc.collect()
    gc.freeze()
    took = time.perf_counter() - start
    log.debug("heap settled in %.3f s, %d objects frozen", took, gc.get_freeze_count())
    return took


def session_ended(*_context) -> None:
    """A page closed: settle the heap ``SETTLE_S`` after the last of a run of closes."""
    global _pending
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:  # no event loop: at once
        settle()
        return
    if _pending is not None:
        _pending.cancel()
    _pending = loop.call_later(SETTLE_S, settle)
