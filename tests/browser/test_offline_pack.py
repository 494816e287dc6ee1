"""The offline explorer (``micropillar pack``) opened from file:// in headless Chromium with
every request that is not file: refused: it draws, computes in the page and keeps its
state in the URL fragment (docs/offline.md)."""
from __future__ import annotations

import math

import pytest

from app.offline.pack import write
from model import Params, simulate_support
from model.controls import CONTROLS

from .serving import VIEWPORT

DRAWN = "Number(document.documentElement.getAttribute('data-drawn') || 0)"
DEFAULTS = {k: CONTROLS[k].default for k in ("k_r", "k_theta", "F_N", "theta0_deg")}


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
        return self.page.evaluate(
            f"(() => {{ const d = Bokeh.documents[0].get_model_by_name('{name}').data;"
            " return Object.fromEntries(Object.entries(d).map(([k, v]) => [k, Array.from(v)])); })()")

    def text(self, name: str) -> str:
        return self.page.evaluate(f"Bokeh.documents[0].get_model_by_name('{name}').text")

    def foreign_requests(self) -> list[str]:
        return [u for u in self.requests if not u.startswith("file:")]


@pytest.fixture
def offline(browser, explorer_file):
    page = Offline(browser, explorer_file)
    yield page
    page.context.close()


def test_opens_from_file_with_no_request_and_no_error(offline):
    offline.open()
    orbit = offline.data("orbit-source")
    assert len(orbit["x"]) > 100  # the orbit was computed in the page
    assert offline.page.evaluate("JSON.stringify(explorer.state)") == (
        '{"tab":"support","k_r":3,"k_theta":0.01,"F_N":1,"theta0_deg":90}')
    want = simulate_support(Params(k_r=3, k_theta=0.01)).F_mean[0]
    got = offline.page.evaluate("explorer.result.F_mean_x")
    assert got == pytest.approx(want, rel=1e-4)
    assert "0.943" in offline.text("headline")  # F_T,x/(mu0 F_N) of the pendulum at 90 deg
    assert offline.foreign_requests() == []
    assert offline.errors == []


def test_a_slider_key_press_changes_the_plotted_data(offline):
    offline.open()
    before = offline.data("orbit-source")
    drawn = offline.page.evaluate(DRAWN)
    handle = offline.page.locator(".noUi-handle").nth(3)  # theta0, the fourth slider
    handle.focus()
    for _ in range(5):
        handle.press("ArrowLeft")
    offline.page.wait_for_function(f"{DRAWN} > {drawn} && explorer.state.theta0_deg === 85")
    offline.page.wait_for_function("!Bokeh.documents[0].get_model_by_name('status').text"
                                   ".startsWith('computing')")
    after = offline.data("orbit-source")
    assert after["x"] != before["x"]
    assert "theta0_deg=85" in offline.page.evaluate("location.hash")
    # What is drawn is the kernel's orbit for the new state.
    want = offline.page.evaluate(
        "Array.from(explorer.simulate({k_r: 3, k_theta: 0.01, F_N: 1, theta0: 85 * Math.PI / 180,"
        " samples: 1500}).series.x)")
    assert after["x"] == pytest.approx(want, abs=1e-12)
    assert offline.errors == []


def test_a_link_opens_in_its_state(offline):
    offline.open("#k_r=0.03&k_theta=0.03&F_N=3&theta0_deg=120")
    state = offline.page.evaluate("explorer.state")
    assert state == {"tab": "support", "k_r": 0.03, "k_theta": 0.03, "F_N": 3, "theta0_deg": 120}
    sliders = offline.page.evaluate(
        "['k_r', 'k_theta', 'F_N', 'theta0_deg'].map(k => "
        "Bokeh.documents[0].get_model_by_name('slider-' + k).value)")
    assert sliders == pytest.approx([math.log10(0.03), math.log10(0.03), math.log10(3), 120])
    want = simulate_support(Params(k_r=0.03, k_theta=0.03, F_N=3,
                                   theta0=math.radians(120))).F_mean[0]
    assert offline.page.evaluate("explorer.result.F_mean_x") == pytest.approx(want, rel=1e-3)
    assert offline.text("notice") == ""
    # A new fragment in the same page moves it too.
    drawn = offline.page.evaluate(DRAWN)
    offline.page.evaluate("location.hash = '#regime=slider&F_N=1&theta0_deg=90'")
    offline.page.wait_for_function(f"{DRAWN} > {drawn}")
    assert offline.page.evaluate("[explorer.state.k_r, explorer.state.k_theta]") == [0.01, 3]
    assert offline.errors == []


def test_a_bad_link_gets_a_notice_and_the_defaults(offline):
    offline.open("#k_r=banana&F_N=1e9&theta0_deg=45&tab=array&colour=red")
    state = offline.page.evaluate("explorer.state")
    assert state["k_r"] == DEFAULTS["k_r"] and state["F_N"] == DEFAULTS["F_N"]
    assert state["theta0_deg"] == 45  # the good value is kept
    notice = offline.text("notice")
    for part in ("k_r=banana", "F_N=1e9", "the array tab is not in the offline explorer yet",
                 "colour is not a setting"):
        assert part in notice, (part, notice)
    assert len(offline.data("orbit-source")["x"]) > 100  # never a blank page
    assert offline.errors == []
