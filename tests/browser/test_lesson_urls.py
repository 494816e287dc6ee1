"""Every link of the lesson (docs/teaching.md, app/lesson.py) opens the explorer in the
state it names -- tab, springs, load, orientation, projector mode -- without a notice,
with the animation waiting at its first frame until Play is pressed (the class predicts
first)."""
from __future__ import annotations

import math

import pytest

from app.lesson import BASE_URL, STEPS, lesson_url
from model import REGIMES

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(300)]

PLAYERS = {"support": "support_player_frame", "array": "array_player_frame"}


def _frame(page, name):
    return page.evaluate("(n) => { const m = Bokeh.documents[0].get_model_by_name(n); "
                         "return m ? m.value : null; }", name)


@pytest.mark.parametrize("step", STEPS, ids=lambda s: s.key)
def test_a_lesson_link_opens_its_state(page, page_log, app_url, step):
    url = lesson_url(step).replace(BASE_URL, app_url)
    pt.wait_for_app(page, url)
    pt.settle(page)  # at rest: nothing plays
    notice = page.locator(".page-notice")
    assert not notice.is_visible(), notice.inner_text()
    k_r = pt.find_slider(page, "ctl-k_r", r"^k_r")
    assert math.isclose(10 ** k_r.value, REGIMES[step.regime].k_r, rel_tol=1e-6)
    theta0 = pt.find_slider(page, "ctl-theta0", r"θ₀")
    assert theta0.value == step.theta0_deg
    active = page.locator(".tab-bar .bk-btn.bk-active, .tab-bar button.bk-active").first
    assert active.is_visible()
    assert pt.model_value(page, "Toggle$", "active", "ctl-projector") is True, \
        "the link dropped projector mode"
    if step.tab in PLAYERS:
        name = PLAYERS[step.tab]
        page.wait_for_timeout(2000)
        assert _frame(page, name) == 0, f"the {step.tab} animation started before Play"
        page.locator('[title="Play or pause (Space)"] >> visible=true').first.click()
        pt.wait_for(page, lambda: (_frame(page, name) or 0) >= 5, timeout_s=30,
                    what=f"the {step.tab} animation to play after Play")
    assert page_log.errors == [], page_log.errors
