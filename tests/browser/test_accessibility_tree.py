"""What a screen reader is given: Chromium's accessibility tree (CDP
``Accessibility.getFullAXTree``, through every shadow root) names every slider and
button, and every plot is a figure with a name (its title) and a description (its
tab's words) that changes with the state (issue 25's "Done means")."""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

BUTTONS = {"button", "toggleButton", "ToggleButton", "PopUpButton", "tab"}


def _tree(page) -> list[dict]:
    """The page's accessibility tree: the nodes a screen reader is given (not ignored),
    as {role, name, description}."""
    cdp = page.context.new_cdp_session(page)
    try:
        cdp.send("Accessibility.enable")
        nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    finally:
        cdp.detach()
    out = []
    for node in nodes:
        if node.get("ignored"):
            continue
        value = lambda key: str((node.get(key) or {}).get("value") or "").strip()  # noqa: E731
        out.append({"role": value("role"), "name": value("name"),
                    "description": value("description")})
    return out


def _figures(page) -> dict:
    return {n["name"]: n["description"] for n in _tree(page) if n["role"] == "figure"}


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
