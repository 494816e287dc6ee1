"""A text the page rewrites at every slider move (the headline, the regime's words).

Written in place: ``LiveHTML`` is a ``JSComponent`` whose ``html`` the browser puts into its
element when it changes, and nothing else. A Bokeh ``Div`` would re-render on a new text
and lay its whole root out again (in this page: every figure measured and repainted, ~60 ms
of the browser's time per move), and a Panel text pane also renders, escapes and restyles
the text on the server (~2.6 ms as HTML, ~4 ms as Markdown, measured in process).
"""
from __future__ import annotations

import param
from markdown_it import MarkdownIt  # Panel's own Markdown renderer
from panel.custom import JSComponent

_MARKDOWN = MarkdownIt()


def markdown_html(text: str) -> str:
    """``text`` (Markdown) as HTML, as Panel's Markdown pane renders it."""
    return _MARKDOWN.render(text)


class LiveHTML(JSComponent):
    """``html`` shown as it is; a new ``html`` replaces the element's content in place."""

    html = param.String(default="", doc="the HTML shown (trusted: written by the app)")

    _esm = """
    export function render({ model }) {
      const box = document.createElement("div");
      box.className = "live-html";
      box.innerHTML = model.html;
      model.on("html", () => { box.innerHTML = model.html; });
      return box;
    }
    """
    _stylesheets = [".live-html p { margin: 0; }"]
