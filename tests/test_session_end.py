"""Sessions that end mid-computation (the browser went away): the destroyed session's
waiting job never starts, its queued work is cancelled, a late result is dropped and the
result slot lets go of the session's document; a debounced result is marked busy from the
control change on. (Other faults: tests/test_faults.py.)
"""
from __future__ import annotations

import asyncio
import concurrent.futures as cf
import gc
import time
import weakref

import pytest

from app import slot as slots
from app.slot import Request, Slot

# ---------------------------------------------------------------------- (b) sessions that end

class SessionDoc:
    """What a ``Slot`` uses of a Bokeh server session's ``Document``, on an asyncio
    loop; ``destroy()`` does what Bokeh does when it discards the session (the browser
    went away): it runs the ``on_session_destroyed`` callbacks once and forgets them.
    Any use after that is recorded in ``used_after_destroy``."""

    def __init__(self, name: str):
        from bokeh.document import Document

        self.name = name
        self.session_context = object()
        self.destroyed = False
        self.used_after_destroy: list[str] = []
        self._bokeh = Document()  # registers (and checks) the destroy callbacks

    def _use(self, what: str) -> None:
        if self.destroyed:
            self.used_after_destroy.append(what)

    def add_next_tick_callback(self, callback):
        self._use("add_next_tick_callback")
        asyncio.get_running_loop().call_soon(callback)

    def add_timeout_callback(self, callback, timeout_ms):
        self._use("add_timeout_callback")
        asyncio.get_running_loop().call_later(timeout_ms / 1000, callback)

    def on_session_destroyed(self, *callbacks):
        self._bokeh.on_session_destroyed(*callbacks)

    @property
    def callbacks(self):
        return self._bokeh.callbacks

    def hold(self, policy="combine"):
        self._use("hold")
        self._bokeh.hold(policy)

    def unhold(self):
        self._bokeh.unhold()

    def destroy(self) -> None:
        """As bokeh.application.handlers.document_lifecycle does."""
        self.destroyed = True
        callbacks = self._bokeh.session_destroyed_callbacks
        self._bokeh.session_destroyed_callbacks = set()
        for callback in callbacks:
            callback(self.session_context)


def test_the_fake_session_document_matches_bokeh():
    from bokeh.document import Document

    real = Document()
    for name in ("add_next_tick_callback", "add_timeout_callback", "on_session_destroyed",
                 "session_context", "session_destroyed_callbacks", "callbacks", "hold",
                 "unhold"):
        assert hasattr(real, name), name
    assert hasattr(real.callbacks, "hold_value")


