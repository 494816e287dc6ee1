"""A text the page rewrites at every slider move (the headline, the regime's words), as a
plain Bokeh ``Div``: writing its HTML is one property change (~0.06 ms of the server),
where a Panel text pane renders, escapes and restyles it again (~2.6 ms as HTML, ~4 ms as
Markdown, measured in process).
"""
from __future__ import annotations

import panel as pn
from bokeh.models import Div
from markdown_it import MarkdownIt  # Panel's own Markdown renderer

_MARKDOWN = MarkdownIt()


def markdown_html(text: str) -> str:
    """``text`` (Markdown) as HTML, as Panel's Markdown pane renders it."""
    return _MARKDOWN.render(text)


class TextDiv:
    """A ``Div`` with ``html`` in a Panel layout (``pane``); ``text`` reads and writes it
    (written only when it changes)."""

    def __init__(self, html: str, css_class: str, styles: dict | None = None,
                 margin=(0, 5)):
        self.div = Div(text=html, css_classes=[css_class], styles=styles or {},
                       margin=margin, sizing_mode="stretch_width")
        self.pane = pn.pane.Bokeh(self.div, sizing_mode="stretch_width", margin=0)

    @property
    def text(self) -> str:
        return self.div.text

    @text.setter
    def text(self, html: str) -> None:
        if html != self.div.text:
            self.div.text = html
