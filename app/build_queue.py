"""Page builds take turns: one build step per turn of the server's event loop.

The server's one event loop answers everything: page requests, the browsers' messages,
Panel's ``/liveness`` probe. A page is built in two steps of ~0.3 s each once a browser
has it (its Python objects, then its models: ``app.opening``). No step is long, but when
several browsers open pages at once, their builds were all ready in the same turn of the
loop and ran back to back: a liveness probe waited behind all of them (1.4-1.9 s for a
burst of 20 worst-case requests with a health check and a visitor, issue 24).

So a build step does not run where it is asked for: ``BuildQueue.enqueue`` puts it in the
process's one queue (``build_queue()``), first in, first out, and a pump on the event loop
hands ONE step to its session (Panel's ``pn.state.execute``: Bokeh's next tick, with the
session's document locked and ``pn.state.curdoc`` set) and is scheduled again only once
that step is done, ``STEP_GAP_S`` later. Between two steps Tornado polls its sockets and
answers what came in meanwhile; a burst of page opens delays a probe by one step, not by
all of them. (The gap: an HTTP request takes Tornado a few turns of the loop -- accept,
read, answer --, and the two or three turns between a step and the next were not enough:
a probe that came during a page's first step was answered only after its second.)

* A step's continuation (``enqueue(..., first=True)``: the page's models after its
  objects) goes to the front: it follows its own first step within a turn or two, as
  before the queue. What the page registered with ``pn.state.onload`` while it was built
  runs at once (the page is loaded by then), e.g. the player's "ready" change, timed to
  reach the browser after the models (``app.figures.player.READY_DELAY_MS``); and a page
  is up as soon as its own build is done, not after every page queued before it.
* The steps of a session that ended meanwhile are dropped; a step that raises is logged
  and the pump goes on (the step shows the page's failure itself: ``FAILED_TEXT``).
* Without a server (no session: tests, a notebook) a step runs at once.
"""
from __future__ import annotations

import logging
from collections import deque
from functools import partial

import panel as pn
from tornado.ioloop import IOLoop

log = logging.getLogger(__name__)

#: Seconds between the end of a step and the next: the loop answers what came in meanwhile
#: (a liveness probe needs well under a millisecond of it once it has its turns).
STEP_GAP_S = 0.01


def _ended(doc) -> bool:
    """Whether ``doc``'s session is gone (Bokeh clears ``session_context`` on destroy)."""
    context = doc.session_context
    return context is None or context.destroyed


class BuildQueue:
    """One FIFO queue of build steps per server process: one step at a time, each in a
    turn of the event loop of its own, ``STEP_GAP_S`` after the last one ended."""

    def __init__(self):
        self._steps: deque = deque()   # (document, step)
        self._armed = False            # a pump is scheduled on the event loop
        self._handed = None            # (token, session id) of the step handed over, not run
        self.ran = self.failed = self.dropped = 0

    def __len__(self) -> int:
        return len(self._steps)

    @property
    def idle(self) -> bool:
        """Nothing queued, scheduled or running."""
        return not self._steps and not self._armed and self._handed is None

    def enqueue(self, step, doc=None, first: bool = False) -> None:
        """Run ``step()`` in ``doc``'s session (default: the current one) on a later turn
        of the event loop, after the steps queued before it (``first``: before them)."""
        doc = pn.state.curdoc if doc is None else doc
        if doc is None or doc.session_context is None:
            step()
            return
        doc.on_session_destroyed(self._session_ended)
        if first:
            self._steps.appendleft((doc, step))
        else:
            self._steps.append((doc, step))
        self._arm()

    def _arm(self, gap: float = 0.0) -> None:
        if not self._armed and self._handed is None and self._steps:
            self._armed = True
            if gap > 0:
                IOLoop.current().call_later(gap, self._pump)
            else:
                IOLoop.current().add_callback(self._pump)

    def _pump(self) -> None:
        """Hand the first step of a live session to its session; reschedule on its end."""
        self._armed = False
        while self._steps and self._handed is None:
            doc, step = self._steps.popleft()
            if _ended(doc):
                self.dropped += 1
                continue
            token = object()
            self._handed = (token, doc.session_context.id)
            try:
                # This callback runs in its own copy of the context (asyncio copies it for
                # each callback): ``execute`` reads the session from it and the step gets it.
                pn.state.curdoc = doc
                pn.state.execute(partial(self._run, token, step), schedule=True)
            except Exception:  # the session ended meanwhile
                log.debug("a build step's session is gone; step dropped", exc_info=True)
                self._handed = None
                self.dropped += 1

    def _run(self, token, step) -> None:
        try:
            step()
            self.ran += 1
        except Exception:
            self.failed += 1
            log.exception("a page build step failed")
        finally:
            if self._handed is not None and self._handed[0] is token:
                self._handed = None
            self._arm(STEP_GAP_S)

    def _session_ended(self, session_context) -> None:
        """A session ended: its steps are dropped as they come up; if Bokeh had its next
        step already (a next tick of a destroyed session never runs), the pump goes on."""
        if self._handed is not None and self._handed[1] == session_context.id:
            self._handed = None
            self.dropped += 1
            self._arm()


_QUEUE = BuildQueue()


def build_queue() -> BuildQueue:
    """The server process's ``BuildQueue``."""
    return _QUEUE
