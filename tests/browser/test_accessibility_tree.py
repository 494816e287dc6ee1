"""What a screen reader is given: Chromium's accessibility tree (CDP
``Accessibility.getFullAXTree``, through every shadow root) names every slider and
button, and every plot is a figure with a name (its title) and a description (its
tab's words) that changes with the state (issue 25's "Done means")."""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt
from .axe_tools import ax_figures as _figures
from .axe_tools import ax_tree as _tree

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

BUTTONS = {"button", "toggleButton", "ToggleButton", "PopUpButton", "tab"}


def _check_names(nodes: list[dict], where: str) -> None:
    sliders = [n for n in nodes if n["role"] == "slider"]
    buttons = [n for n in nodes if n["role"] in BUTTONS]
    assert len(sliders) >= 4 and len(buttons) >= 10, (where, len(sliders), len(buttons))
    unnamed = [n for n in sliders + buttons if not n["name"]]
    assert not unnamed, f"{where}: sliders or buttons without a name: {unnamed}"


def test_every_slider_button_and_plot_has_a_name_and_the_plots_words_follow_the_state(
        page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?regime=pendulum")
    pt.wait_for(page, lambda: any("pendulum regime" in d for d in _figures(page).values()),
                timeout_s=120, what=lambda: f"the plots as figures: {_figures(page)}")
    nodes = _tree(page)
    _check_names(nodes, "One support")
    figures = _figures(page)
    assert len(figures) >= 4, figures  # top view, friction, friction law, energy split
    assert all(name and words for name, words in figures.items()), figures
    assert any(re.search("top view", name, re.I) for name in figures), list(figures)
    before = dict(figures)

    page.get_by_role("button", name="Soft", exact=True).focus()
    page.keyboard.press("Space")
    pt.wait_for(page, lambda: any("soft regime" in d for d in _figures(page).values()),
                timeout_s=120, what=lambda: f"the figures' words to follow: {_figures(page)}")
    after = _figures(page)
    assert set(after) == set(before)
    assert all(after[name] != before[name] for name in before), (before, after)

    for title, figure in (("Regime map", "Uniform array"), ("Load", "")):
        pt.open_tab(page, "^" + re.escape(title))
        pt.wait_for(page, lambda: any("soft regime" in d for n, d in _figures(page).items()
                                      if figure in n), timeout_s=180,
                    what=lambda: f"the {title} tab's figure and its words: {_figures(page)}")
        _check_names(_tree(page), title)
    assert page_log.errors == [], page_log.errors


#: The Design tab's figures (their titles) and what their words must hold.
DESIGN_FIGURES = {"The design on Fig. 5a": "star at k̃_r", "Fig. 11a": "Polar diagram",
                  "Friction law": "At the design's V₀", "Friction vs sliding speed":
                  "Dashed: the flat material's μ(V₀)"}


def _design(page) -> dict:
    """The Design tab's figures: {title prefix: description} of those on show."""
    figures = _figures(page)
    return {key: words for key in DESIGN_FIGURES for name, words in figures.items()
            if name.startswith(key)}


def _design_said(page, *needles) -> bool:
    said = _design(page)
    return (set(said) == set(DESIGN_FIGURES)
            and all(DESIGN_FIGURES[k] in w for k, w in said.items())
            and all(any(n in w for w in said.values()) for n in needles))


def test_the_design_tabs_figures_are_named_and_described_by_the_designs_result(
        page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?tab=design")
    pt.wait_for(page, lambda: _design_said(page, "V₀ = 1 m/s", "stiff regime",
                                           "Its friction F_T,x/(μ₀F_N)"), timeout_s=180,
                what=lambda: f"the Design tab's figures and their words: {_figures(page)}")
    _check_names(_tree(page), "Design")
    before = _design(page)

    box = page.locator(".ctl-design_V0 input").first
    box.fill("300 m/s")
    box.press("Enter")
    pt.wait_for(page, lambda: _design_said(page, "at V₀ = 300 m/s", "soft regime"),
                timeout_s=180, what=lambda: f"the words to follow V₀: {_design(page)}")
    after = _design(page)
    for key in ("The design on Fig. 5a", "Friction law"):
        assert after[key] != before[key], (key, after[key])
    assert page_log.errors == [], page_log.errors
