"""How a page reaches its browser: a light page at once, the dashboard once it is opened.

A page request (``GET /app?...``) runs on the server's one event loop, and so does
everything else: other sessions' updates, the liveness endpoint. Building the dashboard
there took ~0.5 s per page (its Python objects ~170 ms, their ~460 Bokeh models ~210 ms,
sending them ~120 ms), held in one piece: a burst of page requests stalled the loop for
seconds. So:

* the request gets a **light page** (``loading_shell``: the title and a spinner, ~25 ms);
* the **dashboard is built when a browser opens the page** (Panel's ``onload``, the page's
  ``document_ready``; ``build_when_opened``) over three turns of the event loop: its
  Python objects, then their models in two messages (``pn.io.hold``), the support tab's
  views in the second (``Dashboard.in_two_parts``; a page opened on another tab in one).
  Other requests are answered between the turns, and a page that is never opened (a
  script fetching URLs) costs the light page only;
* pages opened together are **built one at a time, whole**, the first opened first,
  clients in turn (``LANE``, ``app.page_lane``): their steps no longer take turns, so the
  first visitor's page is not held until the last one's is done;
* the dashboard is **built once when the server starts** (``rehearse``), in a document
  no browser gets: a process's first page cost twice what the next ones did (one-time
  work of Panel and Bokeh), and that first page was a visitor's or the health check's;
* a client whose unopened pages fill its place in the page gate (``app.pages.PageGate``)
  is sent to the **busy page** before any Bokeh session is made: Panel's
  ``authorize_callback`` (``admit_or_busy``, set by the server hooks) answers its request
  with a redirect to a static file (``app/static/busy.html``, ``BUSY_HTML``; ~1 ms), which
  comes back to the page's address a few seconds later. Without the server hooks
  (``panel serve app/main.py``) the busy page is a Panel page (``busy_page``).
"""
from __future__ import annotations

import html
import logging
import time
from pathlib import Path
from typing import Iterator
from urllib.parse import urlencode

import panel as pn
from bokeh.models import CustomJS

from .edge import guard_markup_views
from .heap import page_built
from .page_lane import PageLane
from .pages import page_gate
from .slot import client_address
from .trace import mark
from .views.widgets import caption, look

log = logging.getLogger(__name__)

TITLE = "Micropillar friction explorer"
BUSY_TITLE = f"{TITLE} (busy)"
BUSY_HEADING = "The server is busy"
BUSY_TEXT = ("It is still building several pages for your address that have not been "
             "opened yet. This page reloads itself in a few seconds.")
#: The busy page goes back to the page's address: the one it was sent from (``?next=``,
#: a path of this server, ``admit_or_busy``), else its own (a reload). (``window.URL``: in
#: the button's ``onclick`` a bare ``URL`` is ``document.URL``.)
BACK_JS = ("const n = new URLSearchParams(location.search).get('next');"
           " const u = n ? new window.URL(n, location.href) : null;"
           " u && u.origin === location.origin ? location.replace(u.href) : location.reload();")
#: ... after a random 3-6 s (spread, so a class that was turned away at once does not come
#: back at once).
AUTO_RELOAD_JS = f"setTimeout(() => {{ {BACK_JS} }}, 3000 + 3000 * Math.random());"
#: The busy page's file, served by Bokeh beside the app (a directory app's ``static``
#: folder): ``/app/static/busy.html``. Its text is ``BUSY_HTML`` (``tests/test_opening.py``).
BUSY_FILE = Path(__file__).with_name("static") / "busy.html"
OPENING_TEXT = "Opening the explorer&hellip;"
FAILED_TEXT = ("**The page could not be built.** The server's log says why; reloading the "
               "page tries again.")

BUSY_HTML = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(BUSY_TITLE)}</title>
<style>body {{font-family: system-ui, sans-serif; margin: 2em; max-width: 40em; color: #222}}
h1 {{font-size: 1.4em}} button {{font-size: 1em; padding: 0.4em 1em; cursor: pointer}}</style>
</head><body class="busy-page"><main><h1>{html.escape(BUSY_HEADING)}</h1>
<p>{html.escape(BUSY_TEXT)}</p>
<button type="button" onclick="{html.escape(BACK_JS)}">Reload now</button></main>
<script>{AUTO_RELOAD_JS}</script></body></html>
"""


def admit_or_busy(user_info, path: str):
    """Panel's ``authorize_callback`` (``pn.config.authorize_callback``, set by the server
    hooks, ``app.app_hooks``), run for each page request before its session is made:
    True (Panel builds the page) while the client has room in the page gate
    (``app.pages.page_gate``), else the address of the busy page (Panel redirects there),
    which comes back to the requested address (path and query). ``path``: the page's path
    (``/app``, with the server's ``--prefix``)."""
    if page_gate().has_room(client_address()):
        return True
    doc = pn.state.curdoc  # Panel's stand-in document for the request
    request = doc.session_context.request if doc is not None and doc.session_context else None
    return busy_address(path, getattr(request, "uri", None) or path)


def busy_address(path: str, uri: str) -> str:
    """The busy page beside the app at ``path``, going back to ``uri``."""
    return f"{path.rstrip('/')}/static/{BUSY_FILE.name}?{urlencode({'next': uri})}"


def busy_page(doc=None):
    """The busy page as a Panel page, for the app served without its server hooks
    (``BUSY_HTML`` is the one the server sends)."""
    reload = pn.widgets.Button(**caption("Reload now"), **look("primary"), width=120)
    reload.js_on_click(code=BACK_JS)
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
               pn.pane.HTML(opening_html(), margin=(10, 0), css_classes=["opening-text"])),
        sizing_mode="stretch_both", margin=0, css_classes=["page-shell"],
        stylesheets=[SHELL_CSS])


