"""``app.page_lane``: pages opened together are built one after another, the first opened
first, clients in turn; a page whose visitor left, or whose step failed, does not hold up
the next. (Seen
from a browser stand-in on the served app: tests/test_serving.py.)"""
from __future__ import annotations

import contextvars
import logging

from app.page_lane import PageLane


class Loop:
    """Timers of the pages' documents, run in the order they are due (as Tornado does)."""

    def __init__(self):
        self.now, self.timers, self.log = 0.0, [], []

    def run(self, timers: int | None = None) -> None:
        """Run ``timers`` timers, or all until none is left."""
        for _ in range(timers or 100):
            live = [t for t in self.timers if not t[2].destroyed]
            if not live:
                return
            due = min(live, key=lambda t: t[0])
            self.timers.remove(due)
            self.now = due[0]
            due[3].run(due[1])
        assert timers, "the lane never ran dry"


class Doc:
    """What the lane uses of a page's document; a destroyed document's timers never fire
    (Bokeh drops a session's callbacks with it)."""

    def __init__(self, loop: Loop, name: str):
        self.loop, self.name, self.destroyed, self._on_destroyed = loop, name, False, []

    def add_timeout_callback(self, callback, ms: int) -> None:
        if self.destroyed:
            raise RuntimeError("session destroyed")
        # As asyncio does, the callback runs in the context the timer was set in.
        self.loop.timers.append((self.loop.now + ms / 1e3, callback, self,
                                 contextvars.copy_context()))

    def on_session_destroyed(self, callback) -> None:
        self._on_destroyed.append(callback)

    def destroy(self) -> None:
        self.destroyed = True
        for callback in self._on_destroyed:
            callback(None)


def steps(doc: Doc, n: int = 3, fail_at: int | None = None):
    for i in range(1, n + 1):
        if i == fail_at:
            raise RuntimeError(f"{doc.name} step {i} broke")
        doc.loop.log.append(f"{doc.name}{i}")
        if i < n:
            yield


def test_pages_opened_together_are_built_one_after_another_oldest_first():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b, c = (Doc(loop, n) for n in "ABC")
    lane.add(a, steps(a))
    lane.add(b, steps(b))
    loop.run(timers=2)  # A's first two steps; C opens meanwhile
    lane.add(c, steps(c, n=2))
    loop.run()
    assert loop.log == ["A1", "A2", "A3", "B1", "B2", "B3", "C1", "C2"]
    assert len(lane) == 0
    assert round(loop.now, 6) == 0.08  # one gap before each step, none wasted


def test_each_step_runs_on_its_own_page_s_document():
    """A page's steps read Panel's current document (the session's address, where its
    callbacks go). Each page joins the lane from its own ``onload`` (Panel's current
    document set to it), but a waiting page's step is set by the step of the page before
    it: it must still run on its own document."""
    import panel as pn
    from panel.io.state import set_curdoc

    loop, lane = Loop(), PageLane(gap_ms=10)
    seen = []

    def recording(doc):
        for _ in range(2):
            seen.append((doc.name, getattr(pn.state.curdoc, "name", None)))
            yield
    a, b, c = (Doc(loop, n) for n in "ABC")
    for doc in (a, b, c):
        with set_curdoc(doc):
            lane.add(doc, recording(doc))
    loop.run()
    assert seen and all(page == current for page, current in seen), seen


def test_clients_take_turns_a_client_opening_many_pages_does_not_hold_up_another():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    x1, x2, x3, y1 = (Doc(loop, n) for n in ("X", "x", "z", "Y"))
    for doc in (x1, x2, x3):
        lane.add(doc, steps(doc, n=2), client="10.0.0.1")
    lane.add(y1, steps(y1, n=2), client="10.0.0.2")
    assert len(lane) == 4
    loop.run()
    assert loop.log == ["X1", "X2", "Y1", "Y2", "x1", "x2", "z1", "z2"]
    assert len(lane) == 0


def test_a_page_whose_visitor_left_does_not_hold_up_the_next():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b = Doc(loop, "A"), Doc(loop, "B")
    lane.add(a, steps(a))
    lane.add(b, steps(b))
    loop.run(timers=1)
    a.destroy()  # A's next step was waiting on its timer, which now never fires
    loop.run()
    assert loop.log == ["A1", "B1", "B2", "B3"]
    assert len(lane) == 0


def test_a_page_left_while_waiting_in_the_lane_is_never_built():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b, c = (Doc(loop, n) for n in "ABC")
    for doc in (a, b, c):
        lane.add(doc, steps(doc, n=2))
    b.destroy()
    loop.run()
    assert loop.log == ["A1", "A2", "C1", "C2"]


def test_a_failed_step_ends_its_page_and_the_lane_goes_on(caplog):
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b = Doc(loop, "A"), Doc(loop, "B")
    lane.add(a, steps(a, fail_at=2))
    lane.add(b, steps(b, n=1))
    with caplog.at_level(logging.ERROR, logger="app.page_lane"):
        loop.run()
    assert loop.log == ["A1", "B1"]
    assert "A step 2 broke" in caplog.text
    assert len(lane) == 0


def test_a_page_already_ended_when_its_step_is_due_is_skipped():
    """``add_timeout_callback`` on a session that ended raises: the lane moves on."""
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b = Doc(loop, "A"), Doc(loop, "B")
    a.destroyed = True  # ended before any callback of the lane was told
    lane.add(a, steps(a))
    lane.add(b, steps(b, n=1))
    loop.run()
    assert loop.log == ["B1"]
    assert len(lane) == 0


def test_a_waiting_page_is_told_how_many_pages_come_first_and_about_how_long():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b, c = (Doc(loop, n) for n in "ABC")
    told = {"A": [], "B": [], "C": []}
    for doc in (a, b, c):
        lane.add(doc, steps(doc, n=2), note=lambda ahead, s, n=doc.name: told[n].append((ahead, s)))
    assert told["A"] == []  # built at once: nothing to wait for
    assert told["B"] == [(1, None)] and told["C"] == [(2, None)]  # no build timed yet
    loop.run()
    assert [ahead for ahead, _ in told["C"]] == [2, 1]  # told again only when it changed
    ahead, seconds = told["C"][1]
    assert seconds is not None and seconds > 0  # one page ahead: one build's time
    assert told["B"] == [(1, None)]
    assert loop.log == ["A1", "A2", "B1", "B2", "C1", "C2"]


def test_the_order_told_is_the_order_built():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    docs = [Doc(loop, n) for n in ("P", "Q", "R", "S", "T")]
    clients = ["x", "x", "x", "y", "z"]
    for doc, client in zip(docs, clients):
        lane.add(doc, steps(doc, n=1), client=client)
    told = [d.name for d in lane.order()]
    loop.run()
    assert ["P"] + told == [name[0] for name in loop.log]
    assert told == ["S", "Q", "T", "R"]  # clients in turn: y, then x again, z, x


def test_a_page_leaving_the_lane_moves_the_ones_behind_it_up():
    loop = Loop()
    lane = PageLane(gap_ms=10)
    a, b, c = (Doc(loop, n) for n in "ABC")
    told = []
    lane.add(a, steps(a))
    lane.add(b, steps(b))
    lane.add(c, steps(c), note=lambda ahead, s: told.append(ahead))
    b.destroy()
    assert told == [2, 1]
