"""The One support tab's sound (app/figures/sound.py), heard through the page's Web Audio:

* the toggle is in the player's row, named for screen readers, off, and no AudioContext
  exists before the reader clicks it;
* clicked, then played: the tone runs, its pitch and pan change with the frames and are
  the ones the mapping gives for the trajectory the page shows (soft regime: stick-slip);
* paused it is silent; switched off the oscillator stops and the context is closed;
* the reader leaves the tab (or the browser's tab goes to the background): the player
  pauses and the tone stops, not sounding on over another tab.
"""
from __future__ import annotations

import numpy as np
import pytest

from app.figures.sound import PITCH_HZ, SOUND_NAME

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

# Every AudioContext the page makes, recorded before any of its scripts runs.
_COUNT_CONTEXTS = """
window.__mp_contexts = [];
if (window.AudioContext) {
  const Original = window.AudioContext;
  window.AudioContext = class extends Original {
    constructor(...args) { super(...args); window.__mp_contexts.push(this); }
  };
}
"""


def _sound(page) -> dict | None:
    return page.evaluate("""() => {
      const s = window.__mp_sound;
      if (!s) return null;
      const frame = [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "support_player_frame").value;
      return {running: s.running, frequency: s.frequency, pan: s.pan, frame: s.frame,
              player_frame: frame, context: s.context, oscillator_hz: s.oscillator_hz,
              gain: s.gain};
    }""")


def _expected(v_R, F_y) -> dict:
    """The tones the module's mapping promises (app/figures/sound.py): log pitch over the
    trajectory's own |v_R| range, pan by F_y over its largest |F_y|."""
    speed, lo, hi = np.abs(v_R), *PITCH_HZ
    u = (speed - speed.min()) / np.ptp(speed)
    return {"hz": lo * (hi / lo) ** u, "pan": F_y / np.abs(F_y).max()}


def _contexts(page) -> list[str]:
    return page.evaluate("() => window.__mp_contexts.map((c) => c.state)")


def test_sound_is_off_until_asked_then_follows_the_frames_and_stops(page, page_log, app_url):
    page.add_init_script(_COUNT_CONTEXTS)
    pt.wait_for_app(page, f"{app_url}?regime=soft")
    pt.settle(page, names=["support_frames"])
    pt.wait_for(page, lambda: len((pt.read_source(page, "support_frames") or {}).get("v_R", []))
                == 300, timeout_s=120, what="the player's frames")
    frames = pt.read_source(page, "support_frames")
    assert "soft regime" in page.locator(".support-description [role=status]").first \
        .text_content()
    expected = _expected(np.array(frames["v_R"]), np.array(frames["F_y"]))

    toggle = page.get_by_role("button", name=SOUND_NAME)
    pt.wait_for(page, lambda: toggle.count() == 1, what=f"a button named {SOUND_NAME!r}")
    assert toggle.get_attribute("aria-pressed") == "false"
    box = toggle.bounding_box()
    assert box["height"] >= 24 and box["width"] >= 24, box
    page.wait_for_timeout(500)
    before = _sound(page)
    assert _contexts(page) == [] and (before is None or before["context"] == "none"), \
        f"audio before the reader asked: {before}"

    toggle.click()  # a real gesture: the page may now make sound
    pt.wait_for(page, lambda: _sound(page) is not None and _sound(page)["context"] == "running",
                what=lambda: f"the audio context to run: {_sound(page)}")
    assert len(_contexts(page)) == 1
    assert toggle.get_attribute("aria-pressed") == "true"
    paused = _sound(page)
    assert paused["running"] is False, "sound while the player is paused"
    assert paused["frequency"] == pytest.approx(expected["hz"][paused["player_frame"]])

    pt.click_button(page, "Play")
    pt.wait_for(page, lambda: _sound(page)["running"], what="the tone while playing")
    samples = []
    for _ in range(25):
        page.wait_for_timeout(80)
        samples.append(_sound(page))
    seen = {s["frame"] for s in samples}
    assert len(seen) >= 5, f"the tone did not follow the frames: {samples}"
    for s in samples:
        i = s["frame"]
        assert i == s["player_frame"], s
        assert s["frequency"] == pytest.approx(expected["hz"][i], rel=1e-9), s
        assert s["pan"] == pytest.approx(expected["pan"][i], abs=1e-9), s
        assert PITCH_HZ[0] - 1 <= s["oscillator_hz"] <= PITCH_HZ[1] + 1, s
    assert len({round(s["frequency"], 3) for s in samples}) >= 3, samples
    # The oscillator itself glides to the frames' pitches (not one steady note).
    assert len({round(s["oscillator_hz"], 1) for s in samples}) >= 3, samples
    assert max(s["gain"] for s in samples) > 0

    pt.click_button(page, "Pause")
    pt.wait_for(page, lambda: not _sound(page)["running"] and _sound(page)["gain"] < 1e-3,
                what=lambda: f"silence when paused: {_sound(page)}")

    pt.click_button(page, "Play")
    pt.wait_for(page, lambda: _sound(page)["running"], what="the tone again")
    toggle.click()  # off: the oscillator stops and the context is closed
    pt.wait_for(page, lambda: _contexts(page) == ["closed"],
                what=lambda: f"the context to close: {_contexts(page)}")
    off = _sound(page)
    assert off["running"] is False and off["context"] == "none" and off["frequency"] is None
    assert toggle.get_attribute("aria-pressed") == "false"
    pt.click_button(page, "Pause")
    assert not page_log.errors, page_log.dump()


