"""The offline page's workaround in BokehJS (``app/offline/bokeh_fix.js``) on BokehJS
itself: a figure's paint rewrites its renderers' <style> elements with their own text
(docs/upstream/bokehjs_style_rewrite.py). With the workaround a key press rewrites none; with
BokehJS's own method restored, the same press rewrites several: the canary, which fails the
day BokehJS stops doing it (then the workaround can go). The guard: tests/test_offline_fix.py."""
from __future__ import annotations

from app.edge import TESTED

from .offline_tools import (DRAWN, POLAR, UNIFORM, Offline,  # noqa: F401 (fixtures)
                            explorer_file, offline)
from .style_watch import USE, WATCH


def _press_and_count(offline, presses: int = 3) -> dict:
    page = offline.page
    page.evaluate(WATCH)
    handle = page.locator(".noUi-handle").nth(3)  # theta0
    handle.focus()
    for i in range(presses):
        drawn = page.evaluate(DRAWN)
        handle.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
        page.wait_for_function(f"{DRAWN} > {drawn} && !explorer.pending()")
        page.wait_for_timeout(100)  # the texts' paint after the support's
    return page.evaluate("window.styleWrites")


def test_a_key_press_rewrites_no_style_with_its_own_text(offline):
    offline.open()
    page = offline.page
    page.wait_for_function(f"{POLAR} >= 1 && {UNIFORM} >= 1", timeout=120_000)
    fix = page.evaluate("({applied: MicropillarBokehFix.applied, reason: MicropillarBokehFix"
                        ".reason, version: Bokeh.version})")
    assert fix == {"applied": True, "reason": "", "version": TESTED["bokeh"]}

    fixed = _press_and_count(offline)
    assert fixed["same"] == 0, fixed

    page.evaluate(USE, True)
    own = _press_and_count(offline)
    page.evaluate(USE, False)
    # The canary: BokehJS's own method rewrites unchanged styles at every paint. When this
    # fails, BokehJS has fixed it: delete app/offline/bokeh_fix.js, its use in app/edge.py
    # (``page_js``) and their tests.
    assert own["same"] >= 3 * 10, (
        f"BokehJS {TESTED['bokeh']} no longer rewrites unchanged <style> elements in a paint "
        f"({own}): the workaround app/offline/bokeh_fix.js can go (also from app/edge.py)")
    again = _press_and_count(offline)
    assert again["same"] == 0, again
    # What changes is still written (the same press redraws with the workaround or without).
    assert fixed["changed"] >= 3 and abs(fixed["changed"] - own["changed"]) <= max(
        3, own["changed"] // 4), (fixed, own)
    assert offline.errors == []
