"""``app.views.at_once``: a slider moved in the browser reaches the session's state as the
browser's message is applied, not when Panel hands the change on 50 ms later."""
from __future__ import annotations

import logging
import math

import panel as pn
import pytest
from bokeh.document import Document
from bokeh.models import Slider
from panel.io.state import set_curdoc


def _served_page(pool):
    """The dashboard's models in a served session's document, with ``Dashboard.sent``
    called as the page's build does once its models are on their way."""
    from app.state import ExplorerState
    from app.views import Dashboard
    from fakes import served_document

    doc = served_document()
    with set_curdoc(doc):
        page = Dashboard(ExplorerState())
        doc.add_root(pn.panel(page).get_root(doc))
        page.sent(doc)
    return doc, page


def _slider(doc, css: str) -> Slider:
    [model] = [m for m in doc.select({"type": Slider}) if css in m.css_classes]
    return model


def _from_browser(doc, model, value, end: bool = True) -> None:
    """What Bokeh's server does with the browser's message moving ``model``: a key press or
    a drag's end sets ``value`` and ``value_throttled`` (BokehJS), a drag's position
    (``end=False``) ``value`` alone."""
    setter = object()
    with set_curdoc(doc):
        model.set_from_json("value", value, setter=setter)
        if end:
            model.set_from_json("value_throttled", value, setter=setter)


def _panels_delivery(doc) -> None:
    """Run what Panel scheduled for the changes from the browser (its 50 ms timer)."""
    import asyncio
    import inspect

    for callback in list(doc.session_callbacks):
        if getattr(callback, "timeout", None):
            doc.remove_timeout_callback(callback)
            with set_curdoc(doc):
                result = callback.callback()
                if inspect.isawaitable(result):
                    asyncio.run(result)


def test_a_slider_moved_in_the_browser_changes_the_state_at_once(pool):
    doc, page = _served_page(pool)
    assert page.state.theta0 != 42
    _from_browser(doc, _slider(doc, "ctl-theta0"), 42.0)
    assert page.state.theta0 == 42  # now, not after Panel's delivery (a timer, not run here)
    assert page.controls.theta0.value == 42


def test_a_drag_goes_panels_way_and_its_end_is_taken_at_once(pool):
    """A drag's positions are merged by Panel as before (no update added); its end (the
    release) is taken at once."""
    doc, page = _served_page(pool)
    model = _slider(doc, "ctl-theta0")
    start = page.state.theta0
    for position in (40.0, 41.0, 42.0):
        _from_browser(doc, model, position, end=False)
    assert page.state.theta0 == start  # the positions wait for Panel, merged
    _from_browser(doc, model, 43.0)  # released there
    assert page.state.theta0 == 43
    _panels_delivery(doc)
    assert page.state.theta0 == 43 and page.controls.theta0.value == 43


def test_presses_sooner_than_merge_ms_go_panels_way_and_the_last_arrives(pool):
    """A key held down: the first press at once, the next ones (within ``MERGE_MS``)
    merged by Panel, so the server updates no more often than before."""
    doc, page = _served_page(pool)
    model = _slider(doc, "ctl-theta0")
    for position in (40.0, 41.0, 42.0):  # within microseconds of one another
        _from_browser(doc, model, position)
    assert page.state.theta0 == 40
    _panels_delivery(doc)
    assert page.state.theta0 == 42  # the last press, not an earlier one


def test_a_log_slider_sets_its_quantity(pool):
    doc, page = _served_page(pool)
    _from_browser(doc, _slider(doc, "ctl-k_r"), math.log10(0.5))
    assert page.state.k_r == pytest.approx(0.5)
    assert page.controls.k_r.widget.value == pytest.approx(math.log10(0.5))


def test_every_physics_slider_is_found(pool):
    from app.views.at_once import answer_at_once

    doc, page = _served_page(pool)
    assert answer_at_once(doc, page.controls.sliders) == 4
    assert answer_at_once(Document(), page.controls.sliders) == 0  # not in that document


def test_a_value_the_widget_refuses_leaves_the_state_and_says_so(pool, caplog):
    doc, page = _served_page(pool)
    before = page.state.theta0
    with caplog.at_level(logging.WARNING, logger="app.views.at_once"):
        _from_browser(doc, _slider(doc, "ctl-theta0"), 1e6)  # beyond the slider's 359°
    assert page.state.theta0 == before
    assert "ctl-theta0" in caplog.text and "1000000" in caplog.text


def test_canary_panel_hands_a_browser_change_on_50_ms_late():
    """The wait this module removes (``docs/upstream/widget_change_debounce.py``): the day
    Panel hands a browser's change to its widget at once, ``app.views.at_once`` can go."""
    import runpy
    from pathlib import Path

    script = Path(__file__).parents[1] / "docs" / "upstream" / "widget_change_debounce.py"
    assert runpy.run_path(str(script))["main"]() is True
