"""Fixtures for the browser tests: a served dashboard and a headless Chromium page.

The dashboard is served with ``panel serve app`` from the repository root on a free port;
Chromium is Debian's ``/usr/bin/chromium`` driven by Playwright's sync API.

Where Chromium or Playwright is missing the tests skip with the reason, except in CI
(``CI`` or ``MICROPILLAR_REQUIRE_BROWSER`` set): there they fail instead.

The browser and the server live as long as this package's tests (scope "package"):
Playwright's sync API keeps an event loop running in the main thread while it is open,
which would break the asyncio code of later test modules.

Artifacts (``artifacts/`` at the repository root): ``dashboard.png`` (the default page),
``panel-serve.log`` (the server's log of the last run; with two xdist workers serving, the
log of the one that finished last) and, for a failed test,
``failed-<test>.png`` with ``failed-<test>.console.txt``. ``MICROPILLAR_BROWSER_APP``
serves another app folder instead of ``app`` (to try the harness itself).
"""
from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest

from .page_tools import screenshot
from .serving import CHROMIUM, ROOT, VIEWPORT, ServerError, launch_chromium, serve_app

ARTIFACTS = ROOT / "artifacts"
APP_DIR = os.environ.get("MICROPILLAR_BROWSER_APP", "app")  # another app, to try the harness
SERVER_START_TIMEOUT = 60.0
# Tracebacks the server logs when a closed page still had messages on their way: the
# page was closed by the test, not broken by the app.
CLOSED_CONNECTION_ERRORS = ("tornado.iostream.StreamClosedError",
                            "tornado.websocket.WebSocketClosedError")
#: ... and Bokeh's check, when a closed page's last messages (its time zone, sent as it
#: leaves) reach a connection whose session it has already let go.
SESSION_GONE = "assert self._session is not None"


def browser_required() -> bool:
    """True in CI: a missing browser is then a failure, never a skip."""
    flag = os.environ.get("MICROPILLAR_REQUIRE_BROWSER", "").strip().lower()
    ci = os.environ.get("CI", "").strip().lower()
    return flag not in ("", "0", "false", "no") or ci not in ("", "0", "false", "no")


def unavailable(reason: str):
    """A missing browser: a failure in CI, a skip on a developer's machine."""
    if browser_required():
        pytest.fail(f"browser tests are required here (CI / MICROPILLAR_REQUIRE_BROWSER) "
                    f"but {reason}", pytrace=False)
    pytest.skip(reason)


def pytest_collection_modifyitems(config, items):
    """Every test in this folder carries the ``browser`` marker."""
    here = Path(__file__).parent
    for item in items:
        if Path(str(item.fspath)).parent == here:
            item.add_marker(pytest.mark.browser)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Keep each phase's report on the test item, so fixtures can see a failure."""
    outcome = yield
    report = outcome.get_result()
    setattr(item, f"rep_{report.when}", report)


@pytest.fixture(scope="session")
def artifacts_dir() -> Path:
    """``artifacts/`` at the repository root; failure files of an earlier run are removed
    (once per run: with the browser tests on two xdist workers, the second to start must
    not remove the first one's)."""
    ARTIFACTS.mkdir(exist_ok=True)
    run = os.environ.get("PYTEST_XDIST_TESTRUNUID") or str(os.getpid())
    marker = ARTIFACTS / ".run"
    if not marker.exists() or marker.read_text(encoding="utf-8") != run:
        marker.write_text(run, encoding="utf-8")
        for old in ARTIFACTS.glob("failed-*"):
            old.unlink(missing_ok=True)
    return ARTIFACTS


@pytest.fixture(scope="package")
def server_log(tmp_path_factory, artifacts_dir):
    """The server's log: private to this session, copied to artifacts/ at its end."""
    path = tmp_path_factory.mktemp("panel-serve") / "panel-serve.log"
    path.touch()
    yield path
    shutil.copyfile(path, artifacts_dir / "panel-serve.log")


