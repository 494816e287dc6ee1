"""Server hooks (``panel serve app`` runs ``on_server_loaded`` once, before any request).

* The compiled kernel is loaded and the worker processes started, so the first page is as
  quick as the next; on a first start after installing (nothing in numba's cache) that
  compile runs in the background while pages are served and say so.
* Panel's reader of the page address is guarded (``app.urlstate.panel_query``): a value it
  cannot convert, such as 4301 digits, would otherwise stop the page from syncing.
* Every response carries ``SECURITY_HEADERS``: no other site may frame the dashboard
  (clickjacking), and browsers take each file as the type the server declares. A
  ``bokeh-session-id`` in the address that Bokeh would read as empty is dropped (Bokeh
  would answer 500).
* A page request of a client with no room in the page gate (``app.pages``) gets the busy
  page before any Bokeh session is made (``answer_busy_before_building``): the session
  and its Panel page cost ~25 ms of the event loop each, and a burst of twenty held the
  liveness endpoint half a second.
"""
from app.jobs import start_warm_up
from app.urlstate import panel_query

#: Headers added to every HTTP response of the server (pages, scripts, websocket upgrades,
#: the liveness endpoint, errors).
SECURITY_HEADERS = {
    "X-Frame-Options": "SAMEORIGIN",
    "Content-Security-Policy": "frame-ancestors 'self'",
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "same-origin",
}


def guard_query_parsing() -> None:
    """Replace Panel's query reader by ``panel_query`` of it (once per process)."""
    from panel.io import location

    if not hasattr(location.parse_query, "__wrapped__"):
        location.parse_query = panel_query(location.parse_query)


def add_security_headers() -> None:
    """Send ``SECURITY_HEADERS`` with every response of this process's Tornado server.

    Neither Bokeh nor Panel has an option for response headers, so they are set where
    Tornado resets the headers of each response (``RequestHandler.clear``: on creation
    and before an error page), which every handler, Bokeh's and Panel's alike, inherits."""
    from tornado.web import RequestHandler

    if getattr(RequestHandler.clear, "_security_headers", False):
        return
    reset = RequestHandler.clear

    def clear(self):
        reset(self)
        for name, value in SECURITY_HEADERS.items():
            self.set_header(name, value)
        _drop_empty_session_id(self)

    clear._security_headers = True
    RequestHandler.clear = clear


def _drop_empty_session_id(handler) -> None:
    """A ``bokeh-session-id`` in the address that Bokeh reads as empty makes it raise
    "Session ID must not be empty" and answer 500; without it the page gets a new session,
    as for any address without one. Bokeh reads the last value as Tornado's
    ``get_argument`` gives it: control characters made spaces, then stripped (so
    ``?bokeh-session-id=%00`` is empty too)."""
    from tornado.web import RequestHandler

    request = getattr(handler, "request", None)
    control = RequestHandler._remove_control_chars_regex
    for args in (getattr(request, "query_arguments", None), getattr(request, "arguments", None)):
        values = args.get("bokeh-session-id") if args is not None else None
        if not values:
            continue
        last = values[-1]
        if isinstance(last, bytes):
            last = last.decode("utf-8", errors="replace")
        if not control.sub(" ", last).strip():
            del args["bokeh-session-id"]


def answer_busy_before_building() -> None:
    """Answer a page request with ``app.opening.BUSY_HTML`` when its client has no room in
    the page gate (``PageGate.has_room``), before Panel makes a session for it (once per
    process). Panel's page handler (``panel.io.server.DocHandler``) has no hook before its
    session is made, so its ``get`` is wrapped; the page script keeps its own check (a
    Panel busy page) for a server without these hooks."""
    from panel.io.server import DocHandler

    from app.opening import BUSY_HTML
    from app.pages import page_gate

    if getattr(DocHandler.get, "_busy_first", False):
        return
    build = DocHandler.get

    async def get(self, *args, **kwargs):
        if not page_gate().has_room(self.request.remote_ip):
            self.set_header("Cache-Control", "no-store")
            self.set_header("Content-Type", "text/html; charset=UTF-8")
            self.write(BUSY_HTML)
            return None
        return await build(self, *args, **kwargs)

    get._busy_first = True
    DocHandler.get = get


def on_server_loaded(server_context):
    guard_query_parsing()
    add_security_headers()
    answer_busy_before_building()
    start_warm_up()
