"""Panel: a message held back by ``pn.io.hold`` is overtaken by a later change sent through
Bokeh's own path, and the page meets a model it does not have yet (or keeps an older value).

Panel 1.9.4 (Bokeh 3.9.2). When ``pn.io.hold`` (Panel's ``unlocked``) ends while Bokeh is
writing another message on the session's websocket (its write lock taken: an ``OK`` reply
to one of the many messages a page sends as it lays itself out), Panel serialises its
changes at once but writes them later, polling every 10 ms for the lock. A change made
after it outside Panel's hold -- to a plain Bokeh model, from a Bokeh timeout callback --
is queued on the lock by Bokeh and usually written first. Its message names the new models
only by reference (the held message, serialised first, defines them), so BokehJS stops
with "reference p1047 isn't known" and drops the change; the same inversion between two
changes of one property leaves the page with the older value ("a hold that loses the last
update"). Expected: the messages of a document leave in the order they were made.

Seen in this project's dashboard (a page of ~450 models sent under a hold once opened; a
player's ``tags`` changed from a timeout 300 ms later): the browser received message p1585
before p1570 and logged "reference p1047 isn't known". The race needs Bokeh to be writing
at that moment; this script tries it on ``ROUNDS`` pages and counts the pages that fail.

Run: ``python docs/upstream/hold_overtakes_changes.py``.
Workaround in this project: every change a server callback makes goes through Panel's
hold, so Panel's own queue keeps the order (``app/slot.py``: results applied under
``pn.io.hold``; ``app/opening.py``: what answers a browser event is held while Panel is
busy with it; timed changes through ``pn.state.add_periodic_callback``, which Panel marks
busy).
"""
import numpy as np
import panel as pn
from bokeh.plotting import figure

from harness import pages_failing

ROUNDS = 6


def page():
    shell = pn.Column(pn.pane.Markdown("opening..."))
    doc = pn.state.curdoc

    def build():
        figures = []
        for i in range(30):
            fig = figure(width=200, height=150, title=f"figure {i}")
            fig.line(np.arange(200), np.random.rand(200))
            figures.append(fig)
        with pn.io.hold():  # as Panel itself does for any change of a served page
            shell.objects = [pn.FlexBox(*[pn.pane.Bokeh(f) for f in figures])]

        def later():  # a plain Bokeh model of the new content, outside Panel's hold
            figures[-1].tags = ["ready"]
        doc.add_timeout_callback(later, 0)
    pn.state.onload(lambda: doc.add_next_tick_callback(build))
    return shell


if __name__ == "__main__":
    pages_failing(page, "isn't known", ROUNDS)
