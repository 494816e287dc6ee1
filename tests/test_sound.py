"""The sound of the One support tab's player (app/figures/sound.py): each frame's pitch and
pan as the page's mapping (``TONES_JS``, run here in Node) gives them for a known
trajectory, and the page's toggle and frames (what the browser plays)."""
from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest
from bokeh.models import CustomJS

from app import slot
from app.figures.live_energy import support_frames
from app.figures.sound import PITCH_HZ, SOUND_NAME, TONES_JS
from app.state import ExplorerState
from fakes import InProcessPool
from model import REGIMES, simulate_support


def tones(v_R, F_y) -> dict:
    """The page's tones for these frames (``TONES_JS`` in Node, as the browser runs it)."""
    node = shutil.which("node")
    if node is None:  # a requirement of the suite, like Chromium: never skipped silently
        pytest.fail("node is not installed: the page's sound mapping is tested with Node",
                    pytrace=False)
    code = (f"const f = {TONES_JS.strip()};\n"
            "const a = JSON.parse(require('fs').readFileSync(0, 'utf8'));\n"
            "process.stdout.write(JSON.stringify(f(a.v, a.f, a.lo, a.hi)));")
    done = subprocess.run([node, "-e", code], text=True, capture_output=True, timeout=60,
                          input=json.dumps({"v": list(map(float, v_R)),
                                            "f": list(map(float, F_y)),
                                            "lo": PITCH_HZ[0], "hi": PITCH_HZ[1]}))
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    return {key: np.array(out[key], float) for key in ("hz", "pan")}


@pytest.fixture(scope="module")
def soft_frames():
    p = REGIMES["soft"]
    return support_frames(simulate_support(p, samples=400).series, p, 300)


def test_pitch_follows_the_speed_on_a_log_scale_over_the_trajectorys_range(soft_frames):
    v = np.abs(soft_frames["v_R"])
    hz = tones(soft_frames["v_R"], soft_frames["F_y"])["hz"]
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
    pan = tones(soft_frames["v_R"], f_y)["pan"]
    assert np.all(np.abs(pan) <= 1.0) and np.abs(pan).max() == pytest.approx(1.0)
    assert np.all(np.sign(pan) == np.sign(f_y))  # left for -y, right for +y
    np.testing.assert_allclose(pan, f_y / np.abs(f_y).max(), atol=1e-12)


def test_flat_cases():
    still = tones(np.full(5, 0.3), np.zeros(5))
    np.testing.assert_allclose(still["hz"], np.sqrt(PITCH_HZ[0] * PITCH_HZ[1]))
    np.testing.assert_array_equal(still["pan"], 0.0)
    # The speed's sign does not matter, only |v_R|.
    np.testing.assert_allclose(tones([-2.0, 1.0, 0.0], [0, 0, 0])["hz"],
                               [PITCH_HZ[1], np.sqrt(PITCH_HZ[0] * PITCH_HZ[1]), PITCH_HZ[0]])


def test_the_page_plays_the_players_own_frames_with_an_off_toggle_in_its_row(monkeypatch):
    from app.views import Dashboard

    pool = InProcessPool()
    monkeypatch.setattr(slot, "work_pool", lambda: pool)
    page = Dashboard(ExplorerState(tab="support"))
    view = page.support
    toggle = view.sound_toggle
    assert toggle.active is False
    assert toggle.html_attributes["data-aria-label"] == SOUND_NAME and toggle.height >= 24
    assert toggle in view.player.layout.children[0].children
    # The browser plays it from the player's own frame callbacks, with the frames that
    # draw the support (no sound data of its own from the server).
    followers = [cb for cb in view.player.frame.js_property_callbacks["change:value"]
                 if isinstance(cb, CustomJS) and cb.args.get("toggle") is toggle]
    assert len(followers) == 1 and followers[0].args["play"] is view.player.play
    assert followers[0] in view.player.play.js_property_callbacks["change:active"]
    frames_source = followers[0].args["frames"]
    assert frames_source is view._frames_js.args["data"]
    assert followers[0] in frames_source.js_property_callbacks["change:data"]
    data = view.results.support
    frames = support_frames(data.series, data.params, view.player.n_frames)
    for key in ("v_R", "F_y"):
        np.testing.assert_allclose(frames_source.data[key], frames[key])
    # A new result: new frames, on the same source.
    page.state.F_N = 2.0
    data = view.results.support
    assert data.params.F_N == 2.0
    frames = support_frames(data.series, data.params, view.player.n_frames)
    np.testing.assert_allclose(frames_source.data["v_R"], frames["v_R"])
    assert not any(m.name == "support_sound" for m in page.__panel__().get_root().references())
