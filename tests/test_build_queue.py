"""``app.build_queue``: page build steps of several sessions run one per turn of the event
loop, in order, and what else comes in meanwhile (a liveness probe) runs between them."""
import asyncio
import logging
import time

from tornado.ioloop import IOLoop

from app.build_queue import BuildQueue


class _Context:
    def __init__(self, name):
        self.id, self.destroyed = name, False


class _Session:
    """What the queue uses of a served document: its session context, Bokeh's next tick (a
    callback on the event loop) and the session-ended hook. ``drop_ticks``: a session whose
    next ticks never run (Bokeh drops them once the session is destroyed)."""

    def __init__(self, name, drop_ticks=False):
        self.session_context, self.drop_ticks, self.ended = _Context(name), drop_ticks, set()

    def add_next_tick_callback(self, callback):
        if not self.drop_ticks:
            IOLoop.current().add_callback(callback)

    def on_session_destroyed(self, callback):
        self.ended.add(callback)

    def end(self):
        context, self.session_context = self.session_context, None
        context.destroyed = True
        for callback in self.ended:
            callback(context)


async def _turns_until_idle(queue, turns, limit_s=5.0):
    """Count the loop's turns until ``queue`` is idle."""
    deadline = time.monotonic() + limit_s
    while time.monotonic() < deadline:
        turns[0] += 1
        await asyncio.sleep(0)  # one turn of the loop
        if queue.idle:
            return
    raise AssertionError(f"the queue never drained: {len(queue)} steps left")


def _probe(probe, ran, turns_left=5):
    """A liveness request: Tornado answers it over a few turns of the loop (accept, read,
    answer); ``probe`` gets the number of build steps run when it is answered."""
    if turns_left:
        IOLoop.current().add_callback(_probe, probe, ran, turns_left - 1)
    else:
        probe.append(len(ran))


def test_steps_of_several_sessions_take_turns_and_a_probe_runs_between_them(caplog):
    queue, ran, turns, probe = BuildQueue(), [], [0], []
    sessions = [_Session(name) for name in "abc"]

    def step(name):
        def run():
            ran.append((name, turns[0]))
            if name == "a1":  # a liveness probe arrives while the first page is built
                IOLoop.current().add_callback(_probe, probe, ran)
            if name == "b1":
                raise RuntimeError("broken page")
        return run

    def build(session):
        name = session.session_context.id
        step(f"{name}1")()
        # The page's models: the continuation goes before the other sessions' steps.
        queue.enqueue(step(f"{name}2"), session, first=True)

    async def main():
        for session in sessions:  # three pages opened in the same turn
            queue.enqueue(lambda s=session: build(s), session)
        await _turns_until_idle(queue, turns)

    with caplog.at_level(logging.ERROR, logger="app.build_queue"):
        asyncio.run(main())
    seen = [turn for _, turn in ran]
    assert all(t0 < t1 for t0, t1 in zip(seen, seen[1:])), f"two steps in one turn: {ran}"
    # The probe waits for the step that was running when it came, not for the others.
    assert probe == [1], f"the probe waited for {probe} of {len(ran)} steps"
    assert [name for name, _ in ran] == ["a1", "a2", "b1", "c1", "c2"]  # b2: b1 raised
    assert "a page build step failed" in caplog.text and "broken page" in caplog.text
    assert (queue.ran, queue.failed, queue.dropped) == (4, 1, 0)


def test_steps_run_first_in_first_out():
    queue, ran = BuildQueue(), []
    sessions = [_Session(name) for name in "abcd"]

    async def main():
        for session in sessions:
            queue.enqueue(lambda s=session: ran.append(s.session_context.id), session)
        await _turns_until_idle(queue, [0])

    asyncio.run(main())
    assert ran == list("abcd")


def test_the_steps_of_an_ended_session_are_dropped_and_the_pump_goes_on():
    queue, ran = BuildQueue(), []
    # "b" ends after its step was handed to its session: Bokeh never runs it.
    a, b, c = _Session("a"), _Session("b", drop_ticks=True), _Session("c")

    async def main():
        queue.enqueue(lambda: ran.append("a"), a)
        queue.enqueue(lambda: ran.append("b"), b)
        queue.enqueue(lambda: ran.append("c"), c)
        queue.enqueue(lambda: ran.append("a again"), a)
        deadline = time.monotonic() + 5
        while len(queue) > 2 and time.monotonic() < deadline:  # until "b" is handed over
            await asyncio.sleep(0.001)
        assert ran == ["a"] and len(queue) == 2
        a.end()  # its second step is still queued
        b.end()
        await _turns_until_idle(queue, [0])

    asyncio.run(main())
    assert ran == ["a", "c"]
    assert queue.dropped == 2


def test_without_a_server_a_step_runs_at_once():
    ran = []
    BuildQueue().enqueue(lambda: ran.append(1))
    assert ran == [1]
