"""Serving a plain Panel app on a free loopback port and opening it in headless Chromium,
and a text component in a document timed as its text changes, for the reproducers in
this folder (each runs as ``python docs/upstream/<name>.py``)."""
from __future__ import annotations

import contextlib
import socket
import time
import urllib.error
import urllib.request

import panel as pn

CHROMIUM = "/usr/bin/chromium"  # Debian's; Playwright's own browser works as well
CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"]


def status(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=30) as response:
            return response.status
    except urllib.error.HTTPError as error:
        return error.code


@contextlib.contextmanager
def served(app):
    """``app`` (a function making the page) served at ``/app``: yields the page's URL."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = pn.serve({"app": app}, port=port, address="127.0.0.1", threaded=True,
                      show=False, start=True)
    url = f"http://127.0.0.1:{port}/app"
    try:
        for _ in range(150):
            try:
                status(url)
                break
            except urllib.error.URLError:
                time.sleep(0.2)
        yield url
    finally:
        server.stop()


@contextlib.contextmanager
def browser_page():
    """A Playwright page in headless Chromium whose errors are collected in ``.errors``."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        try:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS)
        except Exception:
            browser = p.chromium.launch(args=CHROMIUM_FLAGS)
        page = browser.new_page()
        page.errors = []
        page.on("pageerror", lambda error: page.errors.append(str(error)))
        page.on("console", lambda m: page.errors.append(m.text) if m.type == "error" else None)
        try:
            yield page
        finally:
            browser.close()


def pages_failing(app, error: str, rounds: int) -> int:
    """Open ``app``'s page ``rounds`` times; print and count the pages whose browser
    logged an error containing ``error``."""
    failed = 0
    with served(app) as url, browser_page() as browser:
        for _ in range(rounds):
            browser.errors.clear()
            browser.goto(url)
            time.sleep(3.0)
            found = [e for e in browser.errors if error in e]
            failed += bool(found)
            print(found[:1] or "page fine")
    print(f"REPRODUCED on {failed} of {rounds} pages" if failed
          else f"not reproduced on {rounds} pages")
    return failed


def live_text():
    """A one-parameter custom component (a text written in place) in a document, as the
    page has it: (the component, its document)."""
    import param
    from bokeh.document import Document
    from panel.custom import JSComponent

    class Live(JSComponent):
        text = param.String(default="")
        _esm = "export function render({ model, el }) { el.textContent = model.text }"

    doc, live = Document(), Live()
    doc.add_root(live.get_root(doc))
    return live, doc


def text_updates_ms(live, n: int) -> list[float]:
    """Milliseconds of each of ``n`` changes of ``live``'s text."""
    times = []
    for i in range(n):
        start = time.perf_counter()
        live.text = f"update {i}"
        times.append((time.perf_counter() - start) * 1e3)
    return times
