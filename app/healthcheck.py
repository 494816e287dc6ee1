"""Health check of a served dashboard: ``python -m app.healthcheck [BASE_URL] [--timeout S]``.

Exit 0 when both hold, else 1 with the reason on stderr:

1. Panel's liveness endpoint ``BASE_URL/liveness?endpoint=/app`` answers 200 (the server
   is up and its event loop responds);
2. a real session of ``/app`` (a Bokeh client, as a browser would open it) receives the
   dashboard's page: a document titled ``TITLE`` with content. Panel answers the liveness
   endpoint with 200 even when the app raises (it shows an error page instead), so this
   second step is what makes a broken app unhealthy.

``BASE_URL`` defaults to ``http://127.0.0.1:5006`` (include a ``--prefix`` if the server
has one). The Dockerfile's HEALTHCHECK runs this module.
"""
from __future__ import annotations

import sys
import urllib.error
import urllib.request

TITLE = "Micropillar friction explorer"
DEFAULT_URL = "http://127.0.0.1:5006"


def check(base_url: str = DEFAULT_URL, timeout: float = 25.0) -> str | None:
    """None when the dashboard is healthy, else why not."""
    base = base_url.rstrip("/")
    try:
        with urllib.request.urlopen(f"{base}/liveness?endpoint=/app", timeout=timeout) as r:
            if r.status != 200:
                return f"liveness answered {r.status}"
    except (urllib.error.URLError, OSError) as error:
        return f"liveness endpoint unreachable: {error}"
    # The page's model types, registered so the client can read the page: Panel's, and
    # the app's own (a Bokeh document naming a type the client lacks cannot be opened).
    import panel  # noqa: F401
    import app.views  # noqa: F401  (the player's frame, the page's behaviour component)
    from bokeh.client import pull_session

    try:
        with pull_session(url=f"{base}/app") as session:
            doc = session.document
            title, roots = doc.title, len(doc.roots)
    except Exception as error:  # noqa: BLE001 -- any failure to open a session is unhealthy
        return f"no session of /app: {type(error).__name__}: {error}"
    if title != TITLE or roots == 0:
        return f"/app did not build the dashboard (title {title!r}, {roots} roots): see the server log"
    return None


def main(argv=None) -> int:
    import argparse

    parser = argparse.ArgumentParser(prog="python -m app.healthcheck",
                                     description=__doc__.split("\n")[0])
    parser.add_argument("base_url", nargs="?", default=DEFAULT_URL)
    parser.add_argument("--timeout", type=float, default=25.0,
                        help="seconds for the liveness request (default 25)")
    args = parser.parse_args(argv)
    problem = check(args.base_url, args.timeout)
    if problem:
        print(f"unhealthy: {problem}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
