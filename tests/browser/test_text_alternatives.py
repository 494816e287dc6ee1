"""Every tab's plots in words and in numbers, for a reader who cannot see them (WCAG 1.1.1):

* the Array, Orientation (polar), Regime map and Load tabs each have a polite live region
  that describes their plots from the computed result and changes with the controls (a
  regime preset), written once per result (the array's stays still while it plays);
* each has a "Data as a table" button, pressed from the keyboard, whose table is
  the tab's CSV download (the same rows and numbers) with units in its column headers.
"""
from __future__ import annotations

import csv
import io
import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(900)]

#: tab title -> (description's CSS class, a phrase of its text, what the soft preset says)
TABS = {"Array": ("array-description", "supports on a", "k_r = 0.03, k_θ = 0.03"),
        "Orientation (polar)": ("polar-description", "Polar diagrams", "k_r = 0.03, k_θ = 0.03"),
        "Regime map": ("map-description", "Regime map", "soft regime"),
        "Load": ("load-description", "Load curves", "soft regime")}


def _region(page, css: str):
    return page.locator(f".{css} [role=status]").first


def _text(page, css: str) -> str:
    region = _region(page, css)
    return (region.text_content() or "") if region.count() else ""


def _ready(page, css: str, phrase: str) -> bool:
    text = _text(page, css)
    return phrase in text and "being computed" not in text


def test_every_tab_describes_its_plots_and_the_words_follow_the_state(page, page_log, app_url):
    pt.wait_for_app(page, f"{app_url}?regime=pendulum")
    for title, (css, phrase, soft) in TABS.items():
        pt.open_tab(page, "^" + re.escape(title))
        pt.wait_for(page, lambda: _ready(page, css, phrase), timeout_s=180,
                    what=lambda: f"the {title} tab's description: {_text(page, css)!r}")
        region = _region(page, css)
        assert region.get_attribute("aria-live") == "polite"
        box = region.bounding_box()
        assert box is None or box["width"] <= 1, "the description is for screen readers only"
        before = _text(page, css)
        assert "k_r = 3, k_θ = 0.01" in before, before
        assert soft not in before, before
        if title == "Array":  # once per result: still while the array plays
            view = page.locator(".array-view")
            view.get_by_role("button", name=re.compile("Play")).click()
            seen = {_text(page, css)}
            for _ in range(8):
                page.wait_for_timeout(120)
                seen.add(_text(page, css))
            assert seen == {before}, f"the description changed while playing: {seen}"
            view.get_by_role("button", name=re.compile("Pause")).click()
        page.get_by_role("button", name="Soft", exact=True).focus()
        page.keyboard.press("Space")
        pt.wait_for(page, lambda: soft in _text(page, css), timeout_s=180,
                    what=lambda: f"the {title} tab's description to follow the Soft preset: "
                                 f"{_text(page, css)!r}")
        assert _text(page, css) != before
        page.get_by_role("button", name="Pendulum", exact=True).click()
        pt.wait_for(page, lambda: "k_r = 3, k_θ = 0.01" in _text(page, css)
                    and soft not in _text(page, css), timeout_s=180,
                    what=lambda: f"the {title} tab's description to come back with the "
                                 f"Pendulum preset: {_text(page, css)!r}")
    assert page_log.errors == [], page_log.errors


def _download(page, label: str) -> str:
    with page.expect_download(timeout=120_000) as info:
        pt.click_button(page, label)
    return open(info.value.path(), encoding="utf-8").read()


def _csv_rows(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO("".join(
        line for line in text.splitlines(keepends=True) if not line.startswith("#")))))


def _table(page, css: str) -> dict:
    return page.evaluate("""(css) => {
      const find = (root, selector) => {  // through shadow roots
        const t = root.querySelector(selector);
        if (t) return t;
        for (const el of root.querySelectorAll("*"))
          if (el.shadowRoot) { const f = find(el.shadowRoot, selector); if (f) return f; }
        return null;
      };
      const host = find(document, "." + css);
      const table = host && find(host.shadowRoot || host, "table");
      if (!table) return null;
      return {caption: table.caption ? table.caption.textContent : "",
              head: [...table.querySelectorAll("thead th")].map((th) => th.textContent),
              scope: [...table.querySelectorAll("thead th")].map((th) => th.getAttribute("scope")),
              rows: [...table.querySelectorAll("tbody tr")].map(
                (tr) => [...tr.children].map((td) => td.textContent))};
    }""", css)


def test_the_numbers_behind_the_plots_are_a_table_opened_from_the_keyboard(page, page_log,
                                                                           app_url):
    pt.wait_for_app(page, f"{app_url}?tab=polar")
    pt.wait_for(page, lambda: _ready(page, "polar-description", "Polar diagrams"),
                timeout_s=180, what="the polar sweep")
    assert _table(page, "polar-table") is None, "the table is written only once opened"
    button = page.locator(".polar-table button").filter(has_text="Data as a table").first
    button.focus()
    page.keyboard.press("Enter")
    pt.wait_for(page, lambda: _table(page, "polar-table") is not None, timeout_s=30,
                what="the table to open with Enter")
    table = _table(page, "polar-table")
    rows = _csv_rows(_download(page, "^Polar sweep CSV$"))
    names, data = rows[0], rows[1:]
    assert len(table["head"]) == len(names) and set(table["scope"]) == {"col"}
    assert table["head"][0] == "θ₀ [°]" and "F_T,x/(μ₀F_N) [–]" in table["head"], table["head"]
    assert len(table["rows"]) == len(data) == 72, "every row of the CSV, here 72"
    ftx = names.index("FTx_over_mu0FN")
    for shown, written in zip(table["rows"], data):
        assert float(shown[0]) == pytest.approx(float(written[0]), rel=1e-3)
        assert float(shown[ftx].replace("−", "-")) == pytest.approx(float(written[ftx]),
                                                                   rel=1e-3)
    assert page_log.errors == [], page_log.errors
