"""A control moved in the browser reaches the session as its message arrives.

Panel hands a change made in the browser to its widget 50 ms after the message arrived
(Panel 1.9's debounce of browser changes, ``docs/upstream/widget_change_debounce.py``),
so each key press on a slider waited 50 ms before its computation could start: a wait
that is not work. Bokeh calls a model's Python ``on_change`` callbacks as the browser's
message is applied; the callback here sets the widget's value there and then, and the
widget's own links carry it on (to the state, and from there to the results). When
Panel's own delivery comes, it finds the value already set and changes nothing. Only a
key press or a drag's end is taken so (BokehJS's ``value_throttled``): a drag's positions
are left to Panel, which merges them as before, so a drag costs the server no more updates
than it did, and its end is taken at once too.

Public API only: Bokeh's ``Document.select`` and ``Model.on_change``, Panel's
``pn.io.hold`` (what the change sets off leaves in one message). A control whose model
is not found keeps Panel's route. Measured with ``benchmarks/bench_dashboard.py`` (key
press -> new orbit data, in headless Chromium): see ``docs/performance.md``.
"""
from __future__ import annotations

import logging
import math
import time

import panel as pn
from bokeh.models import Slider

from ..trace import mark

log = logging.getLogger(__name__)


#: A press that comes sooner than this after the last one taken at once (a key held down)
#: is left to Panel, which merges what arrives within its debounce (ms).
MERGE_MS = 50


def answer_at_once(doc, widgets) -> int:
    """Let a browser's key press or drag's end on each slider in ``widgets`` (Panel
    sliders, each with a CSS class of its own first, e.g. ``ctl-theta0``) reach the
    widget as its message arrives. ``doc`` holds the page's models. Returns how many
    sliders were found."""
    by_class = {}
    for model in doc.select({"type": Slider}):
        for css in model.css_classes:
            by_class.setdefault(css, []).append(model)
    found = 0
    for widget in widgets:
        models = by_class.get(widget.css_classes[0], []) if widget.css_classes else []
        for model in models:
            model.on_change("value_throttled", AtOnce(doc, widget))
        found += bool(models)
    return found


class AtOnce:
    """Bokeh's callback for one slider's model. BokehJS sets ``value_throttled`` (with
    ``value``) for a key press and at the end of a drag, never during one: that value
    becomes the widget's now, what it changes in one message. A drag's positions
    (``value`` alone) and presses within ``MERGE_MS`` of the last one taken go Panel's
    way, merged as before: no update is added, and the last position always arrives."""

    def __init__(self, doc, widget):
        self.doc, self.widget = doc, widget
        self.taken_at = -math.inf

    def __call__(self, _attr, _old, new) -> None:
        now = time.monotonic()
        if new is None or new == self.widget.value or now - self.taken_at < MERGE_MS / 1e3:
            return
        self.taken_at = now
        mark("server receives")
        try:
            with pn.io.hold(self.doc):
                self.widget.value = new
        except Exception:  # noqa: BLE001 - a value the widget refuses: Panel's route says so
            log.warning("slider %s: value %r from the browser not taken at once",
                        self.widget.css_classes, new, exc_info=True)