@pytest.fixture(scope="package")
def app_server(browser, server_log):
    """``panel serve app`` on a free loopback port; yields the base URL (no trailing /).

    It asks for ``browser`` first, so that without a browser nothing is served.
    """
    try:
        with serve_app(server_log, app_dir=APP_DIR, timeout_s=SERVER_START_TIMEOUT) as base:
            yield base
    except ServerError as error:
        pytest.fail(str(error), pytrace=False)


@pytest.fixture(scope="package")
def app_url(app_server) -> str:
    return f"{app_server}/{Path(APP_DIR).name}"


@pytest.fixture(scope="package")
def browser():
    """Debian's headless Chromium, launched by Playwright."""
    if not Path(CHROMIUM).exists():
        unavailable(f"{CHROMIUM} is missing (install Debian's package: apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        unavailable("Playwright is not installed (pip install -e \".[test]\")")
    with sync_playwright() as playwright:
        chromium = launch_chromium(playwright)
        yield chromium
        chromium.close()


class PageLog:
    """Console messages and uncaught page errors of one page, and the server's tracebacks
    (from ``artifacts/panel-serve.log``) since the page was opened."""

    def __init__(self):
        self.messages: list[tuple[str, str]] = []
        self.page_errors: list[str] = []
        self.server_log: Path | None = None
        self.server_offset = 0

    def watch_server(self, path: Path) -> None:
        self.server_log, self.server_offset = path, path.stat().st_size

    def server_errors(self) -> list[str]:
        """The last line of each traceback the server logged since ``watch_server``."""
        if self.server_log is None:
            return []
        with open(self.server_log, "rb") as log:
            log.seek(self.server_offset)
            lines = log.read().decode("utf-8", errors="replace").splitlines()
        errors = []
        for i, line in enumerate(lines):
            if line.startswith("Traceback"):
                end = next((j for j in range(i + 1, len(lines))
                            if lines[j] and not lines[j][0].isspace()), None)
                last = line if end is None else lines[end]
                gone = last == "AssertionError" and any(SESSION_GONE in l for l in lines[i:end])
                if not (last.startswith(CLOSED_CONNECTION_ERRORS) or gone):
                    errors.append(last)
        return errors

    def on_console(self, message):
        text = message.text
        url = (message.location or {}).get("url")
        if message.type == "error" and url and url not in text:
            text = f"{text} ({url})"
        self.messages.append((message.type, text))

    def on_request_failed(self, request):
        self.messages.append(("requestfailed", f"{request.url}: {request.failure}"))

    def on_page_error(self, error):
        self.page_errors.append(str(error))

    @property
    def errors(self) -> list[str]:
        """Console errors and page errors, as text."""
        return ([text for kind, text in self.messages if kind == "error"]
                + [f"uncaught: {text}" for text in self.page_errors]
                + [f"server: {text}" for text in self.server_errors()])

    def dump(self) -> str:
        return "\n".join([f"[{kind}] {text}" for kind, text in self.messages]
                         + [f"[pageerror] {text}" for text in self.page_errors]
                         + [f"[server] {text}" for text in self.server_errors()])


def _artifact_name(nodeid: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", nodeid.split("::", 1)[-1])[:120]


@pytest.fixture
def page_log() -> PageLog:
    return PageLog()


@pytest.fixture
def page(browser, app_server, server_log, page_log, request, artifacts_dir):
    """A fresh 1280x720 page; on failure a screenshot and the console go to artifacts/."""
    page_log.watch_server(server_log)
    context = browser.new_context(viewport=VIEWPORT)
    context.set_default_timeout(30_000)
    new_page = context.new_page()
    new_page.on("console", page_log.on_console)
    new_page.on("pageerror", page_log.on_page_error)
    new_page.on("requestfailed", page_log.on_request_failed)
    yield new_page
    failed = any(getattr(getattr(request.node, f"rep_{when}", None), "failed", False)
                 for when in ("setup", "call"))
    if failed:
        name = _artifact_name(request.node.nodeid)
        try:
            screenshot(new_page, artifacts_dir / f"failed-{name}.png")
        except Exception as error:  # a crashed page cannot be photographed
            print(f"no failure screenshot: {error}")
        (artifacts_dir / f"failed-{name}.console.txt").write_text(page_log.dump(),
                                                                 encoding="utf-8")
    context.close()
