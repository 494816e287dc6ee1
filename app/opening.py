"""How a page reaches its browser: a light page at once, the dashboard once it is opened.

A page request (``GET /app?...``) runs on the server's one event loop, and so does
everything else: other sessions' updates, the liveness endpoint. Building the dashboard
there took ~0.5 s per page (its Python objects ~170 ms, their ~460 Bokeh models ~210 ms,
sending them ~120 ms), held in one piece: a burst of page requests stalled the loop for
seconds. So:

* the request gets a **light page** (``loading_shell``: the title and a spinner, ~25 ms);
* the **dashboard is built when a browser opens the page** (Panel's ``onload``, the page's
  ``document_ready``; ``build_when_opened``), in two turns of the event loop: its Python
  objects, then its models, sent in one message (``pn.io.hold``). Other requests are
  answered between the turns, and a page that is never opened (a script fetching URLs)
  costs the light page only;
* a client whose unopened pages fill its place in the page gate (``app.pages.PageGate``)
  gets the **busy page**, answered before any Bokeh session is made (``BUSY_HTML``, ~1 ms:
  ``app.edge.answer_busy_before_building``), or as a Panel page (``busy_page``) when
  the app runs without its server hooks (``panel serve app/main.py``).
"""
from __future__ import annotations

import html
import logging

import panel as pn
from bokeh.models import CustomJS

from .edge import guard_markup_views
from .trace import mark
from .views.widgets import caption, look

log = logging.getLogger(__name__)

TITLE = "Micropillar friction explorer"
BUSY_TITLE = f"{TITLE} (busy)"
BUSY_HEADING = "The server is busy"
BUSY_TEXT = ("It is still building several pages for your address that have not been "
             "opened yet. This page reloads itself in a few seconds.")
#: The busy page reloads itself after a random 3-6 s (spread, so a class that was turned
#: away at once does not come back at once).
AUTO_RELOAD_JS = "setTimeout(() => window.location.reload(), 3000 + 3000 * Math.random());"
OPENING_TEXT = "Opening the explorer&hellip;"
FAILED_TEXT = ("**The page could not be built.** The server's log says why; reloading the "
               "page tries again.")

BUSY_HTML = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(BUSY_TITLE)}</title>
<style>body {{font-family: system-ui, sans-serif; margin: 2em; max-width: 40em; color: #222}}
button {{font-size: 1em; padding: 0.4em 1em; cursor: pointer}}</style></head>
<body class="busy-page"><h3>{html.escape(BUSY_HEADING)}</h3><p>{html.escape(BUSY_TEXT)}</p>
<button type="button" onclick="window.location.reload()">Reload now</button>
<script>{AUTO_RELOAD_JS}</script></body></html>
"""


def busy_page(doc=None):
    """The busy page as a Panel page (``BUSY_HTML`` is the one answered by the server)."""
    reload = pn.widgets.Button(**caption("Reload now"), **look("primary"), width=120)
    reload.js_on_click(code="window.location.reload()")
    if doc is not None:
        doc.js_on_event("document_ready", CustomJS(code=AUTO_RELOAD_JS))
    return pn.Column(pn.pane.Markdown(f"### {BUSY_HEADING}\n\n{BUSY_TEXT}"), reload,
                     css_classes=["busy-page"])


#: The light page has no box of its own once the dashboard is in it: the dashboard is laid
#: out as the page's root, as if it had been sent with the page (its phone layout too).
SHELL_CSS = ":host(.page-shell) { display: contents !important; }"


def loading_shell():
    """The light page a request gets: the dashboard takes its place once opened."""
    return pn.Column(
        pn.Row(pn.indicators.LoadingSpinner(value=True, size=28, margin=(4, 10)),
               pn.pane.HTML(f"<b>{OPENING_TEXT}</b>", margin=(10, 0))),
        sizing_mode="stretch_both", margin=0, css_classes=["page-shell"],
        stylesheets=[SHELL_CSS])


def build_when_opened(shell, make, doc=None) -> None:
    """Replace ``shell``'s content by the page ``make()`` builds, once a browser has it.

    Call while the page is built (``doc``: its document). Panel's ``onload`` runs
    ``make()`` (the page's Python objects; the results it asks for start then); the
    page's models are made on the event loop's next turn (``pn.state.execute``), under
    ``pn.io.hold``, so they leave in one message and other requests are answered in
    between. Without a server (``doc`` None) the page is built at once.
    """
    if doc is None:
        shell.objects = [make()]
        return
    answer_each_event_in_one_message()
    guard_markup_views(doc)
    pn.state.onload(lambda: _build(shell, make))


_HOLDS: list = []


def answer_each_event_in_one_message() -> None:
    """What a page does in answer to one event from its browser (a slider moved: busy
    markers, readouts, the address, download names) reaches the browser in one message.

    Panel marks the time it processes an event from a browser (``pn.state.busy``); the
    changes made meanwhile are held (``pn.io.hold``) and leave together when it is done.
    Installed once per process."""
    if _HOLDS:
        return
    _HOLDS.append(None)

    def on_busy(event):
        if event.new:
            doc = pn.state.curdoc
            if doc is not None and doc.session_context is not None:
                mark("server receives")
                hold = pn.io.hold(doc)
                hold.__enter__()
                _HOLDS.append(hold)
            return
        while len(_HOLDS) > 1:
            try:
                _HOLDS.pop().__exit__(None, None, None)
                mark("answer sent")
            except Exception:
                log.exception("a page's changes could not be sent")
    pn.state.param.watch(on_busy, "busy")


def _build(shell, make) -> None:
    mark("page build starts")
    try:
        page = make()
    except Exception:
        log.exception("the dashboard could not be built")
        shell.objects = [pn.pane.Alert(FAILED_TEXT, alert_type="danger",
                                       css_classes=["page-failed"])]
        return
    mark("page objects built")
    pn.state.execute(lambda: _attach(shell, page), schedule=True)


def _attach(shell, page) -> None:
    """The page's models, sent as one message."""
    try:
        mark("page models start")
        with pn.io.hold():
            shell.objects = [page]
        mark("page sent")
    except Exception:
        log.exception("the dashboard could not be shown")
