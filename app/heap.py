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
* ``settle()``: closed pages' objects must be collectable again (their reference cycles
  are freed only by a collection): everything is unfrozen, collected once, and what
  lives is frozen again. The server does it once pages have stopped closing for a few
  seconds and the closed pages are worth the pause (``app.pages.settle_due``: none left
  open, or the closed ones half the open ones; ``app.pages.release_memory``, before it
  hands the freed memory back), in
  place of the full collection it made there before; Panel's own collection after
  sessions end looks only at what was made since the last freeze.
"""
from __future__ import annotations

import gc
import logging
import time

log = logging.getLogger(__name__)


def page_built() -> None:
    """A page is built and sent: freeze what lives now (``gc.freeze``)."""
    gc.freeze()


def settle() -> float:
    """Unfreeze, collect once (the closed pages' reference cycles), freeze what lives;
    the seconds the collection took."""
    start = time.perf_counter()
    gc.unfreeze()
    gc.collect()
    gc.freeze()
    took = time.perf_counter() - start
    log.debug("heap settled in %.3f s, %d objects frozen", took, gc.get_freeze_count())
    return took
