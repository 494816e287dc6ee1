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


def test_the_closed_pages_are_collected_once_they_are_worth_the_pause():
    """A collection pauses every page still open: with others open it waits until the
    closed pages are ``SETTLE_FRACTION`` of them; with none open it is made at once."""
    from app.pages import settle_due

    assert not settle_due(1, 29, fraction=0.5)  # one leaves a class of thirty
    assert settle_due(15, 29, fraction=0.5)  # half of them have gone
    assert settle_due(1, 0, fraction=0.5)  # the last one left: no one is paused
    assert settle_due(1, 29, fraction=0.0)  # the setting 0: at every departure
    assert settle_due(1, 1, fraction=0.5) and not settle_due(1, 3, fraction=0.5)


def test_a_departure_among_many_open_pages_defers_the_collection(monkeypatch):
    monkeypatch.setattr("app.pages.SETTLE_FRACTION", 0.5)
    ref = _page_in_a_cycle()
    heap.page_built()
    done = release_memory(lambda: 29, closed=1)
    assert not done["settled"] and ref() is not None  # the 29 pages are not paused
    done = release_memory(lambda: 29, closed=15)
    assert done["settled"] and ref() is None


@pytest.mark.parametrize("text", ["x", "-1", "inf", "nan", ""])
def test_a_bad_settle_fraction_names_the_setting_and_the_fix(text):
    from app.pages import settle_fraction

    with pytest.raises(ValueError, match=r"MICROPILLAR_SETTLE_FRACTION=.*give a number >= 0"):
        settle_fraction(text)
    assert settle_fraction(None) == 0.5 and settle_fraction("0") == 0.0


def test_departures_are_counted_until_their_pages_are_collected(monkeypatch):
    """``schedule_release`` counts the sessions ended; the collection, when due, is given
    them all and the count starts again; deferred, they keep counting."""
    from app import pages

    calls, timers = [], []

    class Timer:  # what threading.Timer would run after the delay, run by the test
        def __init__(self, _delay, fn, args):
            self.fn, self.args = fn, args
            self.daemon = False
            timers.append(self)

        def start(self):
            pass

        def cancel(self):
            pass

    def depart():
        pages.schedule_release(lambda: 4)
        (timer,) = timers
        timers.clear()
        calls.append(timer.fn(*timer.args))

    monkeypatch.setattr(pages.threading, "Timer", Timer)
    monkeypatch.setattr(pages, "_CLOSED", 0)
    monkeypatch.setattr(pages, "_RELEASE_TIMER", None)
    monkeypatch.setattr(pages, "SETTLE_FRACTION", 0.5)
    depart()
    depart()
    assert [c["settled"] for c in calls] == [False, True]  # 1 < 2, then 2 >= 0.5 * 4
    assert pages._CLOSED == 0
    depart()
    assert not calls[-1]["settled"] and pages._CLOSED == 1
