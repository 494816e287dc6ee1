"""Micropillar friction explorer: ``panel serve app`` serves this page at ``/app``.

Builds the page of one browser session from the URL's state. The code lives in the
installed package ``app`` (imported by that name, as the worker processes and the tests
import it), so this script only makes the page.

A client (address) with several pages built that no browser has opened yet gets a short
"busy" page instead (``app.pages.PageGate``): a page build holds the server's event loop,
so a burst of page requests must not stall the other sessions and the health check.
Panel's liveness probe (``/liveness?endpoint=/app``, no browser session) builds nothing.
"""
import panel as pn
from bokeh.models import CustomJS

from app.app_hooks import guard_query_parsing
from app.pages import page_gate, schedule_release, sessions_of
from app.results import client_address
from app.views import Dashboard
from app.views.widgets import caption, look

guard_query_parsing()  # already done by the server hook; kept for `panel serve app/main.py`
TITLE = "Micropillar friction explorer"
pn.extension("mathjax", notifications=False)


#: The busy page reloads itself after a random 3-6 s (spread, so a class that was turned
#: away at once does not come back at once).
AUTO_RELOAD_JS = "setTimeout(() => window.location.reload(), 3000 + 3000 * Math.random());"


def busy_page(doc=None):
    reload = pn.widgets.Button(**caption("Reload now"), **look("primary"), width=120)
    reload.js_on_click(code="window.location.reload()")
    if doc is not None:
        doc.js_on_event("document_ready", CustomJS(code=AUTO_RELOAD_JS))
    return pn.Column(pn.pane.Markdown(
        "### The server is busy\n\nIt is still building several pages for your address "
        "that have not been opened yet. This page reloads itself in a few seconds."),
        reload, css_classes=["busy-page"])


def serve() -> None:
    """The dashboard, or the busy page. (A function: the callbacks it leaves behind must
    not reach for this script's globals, which are gone once the page is built.)"""
    doc, gate, client = pn.state.curdoc, page_gate(), client_address()
    if doc is not None and doc.session_context is None:
        # Panel's liveness probe: a document no browser will get (``servable`` adds
        # nothing to it), built on the event loop at every health check. The script
        # running is its answer; whether the dashboard builds, app.healthcheck checks
        # with a real session. Building it here held the loop ~0.3 s (seconds under a
        # class) and took a place in the page gate each time.
        return
    page_id, release, count = id(doc), schedule_release, sessions_of
    if doc is not None and not gate.admit(client, page_id):
        busy_page(doc).servable(title=f"{TITLE} (busy)")
        return
    if doc is not None:
        pn.state.onload(lambda: gate.opened(client, page_id))
        doc.on_session_destroyed(
            lambda context: (gate.gone(client, page_id), release(count(context))))
    Dashboard.from_session().servable(title=TITLE)
    if doc is not None:
        gate.built(client, page_id)


serve()
