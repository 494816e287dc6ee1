"""Helpers of the offline explorer's browser tests: the packed file, a page of it opened
from file:// with every request that is not file: refused, and what the page shows."""
from __future__ import annotations

import pytest

from app.offline.pack import write
from model.controls import CONTROLS

from .serving import VIEWPORT

__all__ = ["DRAWN", "UNIFORM", "POLAR", "DEFAULTS", "Offline", "explorer_file", "offline"]

DRAWN = "Number(document.documentElement.getAttribute('data-drawn') || 0)"
UNIFORM = "Number(document.documentElement.getAttribute('data-uniform') || 0)"
DEFAULTS = {k: CONTROLS[k].default for k in ("k_r", "k_theta", "F_N", "theta0_deg")}
POLAR = "Number(document.documentElement.getAttribute('data-polar') || 0)"


@pytest.fixture(scope="module")
def explorer_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("offline") / "explorer.html"
    write(path)
    return path


class Offline:
    """One page of the offline explorer: requests seen, console errors."""

    def __init__(self, browser, path):
        self.path = path
        self.context = browser.new_context(viewport=VIEWPORT)
        self.context.set_default_timeout(30_000)
        self.requests: list[str] = []
        self.errors: list[str] = []
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.on("pageerror", lambda e: self.errors.append(f"uncaught: {e}"))

    def _route(self, route):
        url = route.request.url
        self.requests.append(url)
        if url.startswith("file:"):
            route.continue_()
        else:
            route.abort()

    def open(self, fragment: str = "") -> None:
        self.page.goto(self.path.as_uri() + fragment)
        self.page.wait_for_function(f"{DRAWN} >= 1")

    def data(self, name: str) -> dict:
        """A data source's columns (figures may share a source's name)."""
        return self.page.evaluate(
            f"(() => {{ const m = [...Bokeh.documents[0].all_models].find((m) => m.name === '{name}'"
            " && m.data !== undefined && m.selected !== undefined);"
            " return Object.fromEntries(Object.entries(m.data).map(([k, v]) => [k, Array.from(v)])); })()")

    def model(self, name: str, attr: str):
        return self.page.evaluate(
            f"[...Bokeh.documents[0].all_models].find((m) => m.name === '{name}' && m.data === undefined"
            f" && m.renderers === undefined).{attr}")

    def text(self, name: str) -> str:
        return self.model(name, "text")

    def foreign_requests(self) -> list[str]:
        return [u for u in self.requests if not u.startswith("file:")]


@pytest.fixture
def offline(browser, explorer_file):
    page = Offline(browser, explorer_file)
    yield page
    page.context.close()
