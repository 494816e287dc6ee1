"""The regime panel's words (app/motion_words.py) say what the computed motion did, at
any state: every number in the text is checked against the model's own run of that state
(off the presets: a grid over springs, loads and theta0)."""
import math
import re

import numpy as np
import pytest

from app import worker
from app.motion_words import regime_markdown
from app.state import classify
from app.texts import MECHANISMS
from model import Params, fixed_orientation, simulate_support

SPRINGS = ((0.01, 0.01), (0.01, 3.0), (3.0, 0.01), (3.0, 3.0), (0.1, 0.5), (0.5, 0.05))
LOADS = (0.3, 10.0)
ANGLES = (30.0, 90.0, 150.0)
NUMBER = r"(−?[0-9.e+−]+)"


def _number(text: str) -> float:
    return float(text.replace("−", "-"))


def _reference(k_r, k_theta, F_N, theta0_deg) -> dict:
    """The motion as the model gives it, computed here without the app."""
    p = Params(k_r=k_r, k_theta=k_theta, F_N=F_N, theta0=math.radians(theta0_deg))
    fixed = fixed_orientation(p)
    res = simulate_support(p.replace(beta=fixed.beta), samples=worker.SAMPLES,
                           max_steps=worker.MAX_STEPS)
    s = res.series
    theta = np.degrees(s.theta)
    return {"r_min": res.r_min, "r_max": res.r_max, "theta_min": theta.min(),
            "theta_max": theta.max(), "theta_end": theta[-1],
            "stick": 100 * np.mean(np.hypot(s.v_x - 1, s.v_y) < 0.1),
            "contact": res.t_out / p.L0, "Dy_Dx": fixed.Dy_over_Dx,
            "U_el": fixed.work_split["U_el"], "change": 100 * (1 - fixed.FTx_over_mu0FN)}


@pytest.mark.parametrize("k_r, k_theta", SPRINGS)
@pytest.mark.parametrize("F_N", LOADS)
@pytest.mark.parametrize("theta0_deg", ANGLES)
def test_every_number_of_the_regime_text_is_the_computed_motion(k_r, k_theta, F_N,
                                                                 theta0_deg):
    p = Params(k_r=k_r, k_theta=k_theta, F_N=F_N, theta0=math.radians(theta0_deg))
    text = regime_markdown(classify(k_r, k_theta), worker.compute_support(p))
    ref = _reference(k_r, k_theta, F_N, theta0_deg)
    title, mechanism = MECHANISMS[classify(k_r, k_theta)]
    assert text.startswith(f"**{title}.** {mechanism}")
    assert f"(θ₀ = {theta0_deg:g}°, F_N = {F_N:.3g})" in text
    m = re.search(rf"between {NUMBER} and {NUMBER} r₀", text)
    assert _number(m[1]) == pytest.approx(ref["r_min"], rel=6e-3)
    assert _number(m[2]) == pytest.approx(ref["r_max"], rel=6e-3)
    m = re.search(rf"turned from {theta0_deg:g}° to between {NUMBER}° and {NUMBER}° "
                  rf"\(ending at {NUMBER}°\)", text)
    for got, key in zip(m.groups(), ("theta_min", "theta_max", "theta_end")):
        assert _number(got) == pytest.approx(ref[key], abs=0.51), key
    m = re.search(rf"for {NUMBER} % of a contact {NUMBER} times as long", text)
    assert _number(m[1]) == pytest.approx(ref["stick"], abs=0.51)
    assert _number(m[2]) == pytest.approx(ref["contact"], rel=6e-3)
    m = re.search(rf"D_y/D_x = {NUMBER}, U_el/W = {NUMBER}", text)
    assert _number(m[1]) == pytest.approx(ref["Dy_Dx"], rel=6e-3, abs=1e-12)
    assert _number(m[2]) == pytest.approx(ref["U_el"], abs=0.0051)
    m = re.search(rf"friction is {NUMBER} % (below|above) a rigid surface", text)
    if m is None:
        assert "the same as on a rigid surface" in text and abs(ref["change"]) < 0.05
    else:
        sign = 1 if m[2] == "below" else -1
        assert sign * _number(m[1]) == pytest.approx(ref["change"], abs=0.051)


def test_the_issue_s_states_are_told_their_own_numbers():
    """k_r = k_theta = 0.01 at F_N = 10 stretches to ~112 r0 (not "about 20"); the slider
    at theta0 = 150 deg is 3.3 % below (not "9-16 %")."""
    soft = worker.compute_support(Params(k_r=0.01, k_theta=0.01, F_N=10.0))
    text = regime_markdown("soft", soft)
    assert f"and {soft.result.r_max:.3g} r₀" in text and "112" in text
    assert "about 20" not in text and "16 %" not in text
    slider = worker.compute_support(Params(k_r=0.01, k_theta=3.0, theta0=math.radians(150)))
    text = regime_markdown("slider", slider)
    assert "3.3 % below" in text and "9-16" not in text and "9–16" not in text


def test_without_a_result_the_text_says_it_is_being_computed():
    assert regime_markdown("pendulum", None).endswith("*The motion is being computed.*")
    # No amount fixed in the words of a regime: those come from the computed motion.
    words = " ".join(m for _, m in MECHANISMS.values())
    assert not re.search(r"[0-9.]+ ?(%|r₀|V₀)|about [0-9]|[0-9] times", words)


def test_the_page_s_regime_panel_follows_the_computed_support():
    from app.state import ExplorerState
    from app.views import Dashboard
    from app.views.live_text import markdown_html

    page = Dashboard(ExplorerState())
    page.state.param.update(k_r=0.01, k_theta=0.01, F_N=10.0)
    text = page.readouts.regime.html
    assert text == markdown_html(regime_markdown("soft", page.results.support))
    assert text.startswith("<p><strong>Soft (both springs soft).</strong>")
    assert f"{page.results.support.result.r_max:.3g} r₀" in text
