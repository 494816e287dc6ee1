"""Server hooks (``panel serve app`` runs ``on_server_loaded`` once, before any request).

* The compiled kernel is loaded and the worker processes started, so the first page is as
  quick as the next; on a first start after installing (nothing in numba's cache) that
  compile runs in the background while pages are served and say so.
* The serving edge's guards (``app.edge``: security headers, the busy page before any
  session, the guard on Panel's address reader) are installed on the tested stack; on
  another one the server says so in one line.
"""
from app.edge import install
from app.jobs import start_warm_up
from app.opening import BUSY_HTML
from app.pages import page_gate


def on_server_loaded(server_context):
    install(BUSY_HTML, lambda remote_ip: page_gate().has_room(remote_ip))
    start_warm_up()
