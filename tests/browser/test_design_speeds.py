"""The Design tab of the served dashboard from a lab's two measured curves to the
comparison: the flat material's curve uploaded and fitted, the structured surface's
friction against sliding speed predicted in the background (points with error bars, the
flat mu(V0) beside them), the structured sample's curve uploaded over it, and the RMS of
the difference and the speeds where they disagree said in words."""
from __future__ import annotations

from pathlib import Path

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(300)]

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: The structured example's pillars (``model.lab.friction_example.STRUCTURED_DESIGN``).
QUERY = "?tab=design&d_E=1%20MPa&d_Lx=0.1%20mm&d_FN=10%20uN&d_V0=1%20m/s"
N_SPEEDS = 5


def _text(page, css: str) -> str:
    """The text of a Markdown pane (its paragraphs)."""
    return " ".join(page.locator(f"{css} p").all_inner_texts())


def _count(page, name: str, key: str = "v") -> int:
    return len((pt.read_source(page, name) or {}).get(key, []))


def test_both_curves_uploaded_give_the_fit_the_prediction_and_the_comparison(
        page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}{QUERY}")
    pt.wait_for_plot(page, "design_speeds")
    page.locator(".design-friction-file input[type=file]").first.set_input_files(
        str(EXAMPLES / "flat_friction.csv"))
    page.locator(".design-friction p").filter(has_text="Fitted to").first.wait_for(
        timeout=30_000)
    for css, value in ((".ctl-speeds_range input", "0.1 m/s..3 m/s"),
                       (".ctl-speeds_n input", str(N_SPEEDS))):
        box = page.locator(css).first
        box.fill(value)
        box.press("Enter")
    page.wait_for_timeout(500)
    page.locator(".design-speeds-predict button").first.click()
    # Points arrive one by one, each with its error bar; the flat law is drawn beside them.
    pt.wait_for(page, lambda: _count(page, "speeds_model") == N_SPEEDS, timeout_s=180.0,
                what=lambda: f"{N_SPEEDS} predicted points; the note says "
                             f"{_text(page, '.design-speeds')!r}")
    model = pt.read_source(page, "speeds_model")
    assert all(lo <= mu <= hi for lo, mu, hi in zip(model["lo"], model["mu"], model["hi"]))
    assert model["v"][0] == pytest.approx(0.1) and model["v"][-1] == pytest.approx(3.0)
    assert _count(page, "speeds_flat") > 10
    pt.wait_for(page, lambda: "speeds computed" in _text(page, ".design-speeds"),
                timeout_s=30.0, what=lambda: f"the note saying the curve is done: "
                                             f"{_text(page, '.design-speeds')!r}")
    page.locator(".design-structured-file input[type=file]").first.set_input_files(
        str(EXAMPLES / "structured_friction.csv"))
    pt.wait_for(page, lambda: "RMS" in _text(page, ".design-speeds-compare"), timeout_s=30.0,
                what=lambda: f"the comparison; it says {_text(page, '.design-speeds-compare')!r}")
    text = _text(page, ".design-speeds-compare")
    assert "structured_friction.csv" in text and "over 12 speeds" in text, text
    assert ("disagree beyond the model's error" in text
            or "agree within the model's error" in text), text
    assert _count(page, "speeds_measured") == 12
    assert _count(page, "speeds_difference", "d") == 12
    assert page_log.errors == [], page_log.errors
