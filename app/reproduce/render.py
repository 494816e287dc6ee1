"""Standalone HTML (BokehJS inlined: opens offline) and PNG pictures of the figures.

PNGs are screenshots of the HTML taken by headless Chromium through Playwright (Bokeh's
own ``export_png`` needs Selenium and a driver; Playwright drives Debian's ``chromium``).
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

from bokeh.io import save
from bokeh.resources import INLINE

CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--no-first-run", "--disable-sync",
                  "--disable-dev-shm-usage"]


#: Right and bottom edges of everything drawn on the page.
_EXTENT = """() => { let w = 0, h = 0;
  for (const el of document.querySelectorAll('body *')) {
    const r = el.getBoundingClientRect();
    if (r.width > 0 && r.height > 0) { w = Math.max(w, r.right); h = Math.max(h, r.bottom); }
  } return [w, h]; }"""


def save_html(model, path: Path, title: str) -> Path:
    save(model, filename=str(path), resources=INLINE, title=title)
    return path


def chromium() -> str | None:
    """The Chromium executable to use, or None: ``$MICROPILLAR_CHROMIUM``, else Debian's."""
    for candidate in (os.environ.get("MICROPILLAR_CHROMIUM"), "/usr/bin/chromium",
                      shutil.which("chromium")):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    return None


def browser_problem() -> str | None:
    """Why PNGs cannot be made here (None when they can)."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install '.[test]')"
    if chromium() is None:
        return "no Chromium found (apt-get install chromium)"
    return None


def html_to_png(pages: list, progress=None) -> list:
    """Screenshot each ``(html, png)`` pair in one browser session; returns the PNG paths.

    Each page is shown in a viewport as wide as its content and captured whole, after
    BokehJS has rendered it.
    """
    from playwright.sync_api import sync_playwright

    done = []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=chromium(), args=CHROMIUM_FLAGS)
        try:
            page = browser.new_page(viewport={"width": 800, "height": 600})
            for i, (html, png) in enumerate(pages):
                page.goto(Path(html).resolve().as_uri())
                page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0 && "
                                       "document.querySelector('.bk-Figure, .bk-Row, "
                                       ".bk-Column, .bk-GridPlot') !== null", timeout=30_000)
                page.wait_for_timeout(300)  # the canvas paints after the layout settles
                w, h = page.evaluate(_EXTENT)
                page.set_viewport_size({"width": max(400, int(w) + 24),
                                        "height": max(300, int(h) + 24)})
                page.wait_for_timeout(100)
                w, h = page.evaluate(_EXTENT)
                page.screenshot(path=str(png), clip={"x": 0, "y": 0, "width": int(w) + 8,
                                                     "height": int(h) + 8})
                done.append(Path(png))
                if progress is not None:
                    progress(i + 1, len(pages))
        finally:
            browser.close()
    return done
