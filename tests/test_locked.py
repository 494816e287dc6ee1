"""``app.views.locked``: an edit of a figure made from a watcher goes to the figure's own
document, locked, at its next tick -- also when the context names another session's
document (``pn.state.curdoc``), whose next tick never comes once that session closed."""
from __future__ import annotations

from types import SimpleNamespace

from bokeh.document import Document
from bokeh.plotting import figure
from panel.io.state import set_curdoc

from app.views.locked import locked


def _served() -> Document:
    """A document as a server's session has it (Bokeh keeps its session context behind
    a weak reference: a callable)."""
    doc, context = Document(), SimpleNamespace(id="a served session")
    doc._session_context = lambda: context
    return doc


def test_the_edit_waits_for_the_next_tick_of_the_figures_own_document():
    mine, other = _served(), _served()
    fig = figure()
    mine.add_root(fig)
    drawn = []
    with set_curdoc(other):  # a context left naming another session's document
        locked(lambda: drawn.append(fig.title.text), fig)
    assert drawn == []  # not now: at the next tick, locked
    assert len(mine.session_callbacks) == 1 and len(other.session_callbacks) == 0
    next_tick = mine.session_callbacks[0]
    next_tick.callback()
    assert len(drawn) == 1


def test_a_figure_in_no_served_document_is_edited_at_once():
    fig, drawn = figure(), []
    locked(lambda: drawn.append(1), fig)
    Document().add_root(fig)  # a document with no session (a notebook, a saved page)
    locked(lambda: drawn.append(2), fig)
    assert drawn == [1, 2]