async def _until(predicate, timeout_s: float = 30.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "timed out"
        await asyncio.sleep(0.02)


@pytest.fixture
def own_worker():
    """A worker process of its own, shut down after."""
    pool = cf.ProcessPoolExecutor(max_workers=1)
    pool.submit(abs, -1).result(timeout=120)  # started and warm
    yield pool
    pool.shutdown(wait=True, cancel_futures=True)


class Owner:
    """What a ``Slot`` uses of its ``SessionResults``."""

    LABELS = {}
    session_id = 0

    def __init__(self):
        self.errors, self.busy = {}, set()

    def _set_error(self, name, message):
        self.errors[name] = message

    def _set_busy(self, name, flag):
        (self.busy.add if flag else self.busy.discard)(name)


class Direct:
    """A work pool that calls the job's function, which returns the future itself."""

    def submit(self, lane, key, fn, *args, **options):
        return fn(*args)


def _slot(applied: list, tag: str):
    """A slot whose requests come from ``made.next`` (a callable returning a future)."""
    made = Slot(Owner(), tag, make=lambda: Request("any", None, made.next),
                apply=applied.append)
    return made


def test_a_destroyed_session_frees_its_work(monkeypatch, own_worker):
    """Session A asks for a long run and, while it runs, for another one; then its browser
    goes away. Session B's request must not wait for A's second run (never started), A's
    result must not be applied, and nothing may keep A's document alive."""
    current = {}
    monkeypatch.setattr(slots, "_session_doc", lambda: current.get("doc"))
    monkeypatch.setattr(slots, "work_pool", Direct)
    pool = own_worker
    started, applied = [], {"A": [], "B": []}

    def job(tag: str, seconds: float):
        def start():
            started.append(tag)
            return pool.submit(time.sleep, seconds)
        return start

    async def scenario():
        doc_a = SessionDoc("A")
        current["doc"] = doc_a
        a = _slot(applied["A"], "A")
        a.next = job("A1", 1.5)
        a.request()
        await asyncio.sleep(0.3)  # A1 runs in the worker
        a.next = job("A2", 1.5)
        a.request()  # waits for A1 (newest wins)
        assert started == ["A1"]
        doc_a.destroy()
        a.next = job("A3", 0.0)
        a.request()  # a late event of the ended session starts nothing

        doc_b = SessionDoc("B")
        current["doc"] = doc_b
        b = _slot(applied["B"], "B")
        b.next = job("B1", 0.0)
        b.request()
        await _until(lambda: applied["B"])
        await _until(lambda: not a._running)  # A1 has finished; A's slot is idle
        await asyncio.sleep(0.2)
        assert started == ["A1", "B1"]  # A2 was dropped with its session
        assert applied["A"] == [] and applied["B"] == [None]
        assert b.owner.errors == {"B": ""}
        assert doc_a.used_after_destroy == [] and not doc_b.destroyed
        return weakref.ref(doc_a), a

    doc_ref, slot = asyncio.run(scenario())
    current.clear()
    gc.collect()
    assert doc_ref() is None  # the slot keeps no reference to the ended session


def test_a_destroyed_session_cancels_its_queued_work(monkeypatch):
    """Work still waiting in a queue (behind other sessions' work) is cancelled, so the
    worker never runs it; a delayed request is never sent."""
    current = {}
    monkeypatch.setattr(slots, "_session_doc", lambda: current.get("doc"))
    monkeypatch.setattr(slots, "work_pool", Direct)
    queued = cf.Future()  # as returned by a pool whose workers are busy elsewhere
    started = []

    async def scenario():
        doc = SessionDoc("A")
        current["doc"] = doc
        slot = Slot(Owner(), "A", make=lambda: Request("any", None, lambda: queued),
                    apply=lambda value: pytest.fail("applied after the end"))
        slot.request()
        later = Slot(Owner(), "L", make=lambda: Request(
            "any", None, lambda: started.append("later") or cf.Future()),
            apply=lambda value: pytest.fail("applied after the end"), delay_ms=50)
        later.request()
        await asyncio.sleep(0)
        doc.destroy()
        await asyncio.sleep(0.2)
        assert queued.cancelled()
        assert started == [] and doc.used_after_destroy == []
        await _until(lambda: not slot._running, 5.0)

    asyncio.run(scenario())


def test_a_delayed_request_marks_its_result_busy_at_once(monkeypatch):
    """A debounced result (the uniform array, the design's array) is stale from the
    control change on: its busy marker (the page's "Updating…") is set when the change
    comes, not when the delay ends, and cleared when a change leaves nothing to compute."""
    current = {}
    monkeypatch.setattr(slots, "_session_doc", lambda: current.get("doc"))
    monkeypatch.setattr(slots, "work_pool", Direct)
    applied, plan = [], {"next": "job"}

    def make():
        if plan["next"] is None:
            return None  # e.g. an unusable design: nothing to compute
        done = cf.Future()
        done.set_result(plan["next"])
        return Request("any", None, lambda: done)

    async def scenario():
        current["doc"] = SessionDoc("A")
        slot = Slot(Owner(), "D", make=make, apply=applied.append, delay_ms=300)
        slot.request()
        assert slot.owner.busy == {"D"}  # before the delay is over
        await _until(lambda: applied == ["job"])
        await _until(lambda: not slot.owner.busy, 5.0)
        plan["next"] = "second"
        slot.request()
        assert slot.owner.busy == {"D"}
        plan["next"] = None
        slot.request()  # the second request is dropped with its marker
        assert slot.owner.busy == set()
        await asyncio.sleep(0.5)
        assert applied == ["job"] and slot.owner.busy == set()

    asyncio.run(scenario())


def test_a_slot_keeps_to_its_own_session_when_the_context_names_another(monkeypatch):
    """A request made while the context names another session's document (a callback
    scheduled while that session was current can leave it so) is scheduled on the slot's
    own session, and that other session's end does not end this slot."""
    current = {}
    monkeypatch.setattr(slots, "_session_doc", lambda: current.get("doc"))
    mine, other = SessionDoc("mine"), SessionDoc("other")
    scheduled = {"mine": 0, "other": 0}
    for doc in (mine, other):
        doc.add_timeout_callback = (
            lambda name: lambda callback, ms: scheduled.__setitem__(name, scheduled[name] + 1)
        )(doc.name)
    made = Slot(Owner(), "support", make=lambda: Request("any", None, abs), apply=[].append,
                delay_ms=100)
    current["doc"] = mine
    made.request()
    current["doc"] = other
    made.request()
    assert scheduled == {"mine": 2, "other": 0}
    other.destroy()
    assert not made.closed
    mine.destroy()
    assert made.closed