def _set_active(page, on: bool) -> None:
    """Switch the sound as the page itself does (its model's property, not a click)."""
    page.evaluate("""(on) => { [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "support_player_sound").active = on; }""", on)


def test_the_toggle_says_whether_the_sound_is_on_however_it_changed(page, page_log, app_url):
    page.add_init_script(_COUNT_CONTEXTS)
    pt.wait_for_app(page, f"{app_url}?regime=soft")
    toggle = page.get_by_role("button", name=SOUND_NAME)
    pt.wait_for(page, lambda: toggle.count() == 1, what=f"a button named {SOUND_NAME!r}")
    pressed = lambda: toggle.get_attribute("aria-pressed")  # noqa: E731

    _set_active(page, True)  # switched on by the page, the focus elsewhere
    pt.wait_for(page, lambda: pressed() == "true", what=lambda: f"aria-pressed: {pressed()}")
    pt.open_tab(page, "^Array")  # another tab and back: the button still says it
    page.wait_for_timeout(500)
    pt.open_tab(page, "^One support")
    pt.wait_for(page, lambda: toggle.is_visible(), what="the toggle shown again")
    assert pressed() == "true"

    page.locator("body").click(position={"x": 5, "y": 5})  # the focus off the toggle
    _set_active(page, False)  # the page turns the sound off itself
    pt.wait_for(page, lambda: pressed() == "false", what=lambda: f"aria-pressed: {pressed()}")
    pt.wait_for(page, lambda: _contexts(page) in ([], ["closed"]),
                what=lambda: f"no audio once off: {_contexts(page)}")

    toggle.focus()
    page.keyboard.press("Space")  # and the keyboard
    pt.wait_for(page, lambda: pressed() == "true", what=lambda: f"aria-pressed: {pressed()}")
    page.keyboard.press("Space")
    pt.wait_for(page, lambda: pressed() == "false", what=lambda: f"aria-pressed: {pressed()}")
    assert not page_log.errors, page_log.dump()


def _playing(page) -> bool:
    return page.evaluate("""() => [...Bokeh.documents[0].all_models].find(
        (m) => m.name === "support_player_play").active""")


def _support_tab_shown(page) -> bool:
    return page.evaluate("""() => [...Bokeh.documents[0].all_models].find(
        (m) => (m.css_classes || []).includes("main-tabs")).active === 0""")


def _frame(page) -> int:
    return _sound(page)["player_frame"]


def _sounding_then(page, leave, come_back) -> None:
    """Play with the sound on, ``leave``: the player pauses, the tone fades out and the
    frames stop; ``come_back``: still paused until Play is pressed, then it sounds again."""
    pt.click_button(page, "Play")
    pt.wait_for(page, lambda: _sound(page)["running"] and _sound(page)["gain"] > 0,
                what=lambda: f"the tone while playing: {_sound(page)}")
    leave()
    pt.wait_for(page, lambda: not _playing(page), timeout_s=5,
                what="the player to pause once its tab is hidden")
    pt.wait_for(page, lambda: not _sound(page)["running"] and _sound(page)["gain"] < 1e-3,
                timeout_s=5, what=lambda: f"silence once the tab is hidden: {_sound(page)}")
    stopped = _frame(page)
    page.wait_for_timeout(600)
    assert _frame(page) == stopped, "frames drawn on a hidden tab"
    come_back()
    # The One support tab shown again (the tab bar's change goes through the server): until
    # then a "Play" button on screen is another tab's player's.
    pt.wait_for(page, lambda: _support_tab_shown(page), what="the One support tab again")
    page.wait_for_timeout(600)
    assert not _playing(page) and not _sound(page)["running"]
    pt.click_button(page, "Play")
    pt.wait_for(page, lambda: _sound(page)["running"],
                what=lambda: f"the tone again after Play (playing: {_playing(page)}, "
                             f"the page hidden: {page.evaluate('document.hidden')}, "
                             f"{_sound(page)})")
    pt.click_button(page, "Pause")


_HIDE_PAGE = """(hidden) => {
  Object.defineProperty(document, "hidden", {value: hidden, configurable: true});
  Object.defineProperty(document, "visibilityState",
                        {value: hidden ? "hidden" : "visible", configurable: true});
  document.dispatchEvent(new Event("visibilitychange"));
}"""


def test_leaving_the_tab_pauses_the_player_and_silences_it(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?regime=soft")
    pt.wait_for(page, lambda: len((pt.read_source(page, "support_frames") or {}).get("v_R", []))
                == 300, timeout_s=120, what="the player's frames")
    toggle = page.get_by_role("button", name=SOUND_NAME)
    pt.wait_for(page, lambda: toggle.count() == 1, what=f"a button named {SOUND_NAME!r}")
    toggle.click()
    pt.wait_for(page, lambda: _sound(page) is not None and _sound(page)["context"] == "running",
                what=lambda: f"the audio context to run: {_sound(page)}")
    # Another tab of the dashboard, and back.
    _sounding_then(page, lambda: pt.open_tab(page, "^Array"),
                   lambda: pt.open_tab(page, "^One support"))
    # The browser's tab in the background, and back.
    _sounding_then(page, lambda: page.evaluate(_HIDE_PAGE, True),
                   lambda: page.evaluate(_HIDE_PAGE, False))
    assert not page_log.errors, page_log.dump()
