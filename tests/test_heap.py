"""The server's heap (app/heap.py): a built page's objects are frozen out of Python's
automatic collections, and a closed page's reference cycles are still freed once pages
stop closing (``app.pages.release_memory``)."""
from __future__ import annotations

import gc
import weakref

import pytest

from app import heap
from app.pages import release_memory


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
    heap.settle()
    assert ref() is None
    assert gc.get_freeze_count() > 0  # what lives is frozen again


def test_the_memory_released_after_pages_closed_includes_frozen_pages():
    ref = _page_in_a_cycle()
    heap.page_built()
    release_memory(None)
    assert ref() is None
