"""Server hooks (``panel serve app`` runs ``on_server_loaded`` once, before any request).

* The compiled kernel is loaded and the worker processes started, so the first page is as
  quick as the next; on a first start after installing (nothing in numba's cache) that
  compile runs in the background while pages are served and say so.
* The dashboard is built once (``app.opening.rehearse``) when the solver is ready, so the
  first visitor's page holds the event loop no longer than the next one's.
* The serving edge's guards (``app.edge``: security headers, the busy page before any
  session, the guard on Panel's address reader) are installed on the tested stack; on
  another one the server says so in one line.
"""
import logging

from app.edge import install
from app.jobs import start_warm_up
from app.opening import BUSY_HTML, rehearse
from app.pages import page_gate


log = logging.getLogger(__name__)


def on_server_loaded(server_context):
    install(BUSY_HTML, lambda remote_ip: page_gate().has_room(remote_ip))
    if start_warm_up():  # the solver compiles in the background: no results to show yet
        return
    try:
        log.info("the dashboard rehearsed in %.2f s", rehearse())
    except Exception:  # the pages will say what fails; the server still serves them
        log.exception("the dashboard could not be rehearsed")
