"""Bokeh server: an empty ``bokeh-session-id`` in a page's address answers 500.

Bokeh (3.9.2, served by Panel 1.9.4 or ``bokeh serve``) reads the ``bokeh-session-id``
argument of a page request and, when it is empty -- ``?bokeh-session-id=``, or only control
characters and spaces such as ``%00`` or ``%20``, which Tornado's ``get_argument`` turns
into spaces and strips -- raises "Session ID must not be empty" and answers
``500 Internal Server Error`` with a traceback in the log. Expected: the argument ignored
(a new session, as for an address without one) or a 400.

Run: ``python docs/upstream/empty_session_id.py`` (prints the status of each address).
Workaround in this project: ``app/edge.py`` (``drop_unreadable_session_id``).
"""
import panel as pn

from harness import served, status


def page():
    return pn.pane.Markdown("hello")


if __name__ == "__main__":
    with served(page) as url:
        for query in ("", "?bokeh-session-id=", "?bokeh-session-id=%00",
                      "?bokeh-session-id=%20"):
            print(f"GET /app{query or ' (no argument)'}: {status(url + query)}")
