"""The server's heap (app/heap.py): a built page's objects are frozen out of Python's
automatic collections, and a closed page's reference cycles are still freed."""
from __future__ import annotations

import asyncio
import gc
import weakref

import pytest

from app import heap


class _Node:
    """A Python object of a page (tracked by the collector)."""


def _page_in_a_cycle():
    """A page's objects held only by a reference cycle: a weak reference to one."""
    a, b = _Node(), _Node()
    a.other, b.other = b, a
    return weakref.ref(a)


@pytest.fixture(autouse=True)
def _thawed():
    gc.collect()
    gc.unfreeze()
    yield
    gc.unfreeze()


def test_a_built_page_is_left_out_of_the_automatic_collections():
    page = [_Node() for _ in range(1000)]
    before = gc.get_freeze_count()
    heap.page_built()
    assert gc.get_freeze_count() >= before + len(page)
    assert not any(o is page[0] for o in gc.get_objects(generation=2))  # never traversed


def test_a_closed_pages_cycles_are_freed_though_they_were_frozen():
    ref = _page_in_a_cycle()
    heap.page_built()
    gc.collect()
    assert ref() is not None  # frozen: no collection alone frees it
    heap.session_ended()  # no event loop here: the heap settles at once
    assert ref() is None
    assert gc.get_freeze_count() > 0  # what lives is frozen again


def test_closes_in_a_run_settle_the_heap_once_after_the_last(monkeypatch):
    monkeypatch.setattr(heap, "SETTLE_S", 0.05)
    settled = []
    real = heap.settle
    monkeypatch.setattr(heap, "settle", lambda: settled.append(real()))

    async def run():
        ref = _page_in_a_cycle()
        heap.page_built()
        for _ in range(3):  # a class leaving
            heap.session_ended()
            await asyncio.sleep(0.01)
        assert ref() is not None and settled == []  # not while pages still close
        await asyncio.sleep(0.2)
        assert ref() is None
    asyncio.run(run())
    assert len(settled) == 1
