"""The offline page's tabs drawn when first shown: the polar diagrams (Fig. 11) and the
regime map (Fig. 5).

Their models are not in the page's Bokeh document: BokehJS would deserialise them as the
page opens (about half of its models) though their views wait for their tab. Each such
tab is a panel holding a placeholder in the document and, in the JSON element
``#mp-later``, its panel with the figures, serialised as BokehJS's document JSON encodes
models (``LATER_ID``); the page adds it to the document when the tab is first shown
(``tabs.js``, with BokehJS's ``Document.apply_json_patch``).
"""
from __future__ import annotations

import json
import re

from bokeh.core.serialization import Serializer
from bokeh.layouts import column, row
from bokeh.models import CustomJS, Div, Plot, Select, TabPanel

from ..figures.access_js import figure_classes

__all__ = ["polar_tab", "map_tab", "later_tab", "later_json", "LATER_ID", "POLAR_CAPTION"]

#: The id of the page's JSON element holding the panels of the tabs drawn when shown.
LATER_ID = "mp-later"
POLAR_CAPTION = ("Fixed-orientation arrays (every support at the same θ₀) for the current "
                 "springs and load, 72 orientations on [0°, 180°] mirrored (y → −y), each "
                 "at the load factor β of the controls (self-consistent: solved for each "
                 "orientation); computed in this page. Click a diagram to set θ₀.")


def polar_tab(polar):
    """Fig. 11a-c side by side, the sweep's status and the caption."""
    status = Div(text="", name="polar-status", styles={"color": "#555555"},
                 sizing_mode="stretch_width")
    caption = Div(text=POLAR_CAPTION, name="polar-caption", sizing_mode="stretch_width",
                  styles={"color": "#555555", "font-size": "0.9em"})
    for fig in polar.values():
        fig.js_on_event("tap", CustomJS(code="if (window.explorer) window.explorer._polarTap("
                                             "cb_obj.x, cb_obj.y);"))
    cells = [column([fig], width=335, height=360) for fig in polar.values()]
    return column([row(cells, styles={"flex-wrap": "wrap"}, sizing_mode="stretch_width",
                       name="polar-row"), status, caption],
                  sizing_mode="stretch_width", name="polar-tab")


def map_tab(fig):
    """The regime map, the quantity it shows and its note."""
    fig.sizing_mode = "stretch_width"
    fig.min_width = 300
    fig.js_on_event("tap", CustomJS(code="if (window.explorer) window.explorer._mapTap("
                                         "cb_obj.x, cb_obj.y);"))
    quantity = Select(title="map", value="5a", name="map-quantity", width=260,
                      options=[(q, re.sub(r", F_N = [0-9.]+", "", t))
                               for q, t in _map_titles().items()])
    quantity.js_on_change("value", CustomJS(
        code="if (window.explorer) window.explorer._mapQuantity(cb_obj.value);"))
    note = Div(text="", name="map-note", sizing_mode="stretch_width",
               styles={"color": "#555555", "font-size": "0.9em"})
    return column([quantity, fig, note], sizing_mode="stretch_width", name="map-tab")


def _map_titles() -> dict:
    from ..figures.arrays import MAP_QUANTITIES
    return {q: t for q, (_, t) in MAP_QUANTITIES.items()}


def later_tab(child, title: str, key: str) -> tuple[TabPanel, TabPanel]:
    """(the document's panel: a placeholder, named ``tab-{key}-later``; the panel with
    ``child`` that the page puts in its place, named ``tab-{key}``). Its figures are
    marked for the page's script that names them (``figure_classes``)."""
    content = TabPanel(child=child, title=title, name=f"tab-{key}")
    figure_classes(*sorted((m for m in content.references() if isinstance(m, Plot)
                            and m.name and m.title is not None and m.title.text),
                           key=lambda m: m.name))
    placeholder = Div(text="<i>drawing…</i>", name=f"tab-{key}-placeholder")
    return TabPanel(child=placeholder, title=title, name=f"tab-{key}-later"), content


def later_json(panels: dict, doc) -> str:
    """``{key: panel}`` as the text of the ``#mp-later`` element: each panel as BokehJS's
    document JSON encodes a model (arrays inlined), for ``Document.apply_json_patch``.
    Raises ``ValueError`` when a panel shares a model with ``doc`` (it would be sent twice
    and the page's copy replaced)."""
    ours = {m.id for root in doc.roots for m in root.references()}
    out = {}
    for key, panel in panels.items():
        shared = sorted(m.id for m in panel.references() if m.id in ours)
        if shared:
            raise ValueError(f"the {key} tab shares models with the page's document: {shared}")
        out[key] = Serializer(deferred=False).encode(panel)
    return json.dumps(out, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
