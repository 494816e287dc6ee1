"""What the browser tests count as the server's errors (``conftest.PageLog``): every
traceback the server logged since the page opened, except a closed page's messages
arriving after its connection closed or let its session go."""
from .conftest import PageLog

SESSION_GONE = """error handling message
 message: Message 'PATCH-DOC' content: {'events': [{'kind': 'ModelChanged', 'attr': 'timezone'}]}
 error: AssertionError()
Traceback (most recent call last):
  File "bokeh/server/connection.py", line 65, in session
    assert self._session is not None
           ^^^^^^^^^^^^^^^^^^^^^^^^^
AssertionError
"""
CLOSED = """Traceback (most recent call last):
  File "tornado/websocket.py", line 1, in write_message
tornado.websocket.WebSocketClosedError
"""
REAL = """Traceback (most recent call last):
  File "app/views/support.py", line 1, in _draw
    assert data is not None
AssertionError
"""


def _errors(tmp_path, text: str) -> list[str]:
    path = tmp_path / "panel-serve.log"
    path.write_text("before the page\n", encoding="utf-8")
    log = PageLog()
    log.watch_server(path)
    with open(path, "a", encoding="utf-8") as out:
        out.write(text)
    return log.server_errors()


def test_a_closed_pages_late_messages_are_not_the_servers_errors(tmp_path):
    assert _errors(tmp_path, SESSION_GONE + CLOSED) == []


def test_any_other_traceback_is(tmp_path):
    assert _errors(tmp_path, SESSION_GONE + REAL + CLOSED) == ["AssertionError"]
    assert _errors(tmp_path, REAL.replace("AssertionError", "ValueError: bad")) == [
        "ValueError: bad"]
