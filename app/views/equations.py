"""The Equations tab: the model's equations (Eqs. 3-6, 8-13) typeset by MathJax, which
Bokeh serves itself (no external resources)."""
from __future__ import annotations

import html

import panel as pn

from .layout import SR_ONLY_CSS
from ..texts import EQUATIONS, EQUATIONS_INTRO, EQUATIONS_NOTES


#: A long equation on a phone scrolls within its line (``PageAccess`` makes such a line
#: focusable, ``tabindex``): a shadow at the edge where more of it lies shows that it
#: does. The white covers move with the equation's ends and hide a shadow once that end is
#: in view.
SCROLL_HINT_CSS = ":host([tabindex]) {background: " + ", ".join([
    "linear-gradient(to right, #fff 45%, rgba(255,255,255,0)) left center / 40px 100% "
    "no-repeat local",
    "linear-gradient(to left, #fff 45%, rgba(255,255,255,0)) right center / 40px 100% "
    "no-repeat local",
    "radial-gradient(farthest-side at 0 50%, rgba(0,0,0,0.3), rgba(0,0,0,0)) left center "
    "/ 12px 100% no-repeat scroll",
    "radial-gradient(farthest-side at 100% 50%, rgba(0,0,0,0.3), rgba(0,0,0,0)) right "
    "center / 12px 100% no-repeat scroll #fff"]) + ";}"


class EquationsView(pn.viewable.Viewer):
    """Captions and typeset equations in two columns, readable at 1280 x 720."""

    def __init__(self, **params):
        super().__init__(**params)
        style = {"font-size": "0.92em"}
        items = [pn.Column(pn.pane.Markdown(caption, styles=style, margin=(0, 10)),
                           # A long equation scrolls within its line on a phone.
                           # Screen readers read the TeX source (PageAccess hides the
                           # typeset SVG from them).
                           pn.pane.HTML(f'<p class="sr-only">{html.escape(latex)}</p>',
                                        stylesheets=[SR_ONLY_CSS], margin=0),
                           pn.pane.LaTeX(f"$${latex}$$", renderer="mathjax",
                                         styles={"font-size": "1em", "overflow-x": "auto",
                                                 "max-width": "calc(100vw - 30px)"},
                                         stylesheets=[SCROLL_HINT_CSS],
                                         css_classes=["scroll-x"], margin=(0, 10)),
                           margin=(2, 0))
                 for caption, latex in EQUATIONS]
        half = len(items) // 2
        # Two columns side by side where there is room, one under the other on a phone.
        column = dict(min_width=300, max_width=520, sizing_mode="stretch_width")
        self.layout = pn.FlexBox(
            pn.Column(pn.pane.Markdown(EQUATIONS_INTRO, styles=style, margin=(0, 10)),
                      *items[:half], **column),
            pn.Column(*items[half:], pn.pane.Markdown(EQUATIONS_NOTES, styles=style,
                                                      margin=(0, 10)), **column),
            flex_wrap="wrap", css_classes=["equations"], sizing_mode="stretch_width")

    def __panel__(self):
        return self.layout
