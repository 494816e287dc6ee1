"""Panel: a text pane whose ``visible`` changes after it was sent but before it is drawn
throws in the browser, and the rest of that message is lost.

Panel 1.9.4 (Bokeh 3.9.2). Panel's text views (``PanelMarkupView``: ``Markdown``, ``HTML``,
``Alert``, ...) make their ``container`` element in ``render()``, but their handler of a
change of ``visible`` to True uses it at once. Content sent into a served page in a patch (a page
built once opened, a tab filled later) is built by BokehJS at once and drawn over later
turns -- the views in tabs not on show last -- so a change of ``visible`` arriving in
between throws "Cannot read properties of undefined (reading 'style')". Bokeh's own
``Toggle`` does the same with ``active`` before it is drawn ("... reading 'classList'",
``_update_active``). Expected: a change before the first draw is simply drawn.

Run: ``python docs/upstream/markup_visible_before_drawn.py`` (tries ``ROUNDS`` pages).
NOT REPRODUCED on this project's machines with this script (2026-11-26, Chromium, load
~13 on 2 cores; also with ``pn.extension("mathjax")``): plain Tabs draw their hidden
children at once. The dashboard met it (a ~450-model page sent in a patch, MathJax, a
Card, several Tabs holders filled later) and its browser tests showed the error until the
guard below was installed; the handler that throws is in Panel's bundle
(``PanelMarkupView.connect_signals``: ``this.container.style.visibility`` on ``visible``,
while ``container`` is made in ``render()``). A reproducer still needs the condition that
keeps a built view from being drawn.
Workarounds in this project: ``app/edge.py`` (``MARKUP_GUARD_JS``: the container is a
detached stand-in until drawn) and the player's autoplay retrying until its button is
drawn (``app/figures/player.py``).
"""
import panel as pn

from harness import pages_failing

ROUNDS = 5
NOTES = 100


def page():
    pn.extension("mathjax")  # the text views wait for MathJax before they draw
    shell = pn.Column(pn.pane.Markdown("opening..."))
    doc = pn.state.curdoc
    notes = [pn.pane.Markdown(f"note {i}", visible=False) for i in range(NOTES)]
    tabs = pn.Tabs(("first", pn.pane.Markdown("shown")),
                   *((f"tab {i}", pn.Column(*notes[i::4])) for i in range(4)))

    def flip():  # hidden notes shown (the view's handler touches its container then)
        with pn.io.hold():
            for note in notes:
                note.visible = not note.visible

    def build():
        with pn.io.hold():
            shell.objects = [tabs]
        doc.add_next_tick_callback(flip)  # the next message, right after the content
        for delay in (10, 30, 60, 100, 200, 400):  # and a few more
            pn.state.add_periodic_callback(flip, period=delay, count=1)
    pn.state.onload(lambda: doc.add_next_tick_callback(build))
    return shell


if __name__ == "__main__":
    pages_failing(page, "reading 'style'", ROUNDS)
