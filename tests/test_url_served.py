"""Hostile URLs against the served dashboard (``slow``; loopback only): fuzzed GETs of /app
never answer 500 and leave no traceback in the server log; a session opened with hostile
arguments shows its notice while the next clean session has the defaults (no state leaks
between sessions); over-long numbers break nothing; every response forbids framing and
sniffing. The query parser alone: tests/test_url_fuzz.py (its strategies are used here).
"""
import html
import http.client
import itertools
import math
import os
import time
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from app.state import ExplorerState
from test_url_fuzz import KEY, LONG_DIGITS, ROOT, TEXT, _Tags

# --------------------------------------------------------------------------- served

SERVED = settings(max_examples=16, deadline=None, database=None, phases=(Phase.generate,),
                  suppress_health_check=list(HealthCheck))


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``panel serve app`` on a free loopback port: (base URL, log path)."""
    from browser.serving import ServerError, serve_app

    log = tmp_path_factory.mktemp("url-fuzz") / "panel-serve.log"
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("PYTHONPATH", path)  # the server imports the package from this checkout
        try:
            with serve_app(log, timeout_s=90.0) as base:
                yield base, log
        except ServerError as error:
            pytest.fail(str(error), pytrace=False)


_SOURCES = itertools.count(1)


def _get(url: str) -> tuple[int, str]:
    """GET ``url`` from a loopback address of its own (127.0.1.N): each request is a new
    client to the server, so none is turned away with the busy page of a client whose
    earlier pages were never opened (``app.pages.PageGate``), and each runs the page."""
    status, _headers, body = _fetch(url, _new_source())
    return status, body


def _new_source() -> str:
    n = next(_SOURCES)
    return f"127.0.{1 + n // 250}.{1 + n % 250}"


def _fetch(url: str, source: str) -> tuple[int, dict, str]:
    """GET ``url`` from the loopback address ``source``, redirects not followed: (status,
    headers in lower case, body)."""
    parts = urllib.parse.urlsplit(url)
    connection = http.client.HTTPConnection(parts.hostname, parts.port, timeout=60,
                                            source_address=(source, 0))
    try:
        connection.request("GET", parts.path + (f"?{parts.query}" if parts.query else ""))
        response = connection.getresponse()
        headers = {k.lower(): v for k, v in response.getheaders()}
        return response.status, headers, response.read().decode("utf-8", "replace")
    finally:
        connection.close()


def _tracebacks(log: Path) -> list[str]:
    text = log.read_text(encoding="utf-8", errors="replace")
    return [line for line in text.splitlines() if "Traceback" in line or " ERROR" in line]


RAW = st.sampled_from(["%zz", "%", "%%41", "%ED%A0%80", "%FF%FE", "%00", "&&&", "=&=", ";",
                       "k_r=1&k_r=nan&k_r=%F0%9F%92%A5", "theta0_deg=1e999", "F_N=-0",
                       "beta=self&beta=0", "tab=" + "x" * 3000, "a=" + "%25" * 500])


@pytest.mark.slow
@SERVED
@given(pairs=st.lists(st.tuples(KEY, TEXT), max_size=6), raw=st.lists(RAW, max_size=2))
def test_served_app_survives_fuzzed_queries(served, pairs, raw):
    base, log = served
    encoded = urllib.parse.urlencode([(k.encode("utf-8", "surrogatepass"),
                                       v.encode("utf-8", "surrogatepass")) for k, v in pairs])
    status, body = _get(f"{base}/app?" + "&".join([encoded, *raw]))
    assert status == 200, body[-2000:]
    assert "bokeh" in body.lower()
    assert _tracebacks(log) == []


@pytest.mark.slow
@pytest.mark.parametrize("query", ["bokeh-session-id=", "bokeh-session-id=%20&k_r=0.5",
                                   "bokeh-session-id=&bokeh-session-id=",
                                   "bokeh-session-id=%00", "bokeh-session-id=x&bokeh-session-id=",
                                   "bokeh-session-id=%01%1f%20",
                                   "bokeh-session-id=x&bokeh-session-id=%ED%A0%80",
                                   "bokeh-session-id=%FF%FE"])
def test_an_unreadable_session_id_gets_a_new_session(served, query):
    """Found by the fuzzing above: Bokeh answered 500 ("Session ID must not be empty"), and
    Tornado 400 to a session id that is not UTF-8."""
    base, log = served
    status, body = _get(f"{base}/app?{query}")
    assert status == 200 and "bokeh" in body.lower(), body[-2000:]
    assert _tracebacks(log) == []


def _slider(sliders: dict, name: str) -> float:
    found = [value for title, value in sliders.items() if title.startswith(name)]
    assert len(found) == 1, f"no single slider titled {name!r} among {sorted(sliders)}"
    return found[0]


def _session_view(base: str, arguments: dict):
    """Open a session as a browser would (websocket, then ``document_ready``) and read
    what the page shows: the notice (its HTML and visibility) and the values of the log
    sliders by title."""
    from urllib.parse import urlencode

    from bokeh.models import Slider

    from app.healthcheck import open_dashboard
    from app.pages import UNOPENED_PAGE_S

    # Pages the fuzz tests requested and never opened hold this client's page gate for
    # UNOPENED_PAGE_S: until then the server answers with its short "busy" page.
    query = "?" + urlencode(arguments, doseq=True)
    deadline = time.monotonic() + UNOPENED_PAGE_S + 10
    while True:
        doc = open_dashboard(base, query, timeout=60)
        notices = [m for m in doc.models if any(
            "page-notice" in c for c in (getattr(m, "css_classes", None) or []))]
        sliders = {m.title.split()[0]: m.value for m in doc.models
                   if isinstance(m, Slider) and m.title}
        if notices or time.monotonic() > deadline:
            break
        time.sleep(1.0)
    assert len(notices) == 1, "the page has one notice area (css class page-notice)"
    return notices[0].visible, html.unescape(notices[0].text or ""), sliders


@pytest.mark.slow
def test_hostile_session_shows_notices_and_does_not_leak(served):
    base, log = served
    hostile = {"k_r": "<img src=\"x\" onerror=\"alert(1)\">", "F_N": "2", "theta0_deg": "nan",
               "tab": "[x](http://e.com)", "zz<b>": "1", "beta": "1e999", "regime": "\u202e"}
    visible, notice, sliders = _session_view(base, hostile)
    assert visible
    tags = _Tags()
    tags.feed(notice)
    assert {t for t, _ in tags.tags} <= {"p", "br"}, notice  # no injected elements
    for key in ("k_r", "theta0_deg", "tab", "zz", "beta", "regime"):
        assert key in notice, key
    assert "'2'" not in notice  # the good value is used, not reported
    defaults = ExplorerState()
    shown = {"k_r": math.log10(defaults.k_r), "F_N": math.log10(2.0), "θ₀": defaults.theta0}
    for name, value in shown.items():  # log sliders hold log10 of the value
        assert _slider(sliders, name) == pytest.approx(value, abs=1e-9), name
    # A clean session afterwards: defaults, no notice (nothing leaked from the last one).
    visible, notice, sliders = _session_view(base, {})
    assert not visible and notice.strip() == "", notice
    shown = {"k_r": math.log10(defaults.k_r), "F_N": math.log10(defaults.F_N),
             "θ₀": defaults.theta0}
    for name, value in shown.items():
        assert _slider(sliders, name) == pytest.approx(value, abs=1e-9), name
    time.sleep(0.5)  # let the server log the closed sessions
    assert _tracebacks(log) == []


SECURITY_HEADERS = {"x-frame-options": "SAMEORIGIN", "x-content-type-options": "nosniff"}


@pytest.mark.slow
@pytest.mark.parametrize("path", ["/app", "/app?k_r=0.5", "/liveness?endpoint=/app",
                                  "/static/js/bokeh.min.js", "/app/static/busy.html",
                                  "/no-such-page"])
def test_every_response_forbids_framing_and_sniffing(served, path):
    base, _log = served
    try:
        response = urllib.request.urlopen(base + path, timeout=60)
    except urllib.error.HTTPError as error:  # the 404 page carries them too
        response = error
    with response:
        headers = {k.lower(): v for k, v in response.headers.items()}
    for name, value in SECURITY_HEADERS.items():
        assert headers.get(name) == value, (path, name, headers)
    assert "frame-ancestors 'self'" in headers.get("content-security-policy", "")


@pytest.mark.slow
def test_over_long_number_in_the_address_breaks_nothing(served):
    """``?x=`` + 4301 digits made Panel's query parser raise while building the page:
    the page drew, but without its address model (UnknownReferenceError afterwards)."""
    base, log = served
    for query in (f"x={LONG_DIGITS}", f"k_r={LONG_DIGITS}&F_N=2", "y=%C2%B2"):
        status, body = _get(f"{base}/app?{query}")
        assert status == 200 and "bokeh" in body.lower()
    visible, notice, sliders = _session_view(base, {"k_r": LONG_DIGITS, "F_N": "2"})
    assert visible and "k_r" in notice and "too long" in notice
    assert _slider(sliders, "F_N") == pytest.approx(math.log10(2.0), abs=1e-9)
    time.sleep(0.5)
    text = log.read_text(encoding="utf-8", errors="replace")
    assert _tracebacks(log) == [] and "UnknownReferenceError" not in text


@pytest.mark.slow
def test_a_client_whose_pages_are_not_opened_is_sent_to_the_busy_page(served):
    """Past ``MAX_UNOPENED_PAGES`` pages nobody opened, a client's next page request is
    redirected to the busy page (no session made), which names the page to go back to."""
    from app.opening import BUSY_HTML, busy_address
    from app.pages import MAX_UNOPENED_PAGES

    base, _log = served
    source, query = _new_source(), "/app?F_N=2&theta0_deg=40"
    for _ in range(MAX_UNOPENED_PAGES):
        status, _headers, body = _fetch(base + query, source)
        assert status == 200 and '"token"' in body  # a page with its session
    status, headers, body = _fetch(base + query, source)
    assert status == 302 and '"token"' not in body, (status, body[:300])
    assert headers["location"] == busy_address("/app", query)
    assert headers["cache-control"] == "no-store"
    status, headers, body = _fetch(base + headers["location"], source)
    assert status == 200 and body == BUSY_HTML
    assert headers["content-type"].startswith("text/html")
    status, _headers, body = _fetch(base + query, _new_source())
    assert status == 200 and '"token"' in body  # another client still gets its page
