"""Micropillar friction explorer: ``panel serve app`` serves this page at ``/app``.

Makes the page of one browser session from the URL's state. The code lives in the
installed package ``app`` (imported by that name, as the worker processes and the tests
import it), so this script only makes the page.

The request gets a light page at once; the dashboard is built when a browser opens it
(``app.opening``), so a page request never holds the server's event loop for long. A
client (address) with several pages that no browser has opened yet gets a short "busy"
page instead (``app.pages.PageGate``; the server hooks answer it before any session is
made). Panel's liveness probe (``/liveness?endpoint=/app``, no browser session) builds
nothing.
"""
import panel as pn

from app.opening import BUSY_TITLE, TITLE, build_when_opened, busy_page, loading_shell
from app.page_template import use_page_template
from app.pages import page_gate, schedule_release, sessions_of
from app.results import client_address
from app.views import Dashboard

pn.extension("mathjax", notifications=False)
use_page_template(pn.state.curdoc)  # <meta name="viewport">: phones use their own width


def serve() -> None:
    """The light page that becomes the dashboard once opened, or the busy page. (A
    function: the callbacks it leaves behind must not reach for this script's globals,
    which are gone once the page is built.)"""
    doc, gate, client = pn.state.curdoc, page_gate(), client_address()
    if doc is not None and doc.session_context is None:
        # Panel's liveness probe: a document no browser will get (``servable`` adds
        # nothing to it), built on the event loop at every health check. The script
        # running is its answer; whether the dashboard builds, app.healthcheck checks
        # with a real session.
        return
    page_id, release, count = id(doc), schedule_release, sessions_of
    if doc is not None and not gate.admit(client, page_id):
        busy_page(doc).servable(title=BUSY_TITLE, location=False)
        return
    shell = loading_shell()
    if doc is not None:
        pn.state.onload(lambda: gate.opened(client, page_id))
        doc.on_session_destroyed(
            lambda context: (gate.gone(client, page_id), release(count(context))))
    build_when_opened(shell, Dashboard.from_session, doc)
    shell.servable(title=TITLE, location=False)
    if doc is not None:
        gate.built(client, page_id)


serve()
