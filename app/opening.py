"""How a page reaches its browser: a light page at once, the dashboard once it is opened.

A page request (``GET /app?...``) runs on the server's one event loop, and so does
everything else: other sessions' updates, the liveness endpoint. Building the dashboard
there took ~0.5 s per page (its Python objects ~170 ms, their ~460 Bokeh models ~210 ms,
sending them ~120 ms), held in one piece: a burst of page requests stalled the loop for
seconds. So:

* the request gets a **light page** (``loading_shell``: the title and a spinner, ~25 ms);
* the **dashboard is built when a browser opens the page** (Panel's ``onload``, the page's
  ``document_ready``; ``build_when_opened``), in three turns of the event loop: its Python
  objects, then its models (held), then the message that sends them
  (``app.patches.hold_until_next_tick``); its updates wait until the browser says it has drawn the
  page. Other requests are answered between the turns, and a page that is never opened
  (a script fetching URLs) costs the light page only;
* a client whose unopened pages fill its place in the page gate (``app.pages.PageGate``)
  gets the **busy page**, answered before any Bokeh session is made (``BUSY_HTML``, ~1 ms:
  ``app.app_hooks.answer_busy_before_building``), or as a Panel page (``busy_page``) when
  the app runs without its server hooks (``panel serve app/main.py``).
"""
from __future__ import annotations

import html
import logging

import panel as pn
from bokeh.models import CustomJS

from .patches import hold_patches, hold_until_next_tick
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
#: Seconds the page's updates wait at most for the browser to say it has drawn the page.
SHOWN_WITHIN_S = 10.0
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


#: Panel's text views (``PanelMarkupView``: HTML, Markdown, alerts, spinners) make their
#: ``container`` when first drawn, and their handler of ``visible`` uses it at once: a page
#: sent in a patch has views that BokehJS builds at once but draws over later turns (the
#: tabs not on show last), so a change of ``visible`` in between threw "Cannot read
#: properties of undefined (reading 'style')" and stopped the rest of that message. Until
#: a view is drawn its ``container`` is a detached stand-in (the drawing reads the model's
#: state anew). Installed with the light page, before the dashboard arrives.
MARKUP_GUARD_JS = """
const html = Bokeh.Models.get("panel.models.markup.HTML");
const base = html == null ? null : Object.getPrototypeOf(html.prototype.default_view.prototype);
if (base != null && Object.getOwnPropertyDescriptor(base, "container") == null) {
  Object.defineProperty(base, "container", {
    configurable: true,
    get() { return this._drawn_container ?? document.createElement("div"); },
    set(value) { this._drawn_container = value; },
  });
}
"""


def loading_shell():
    """The light page a request gets: the dashboard takes its place once opened."""
    return pn.Column(
        pn.Row(pn.indicators.LoadingSpinner(value=True, size=28, margin=(4, 10)),
               pn.pane.HTML(f"<b>{OPENING_TEXT}</b>", margin=(10, 0))),
        sizing_mode="stretch_both", margin=0, css_classes=["page-shell"],
        stylesheets=[SHELL_CSS])


def build_when_opened(shell, make, doc=None) -> None:
    """Replace ``shell``'s content by the page ``make()`` builds, once a browser has it.

    Call while the page is built (``doc``: its document). Panel's ``onload`` runs the
    first turn (``make()``: the page's Python objects; results it asks for start then);
    the models are made in the next turn, under a hold released on the turn after, when
    the message carrying them is written (``app.patches.hold_until_next_tick``). Without a server
    (``doc`` None) the page is built at once.
    """
    if doc is None:
        shell.objects = [make()]
        return
    doc.js_on_event("document_ready", CustomJS(code=MARKUP_GUARD_JS))
    pn.state.onload(lambda: _first_turn(shell, make, doc))


def _first_turn(shell, make, doc) -> None:
    try:
        page = make()
    except Exception:
        log.exception("the dashboard could not be built")
        shell.objects = [pn.pane.Alert(FAILED_TEXT, alert_type="danger",
                                       css_classes=["page-failed"])]
        return
    try:
        doc.add_next_tick_callback(lambda: _attach(shell, page, doc))
    except Exception:  # the session closed meanwhile: nothing to show
        log.debug("session gone before its page was shown")


def _attach(shell, page, doc) -> None:
    """The page's models, held and sent on the next turn; then, if the page can say when
    the browser has drawn it (``page.when_shown``), its updates kept back until then
    (begun in the turn that sends the page, so that no update slips in before)."""
    keep = (lambda: _keep_updates_until_shown(page, doc)) if hasattr(page, "when_shown") \
        else None
    hold_until_next_tick(doc, then=keep)
    try:
        shell.objects = [page]
    except Exception:
        log.exception("the dashboard could not be shown")


def _keep_updates_until_shown(page, doc) -> None:
    """Keep the page's update messages back until the browser has drawn ``page``, at most
    ``SHOWN_WITHIN_S`` (``app.patches.hold_patches``). BokehJS builds the views of a page
    sent in a patch over several turns of its own; a change reaching a view built but not
    yet drawn fails in Panel's views ("Cannot read properties of undefined (reading
    'style')"), and results come in that time (a cached one at once)."""
    send_kept, done = hold_patches(doc), []

    def show(*_):
        if not done:
            done.append(True)
            send_kept()

    def late():
        if done:
            return
        session = getattr(doc.session_context, "_session", None)
        if getattr(session, "_subscribed_connections", None):  # a page still open
            log.warning("the browser did not say within %g s that it had drawn the page; "
                        "its updates are sent now", SHOWN_WITHIN_S)
        show()
    doc.add_timeout_callback(late, int(SHOWN_WITHIN_S * 1000))
    page.when_shown(show)
