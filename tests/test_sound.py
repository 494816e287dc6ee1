"""The sound of the One support tab's player (app/figures/sound.py): each frame's pitch and
pan from a known trajectory, and the page's toggle and data (what the browser plays)."""
from __future__ import annotations

import numpy as np
import pytest
from bokeh.models import CustomJS

from app import slot
from app.figures.live_energy import support_frames
from app.figures.sound import PITCH_HZ, SOUND_NAME, sound_data
from app.state import ExplorerState
from fakes import InProcessPool
from model import REGIMES, simulate_support


@pytest.fixture(scope="module")
def soft_frames():
    p = REGIMES["soft"]
    return support_frames(simulate_support(p, samples=400).series, p, 300)


def test_pitch_follows_the_speed_on_a_log_scale_over_the_trajectorys_range(soft_frames):
    v = soft_frames["v_R"]
    hz = sound_data(v, soft_frames["F_y"])["hz"]
    lo, hi = PITCH_HZ
    assert hz[np.argmin(v)] == pytest.approx(lo) and hz[np.argmax(v)] == pytest.approx(hi)
    assert hz.min() == pytest.approx(lo) and hz.max() == pytest.approx(hi)
    # Equal steps of speed, equal musical intervals: log(hz) is linear in |v_R|.
    octaves = np.log2(hz / lo) / np.log2(hi / lo)
    np.testing.assert_allclose(octaves, (v - v.min()) / (v.max() - v.min()), atol=1e-12)
    # The soft regime sticks and slips: both ends of the range are heard, not one note.
    assert np.ptp(np.log2(hz)) == pytest.approx(2.0)


def test_pan_follows_the_sideways_friction(soft_frames):
    f_y = soft_frames["F_y"]
    pan = sound_data(soft_frames["v_R"], f_y)["pan"]
    assert np.all(np.abs(pan) <= 1.0) and np.abs(pan).max() == pytest.approx(1.0)
    assert np.all(np.sign(pan) == np.sign(f_y))  # left for -y, right for +y
    np.testing.assert_allclose(pan, f_y / np.abs(f_y).max(), atol=1e-12)


def test_flat_cases_and_bad_input():
    still = sound_data(np.full(5, 0.3), np.zeros(5))
    np.testing.assert_allclose(still["hz"], np.sqrt(PITCH_HZ[0] * PITCH_HZ[1]))
    np.testing.assert_array_equal(still["pan"], 0.0)
    with pytest.raises(ValueError, match="one value per frame"):
        sound_data(np.ones(4), np.ones(3))
    with pytest.raises(ValueError, match="finite"):
        sound_data(np.array([1.0, np.nan]), np.zeros(2))


def test_the_page_sends_each_frames_tone_and_an_off_toggle_in_the_players_row(monkeypatch):
    from app.views import Dashboard

    pool = InProcessPool()
    monkeypatch.setattr(slot, "work_pool", lambda: pool)
    page = Dashboard(ExplorerState(tab="support"))
    view = page.support
    data = view.results.support
    frames = support_frames(data.series, data.params, view.player.n_frames)
    expected = sound_data(frames["v_R"], frames["F_y"])
    for key in ("hz", "pan"):
        np.testing.assert_allclose(view.sound.data[key], expected[key])
    toggle = view.sound_toggle
    assert toggle.active is False
    assert toggle.html_attributes["data-aria-label"] == SOUND_NAME and toggle.height >= 24
    assert toggle in view.player.layout.children[0].children
    # The browser plays it from the player's own frame callbacks, with these data.
    followers = [cb for cb in view.player.frame.js_property_callbacks["change:value"]
                 if isinstance(cb, CustomJS) and cb.args.get("sound") is view.sound]
    assert len(followers) == 1 and followers[0].args["play"] is view.player.play
    assert followers[0] in view.player.play.js_property_callbacks["change:active"]
    # A new result: new tones, on the same source.
    page.state.F_N = 2.0
    data = view.results.support
    assert data.params.F_N == 2.0
    frames = support_frames(data.series, data.params, view.player.n_frames)
    np.testing.assert_allclose(view.sound.data["hz"],
                               sound_data(frames["v_R"], frames["F_y"])["hz"])