def opening_html(ahead: int = 0, seconds: float | None = None) -> str:
    """The light page's text: opening; with ``ahead`` pages to be built before it (a
    class opening the link together, ``LANE``), how many and about how long."""
    text = f"<b>{OPENING_TEXT}</b>"
    if ahead > 0:
        pages = "1 other page" if ahead == 1 else f"{ahead} other pages"
        text += f" The server is building {pages} first"
        text += f" (about {max(1, round(seconds))} s)." if seconds is not None else "."
    return f'<span role="status">{text}</span>'


def _tell_waiting(doc, shell, ahead: int, seconds: float | None) -> None:
    """Show a waiting page's place in the lane (a change of its light page, made on its
    own document's next turn)."""
    text = opening_html(ahead, seconds)

    def write():
        for pane in shell.select(pn.pane.HTML):
            if "opening-text" in pane.css_classes:
                pane.object = text
    doc.add_next_tick_callback(write)


def build_when_opened(shell, make, doc=None) -> None:
    """Replace ``shell``'s content by the page ``make()`` builds, once a browser has it.

    Call while the page is built (``doc``: its document). Panel's ``onload`` runs
    ``make()`` (the page's Python objects; the results it asks for start then); the
    page's models are made ``STEP_GAP_MS`` later, under ``pn.io.hold``, in one message
    or two (``Dashboard.in_two_parts``), so other requests are answered in between.
    Without a server (``doc`` None) the page is built at once.
    """
    if doc is None:
        shell.objects = [make()]
        return
    answer_each_event_in_one_message()
    guard_markup_views(doc)
    pn.state.onload(lambda: LANE.add(
        doc, build_steps(doc, shell, make), client=client_address(),
        note=lambda ahead, seconds: _tell_waiting(doc, shell, ahead, seconds)))


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
            # Not a page already held (a result being applied): that hold sends what is
            # changed now. Panel's hold restores the hold it found when it ends, so one
            # begun inside another and ended after it left the page held for good, and
            # every later change of that page unsent.
            if doc is not None and doc.session_context is not None \
                    and not doc.callbacks.hold_value:
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


#: Milliseconds between two steps of a page's build. On the next tick instead, a liveness
#: probe that came during a step waited for the next one too (traced with one core busy:
#: 0.88 s through the objects and the first part): Tornado takes a few turns of the loop
#: to accept, read and answer a request, and a next-tick callback runs before them.
STEP_GAP_MS = 10


#: The server's pages are built one at a time, the first opened first, clients in turn.
LANE = PageLane(STEP_GAP_MS)


def build_steps(doc, shell, make) -> Iterator[None]:
    """The steps of a page's build, one per ``next()`` (``LANE``): its Python objects; its
    models and their message (``pn.io.hold``); the rest of its models, when the page
    can be split (``Dashboard.in_two_parts``). A page that cannot be built says so in
    its place."""
    mark("page build starts")
    try:
        page = make()
    except Exception:
        log.exception("the dashboard could not be built")
        shell.objects = [pn.pane.Alert(FAILED_TEXT, alert_type="danger",
                                       css_classes=["page-failed"])]
        return
    mark("page objects built")
    yield
    try:
        mark("page models start")
        split = getattr(page, "in_two_parts", None)
        rest = split() if split is not None else None
        with pn.io.hold(doc):
            shell.objects = [page]
        if rest is not None:
            mark("page first part sent")
            yield
            mark("page rest starts")
            with pn.io.hold(doc):
                rest()
        mark("page sent")
        sent = getattr(page, "sent", None)
        if sent is not None:
            sent(doc)
        page_built()
    except Exception:
        log.exception("the dashboard could not be shown")


def rehearse() -> float:
    """Build the dashboard once, with its models and its message, in a document no browser
    gets; the seconds it took.

    A process's first page build cost about twice what the next ones did, measured with
    ``MICROPILLAR_TRACE`` on pages opened one after another (``page build starts`` ->
    ``page sent``): its objects 0.71 s against 0.22-0.51 s, its models and message 1.03 s
    against 0.52-0.59 s -- the first use of each of Panel's and Bokeh's model classes,
    stylesheets and encoders, done once per process. That step holds the event loop, so
    the first page opened (often the health check's) delayed the liveness probe by a
    second. Run by the server hooks (``app.app_hooks``) before the first request, once the
    solver is ready: the default state's results are computed then (and cached)."""
    from bokeh.document import Document

    from .views import Dashboard

    start = time.perf_counter()
    doc = Document()
    page = pn.panel(Dashboard.from_session())
    doc.add_root(page.get_root(doc))
    doc.to_json()  # the models encoded, as for their message
    return time.perf_counter() - start
