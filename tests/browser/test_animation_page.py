"""The browser-side animations on standalone pages (no server): the array plays and N_c
changes, the live energy bars follow playback and balance, the keyboard shortcuts and the
labelled buttons work. Screenshots at 1280x720, 1920x1080 and 390x844 go to artifacts/.
"""
from __future__ import annotations

import pytest

from app.figures.animation_page import array_document, page_html, support_document
from model import REGIMES

SIZES = {"1280x720": (1280, 720), "1920x1080": (1920, 1080), "phone-390x844": (390, 844)}


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    folder = tmp_path_factory.mktemp("animation-pages")
    urls = {}
    doc, motion, _ = array_document(REGIMES["pendulum"])
    (folder / "array.html").write_text(page_html(doc), encoding="utf-8")
    urls["array"] = (folder / "array.html").as_uri()
    doc, result, _ = support_document(REGIMES["pendulum"])
    (folder / "support.html").write_text(page_html(doc), encoding="utf-8")
    urls["support"] = (folder / "support.html").as_uri()
    return urls, motion, result


@pytest.fixture
def open_page(browser):
    opened, errors = [], []

    def _open(url, size=(1280, 720)):
        context = browser.new_context(viewport={"width": size[0], "height": size[1]})
        page = context.new_page()
        page.on("pageerror", lambda e: errors.append(str(e)))
        # A console error names its source: a failed load says which file it missed.
        page.on("console", lambda m: errors.append(f"{m.text} ({m.location.get('url')})")
                if m.type == "error" else None)
        # Self-contained: the page asks for nothing but itself and inline data.
        page.on("request", lambda r: None if r.url == url or r.url.startswith("data:")
                else errors.append(f"requested {r.url[:200]}"))
        page.goto(url)
        page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0 "
                               "&& window.__mpf_players && Object.keys(window.__mpf_players).length")
        opened.append(context)
        return page

    yield _open
    for context in opened:
        context.close()
    assert not errors, errors


def _state(page, player):
    return page.evaluate("""(p) => {
        const d = Bokeh.documents[0];
        return {frame: d.get_model_by_name(p + "_frame").value,
                playing: d.get_model_by_name(p + "_play").active,
                speed: d.get_model_by_name(p + "_speed").value,
                loop: d.get_model_by_name(p + "_loop").active,
                slider: d.get_model_by_name(p + "_slider").value}; }""", player)


def _in_contact(page):
    return page.evaluate("""() => {
        const a = Bokeh.documents[0].get_model_by_name("array_supports").data.a;
        let n = 0; for (const v of a) if (Number.isFinite(v)) n += 1; return n; }""")


def test_array_plays_and_the_contact_count_changes(pages, open_page):
    urls, motion, _ = pages
    page = open_page(urls["array"])
    assert _state(page, "array_player")["frame"] == 0 and _in_contact(page) == 0
    page.get_by_role("button", name="▶ Play").click()
    counts = []
    for _ in range(12):
        page.wait_for_timeout(250)
        counts.append(_in_contact(page))
    state = _state(page, "array_player")
    assert state["playing"] and state["frame"] > 30, state
    assert len(set(counts)) >= 3, counts
    # What the page counts is the model's count at that frame.
    page.keyboard.press("Space")
    page.wait_for_timeout(300)
    state = _state(page, "array_player")
    assert not state["playing"]
    assert _in_contact(page) == int(motion.N_c[state["frame"]])
    live = page.evaluate("() => Bokeh.documents[0].get_model_by_name('array_live').data.t.length")
    assert live == state["frame"] + 1
    readout = page.evaluate("() => Bokeh.documents[0].get_model_by_name('array_readout').html")
    assert f"N_c = {int(motion.N_c[state['frame']])}</b>" in readout


def test_the_array_plays_on_while_its_slider_is_not_drawn_yet(pages, open_page):
    """A page sent in a patch is drawn over several turns: a player may start before its
    frame slider is drawn, whose view then throws on a new value (BokehJS). The animation
    plays on and no error reaches the page (``open_page`` fails on a page error)."""
    urls, _, _ = pages
    page = open_page(urls["array"])
    # The slider's view as before its first draw (render() makes its title element).
    page.evaluate("""() => { const m = Bokeh.documents[0].get_model_by_name("array_player_slider");
        Bokeh.index.find_one(m).title_el = undefined; }""")
    page.get_by_role("button", name="▶ Play").click()
    page.wait_for_function("() => Bokeh.documents[0].get_model_by_name('array_player_frame')"
                           ".value > 20", timeout=10_000)
    state = _state(page, "array_player")
    assert state["playing"] and state["slider"] > 0, state  # the model follows, drawn or not


def test_energy_bars_follow_playback_and_balance(pages, open_page):
    urls, _, result = pages
    page = open_page(urls["support"])
    read = "() => Bokeh.documents[0].get_model_by_name('energy_live_bars').data.top.slice()"
    before = page.evaluate(read)
    page.keyboard.press("Space")
    seen = []
    for _ in range(6):
        page.wait_for_timeout(300)
        seen.append(page.evaluate(read))
    page.keyboard.press("Space")
    assert before[0] == 0.0
    assert len({round(s[0], 9) for s in seen}) >= 4, seen  # W grows while playing
    for tops in seen:
        # W (left bar) = D_x + D_y + U_el + K (top of the stack), Eq. (12) at every tau.
        assert tops[4] == pytest.approx(tops[0], rel=1e-3, abs=1e-4 * result.W)


