"""Health check of a served dashboard: ``python -m app.healthcheck [BASE_URL] [--timeout S]``.

Exit 0 when both hold, else 1 with the reason on stderr:

1. Panel's liveness endpoint ``BASE_URL/liveness?endpoint=/app`` answers 200 (the server
   is up and its event loop responds);
2. a real session of ``/app`` (a Bokeh client, as a browser would open it) receives the
   dashboard: a document titled ``TITLE``, which, once the client says it has the page
   (the browser's ``document_ready``), gets the dashboard's root (CSS class ``dashboard``)
   within ``--timeout`` (the server sends the dashboard only then, ``app.opening``).
   Panel answers the liveness endpoint with 200 even when the app raises (it shows an
   error page instead), so this second step is what makes a broken app unhealthy.

``BASE_URL`` defaults to ``http://127.0.0.1:5006`` (include a ``--prefix`` if the server
has one). The Dockerfile's HEALTHCHECK runs this module.
"""
from __future__ import annotations

import sys
import time
import urllib.error
import urllib.request

TITLE = "Micropillar friction explorer"
DEFAULT_URL = "http://127.0.0.1:5006"


def check(base_url: str = DEFAULT_URL, timeout: float = 25.0) -> str | None:
    """None when the dashboard is healthy, else why not."""
    base = base_url.rstrip("/")
    deadline = time.monotonic() + timeout
    try:
        with urllib.request.urlopen(f"{base}/liveness?endpoint=/app", timeout=timeout) as r:
            if r.status != 200:
                return f"liveness answered {r.status}"
    except (urllib.error.URLError, OSError) as error:
        return f"liveness endpoint unreachable: {error}"
    try:
        doc = open_dashboard(base, timeout=max(deadline - time.monotonic(), 1.0))
    except TimeoutError:
        return f"/app did not send the dashboard within {timeout:g} s: see the server log"
    except Exception as error:  # noqa: BLE001 -- any failure to open a session is unhealthy
        return f"no session of /app: {type(error).__name__}: {error}"
    if doc.title != TITLE or not has_dashboard(doc):
        return (f"/app did not build the dashboard (title {doc.title!r}, "
                f"{len(doc.roots)} roots): see the server log")
    return None


def has_dashboard(doc) -> bool:
    """Whether ``doc`` holds the dashboard's root (CSS class ``DASHBOARD_CLASS``)."""
    from app.views.page import DASHBOARD_CLASS  # not before the liveness step: the check
    # must answer even when the page cannot be imported
    return any(DASHBOARD_CLASS in (getattr(m, "css_classes", None) or ()) for m in doc.models)


def open_dashboard(base_url: str, query: str = "", timeout: float = 25.0):
    """Open ``base_url/app`` + ``query`` as a browser does -- the page, its websocket, the
    document, then ``document_ready`` -- and return the page's Bokeh document once the
    dashboard has arrived in it (or the document as sent, when it is not the explorer's
    page). The session is opened with a token of its own (``bokeh.util.token``), so no
    page is fetched. Raises ``TimeoutError`` after ``timeout`` seconds. (Bokeh's synchronous client,
    ``pull_session``, drops the messages that arrive while it waits for a reply, so it
    never sees the dashboard.)"""
    import asyncio

    async def bounded():
        return await asyncio.wait_for(_open(base_url.rstrip("/"), query, timeout), timeout)
    try:
        return asyncio.run(bounded())
    except asyncio.TimeoutError as error:
        raise TimeoutError(f"no dashboard within {timeout:g} s") from error


async def _open(base: str, query: str, timeout: float):
    from urllib.parse import parse_qs

    # The page's model types, registered so the client can read the page: Panel's, and
    # the app's own (a Bokeh document naming a type the client lacks cannot be opened).
    import panel  # noqa: F401
    import app.views  # noqa: F401  (the player's frame, the page's behaviour component)
    from bokeh.client.websocket import WebSocketClientConnectionWrapper
    from bokeh.document import Document
    from bokeh.document.events import MessageSentEvent
    from bokeh.events import DocumentReady
    from bokeh.protocol import Protocol
    from bokeh.protocol.receiver import Receiver
    from bokeh.util.token import generate_jwt_token, generate_session_id
    from tornado.httpclient import HTTPRequest
    from tornado.websocket import websocket_connect

    # A session of its own, as Bokeh's clients open one (``bokeh.util.token``): the
    # page's arguments travel in the token, as Bokeh's page handler puts them there.
    arguments = {k: [v.encode() for v in vs]
                 for k, vs in parse_qs(query.lstrip("?"), keep_blank_values=True).items()}
    token = generate_jwt_token(generate_session_id(), extra_payload={
        "headers": {}, "cookies": {}, "arguments": arguments})
    doc = Document()
    url = base.replace("http", "ws", 1) + "/app/ws"
    socket = await websocket_connect(HTTPRequest(url, request_timeout=timeout),
                                     subprotocols=["bokeh", token],
                                     max_message_size=50 * 2**20)
    connection, protocol = WebSocketClientConnectionWrapper(socket), Protocol()
    receiver = Receiver(protocol)

    async def read():
        while True:
            fragment = await socket.read_message()
            if fragment is None:
                raise ConnectionError("the server closed the page's connection")
            message = await receiver.consume(fragment)
            if message is not None:
                return message
    try:
        await read()  # the server's ACK
        await protocol.create("PULL-DOC-REQ").send(connection)
        while (reply := await read()).msgtype != "PULL-DOC-REPLY":
            if reply.msgtype == "ERROR":
                raise ConnectionError(f"server error: {reply.content.get('text')}")
        reply.push_to_document(doc)
        if doc.title != TITLE:
            return doc
        ready = MessageSentEvent(doc, "bokeh_event", DocumentReady())
        await protocol.create("PATCH-DOC", [ready]).send(connection)
        while not has_dashboard(doc):
            message = await read()
            if message.msgtype == "PATCH-DOC":
                message.apply_to_document(doc)
        return doc
    finally:
        socket.close()


def main(argv=None) -> int:
    import argparse

    parser = argparse.ArgumentParser(prog="python -m app.healthcheck",
                                     description=__doc__.split("\n")[0])
    parser.add_argument("base_url", nargs="?", default=DEFAULT_URL)
    parser.add_argument("--timeout", type=float, default=25.0,
                        help="seconds for the whole check (default 25)")
    args = parser.parse_args(argv)
    problem = check(args.base_url, args.timeout)
    if problem:
        print(f"unhealthy: {problem}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
