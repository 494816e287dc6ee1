"""Text that follows a playing animation without laying the page out again.

A Bokeh ``Div`` whose ``text`` changes draws itself anew and has BokehJS lay out the
whole page from its root: every figure in the page (other tabs too) is measured and
repainted, which in the served dashboard costs as much as several animation frames. A
``bokeh.models.dom.HTML`` node placed in a ``Div``'s ``elements`` redraws only itself
when its ``html`` changes, so the players' readouts are written there::

    box = live_div("τ = 0.00", name="energy_live_readout", width=420)
    content = live_html(box)     # the readout's text: content.html
    CustomJS(args=dict(readout=content),
             code="readout.setv({html: `τ = ${t.toFixed(2)}`}, {sync: false});")

The box carries ``LIVE_CLASS``: the page's accessibility pass (``app.figures.access_js``)
need not walk the page again when only such text has changed.
"""
from __future__ import annotations

from bokeh.models import Div
from bokeh.models.dom import HTML

from .access_js import LIVE_CLASS

__all__ = ["live_div", "live_html", "LIVE_CLASS"]


def live_div(html: str, name: str, **kwargs) -> Div:
    """A ``Div`` showing ``html`` in a ``dom.HTML`` node called ``name`` (its
    ``elements[0]``; the Div itself is ``name + "_box"``). ``kwargs`` go to the Div
    (width, height, styles, sizing_mode, ...)."""
    classes = [*kwargs.pop("css_classes", []), LIVE_CLASS]
    return Div(text="", elements=[HTML(html=html, name=name)], name=f"{name}_box",
               css_classes=classes, **kwargs)


def live_html(box: Div) -> HTML:
    """The ``dom.HTML`` node of a ``live_div``: set its ``html`` to change the text."""
    content = box.elements[0] if box.elements else None
    if not isinstance(content, HTML):
        raise TypeError(f"{box!r} is not a live_div (its elements are {box.elements!r})")
    return content