def test_keyboard_shortcuts(pages, open_page):
    urls, _, _ = pages
    page = open_page(urls["array"])
    page.keyboard.press("ArrowRight")
    page.keyboard.press("ArrowRight")
    page.wait_for_timeout(150)
    assert _state(page, "array_player")["frame"] == 2
    page.keyboard.press("ArrowLeft")
    page.wait_for_timeout(150)
    s = _state(page, "array_player")
    assert s["frame"] == 1 and s["slider"] == 1
    page.keyboard.press("ArrowUp")
    assert _state(page, "array_player")["speed"] == "2"
    page.keyboard.press("ArrowDown")
    page.keyboard.press("ArrowDown")
    assert _state(page, "array_player")["speed"] == "0.5"
    loop = _state(page, "array_player")["loop"]
    page.keyboard.press("l")  # a letter typed away from the player does nothing (WCAG 2.1.4)
    assert _state(page, "array_player")["loop"] is loop
    page.get_by_role("button", name="Step ▶").focus()
    page.keyboard.press("l")  # on the player's buttons it toggles the loop
    assert _state(page, "array_player")["loop"] is (not loop)
    page.locator("body").focus()
    page.evaluate("() => document.activeElement.blur()")
    page.keyboard.press("Space")
    page.wait_for_timeout(600)
    s = _state(page, "array_player")
    assert s["playing"] and s["frame"] > 1
    page.keyboard.press("Space")
    page.keyboard.press("Home")
    page.wait_for_timeout(150)
    s = _state(page, "array_player")
    assert not s["playing"] and s["frame"] == 0


def test_buttons_are_labelled_and_step(pages, open_page):
    urls, _, _ = pages
    page = open_page(urls["support"])
    labels = ("▶ Play", "◀ Step", "Step ▶", "|◀ Start", "⟳ Loop")
    tips = ("Play or pause (Space)", "One frame back (←)", "One frame forward (→)",
            "Back to the first frame (Home)", "Start again at the end (L)",
            "Playback speed (↑ faster, ↓ slower)")
    for name in labels:
        assert page.get_by_role("button", name=name, exact=True).count() == 1, name
    for tip in tips:
        assert page.get_by_title(tip, exact=True).count() == 1, tip
    forward = page.get_by_role("button", name="Step ▶", exact=True)
    forward.click()
    forward.click()
    page.get_by_role("button", name="◀ Step", exact=True).click()
    page.wait_for_timeout(150)
    assert _state(page, "support_player")["frame"] == 1
    # The support scene follows: the mass sits where the trajectory is at that frame.
    mass = page.evaluate("() => Bokeh.documents[0].get_model_by_name('scene_mass').data.tau[0]")
    tau = page.evaluate("() => Bokeh.documents[0].get_model_by_name('support_frames').data.tau[1]")
    assert mass == tau > 0


@pytest.mark.parametrize("size, follows", [((390, 844), True), ((1920, 1080), False)])
def test_top_view_keeps_equal_scales_and_follows_the_slab_on_a_phone(pages, open_page, size,
                                                                     follows):
    urls, motion, _ = pages
    page = open_page(urls["array"], size)
    for _ in range(40):
        page.keyboard.press("ArrowRight")
    page.wait_for_timeout(300)
    view = page.evaluate("""() => {
        const f = Bokeh.documents[0].get_model_by_name("array_top");
        const s = Bokeh.documents[0].get_model_by_name("array_slab").data;
        return {x0: f.x_range.start, x1: f.x_range.end, y0: f.y_range.start, y1: f.y_range.end,
                w: f.inner_width, h: f.inner_height, left: s.left[0], right: s.right[0]}; }""")
    full = motion.slab_lead[0] + motion.t_end.max() - (motion.slab_lead[0] - motion.params.L0)
    span = view["x1"] - view["x0"]
    # A phone shows a window around the slab; a wide screen (nearly) the whole travel.
    assert bool(span < full / 2) is follows, view
    assert view["x0"] <= view["left"] and view["right"] <= view["x1"], view  # slab in view
    if span < full - 1e-6:  # following: equal scales, r0 as many pixels along x as along y
        assert span / view["w"] == pytest.approx((view["y1"] - view["y0"]) / view["h"], rel=0.02)


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("which", ["array", "support"])
def test_screenshots(pages, open_page, artifacts_dir, which, size):
    """Pictures to look at (artifacts/animation-*.png), taken mid-playback."""
    urls, _, _ = pages
    page = open_page(urls[which], SIZES[size])
    page.keyboard.press("Space")
    page.wait_for_timeout(2500)
    page.keyboard.press("Space")
    page.wait_for_timeout(300)
    page.screenshot(path=str(artifacts_dir / f"animation-{which}-{size}.png"), full_page=True)
    assert _state(page, f"{which}_player")["frame"] > 0
