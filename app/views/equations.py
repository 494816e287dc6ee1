"""The Equations tab: the model's equations (Eqs. 3-6, 8-13) typeset by MathJax, which
Bokeh serves itself (no external resources)."""
from __future__ import annotations

import panel as pn

from ..texts import EQUATIONS, EQUATIONS_INTRO, EQUATIONS_NOTES


class EquationsView(pn.viewable.Viewer):
    """Captions and typeset equations in two columns, readable at 1280 x 720."""

    def __init__(self, **params):
        super().__init__(**params)
        style = {"font-size": "0.92em"}
        items = [pn.Column(pn.pane.Markdown(caption, styles=style, margin=(0, 10)),
                           pn.pane.LaTeX(f"$${latex}$$", renderer="mathjax",
                                         styles={"font-size": "1em"}, margin=(0, 10)),
                           margin=(2, 0))
                 for caption, latex in EQUATIONS]
        half = len(items) // 2
        self.layout = pn.Row(
            pn.Column(pn.pane.Markdown(EQUATIONS_INTRO, styles=style, margin=(0, 10)),
                      *items[:half], width=480),
            pn.Column(*items[half:], pn.pane.Markdown(EQUATIONS_NOTES, styles=style,
                                                      margin=(0, 10)), width=480),
            css_classes=["equations"])

    def __panel__(self):
        return self.layout
