"""Waiting for the page to hold still: its next painted frame, or a reading of it that
stops changing (a layout after a resize), instead of a fixed wait; and screenshots of a
page at rest, for a person to look at (``$MICROPILLAR_SCREENSHOTS``)."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path


def wait_until_still(page, read_js: str, quiet_ms: int = 300, timeout_ms: int = 15_000) -> None:
    """Wait until ``read_js`` (a JavaScript function returning a string, read on every
    animation frame) has not changed for ``quiet_ms``; raises if it still changes after
    ``timeout_ms`` (e.g. the page laying itself out again after a resize)."""
    page.evaluate("""([quiet, timeout]) => new Promise((resolve, reject) => {
      const read = """ + read_js + """;
      let last = read(), since = performance.now();
      const start = since;
      const tick = () => {
        const now = read(), t = performance.now();
        if (now !== last) { last = now; since = t; }
        if (t - since >= quiet) resolve(true);
        else if (t - start >= timeout) reject(new Error(`it kept changing: ${now}`));
        else requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    })""", [quiet_ms, timeout_ms])


def next_paint(page) -> None:
    """Wait until the browser has painted a frame from now on (two animation frames: the
    one that draws what is pending and the one after it), e.g. before a screenshot of a
    page at rest (``settle``)."""
    page.evaluate("() => new Promise((resolve) => "
                  "requestAnimationFrame(() => requestAnimationFrame(() => resolve(true))))")


def shots_dir() -> Path:
    """Where the suite saves its screenshots: ``$MICROPILLAR_SCREENSHOTS``, or else a new
    temporary folder."""
    folder = os.environ.get("MICROPILLAR_SCREENSHOTS")
    path = Path(folder) if folder else Path(tempfile.mkdtemp(prefix="micropillar-shots-"))
    path.mkdir(parents=True, exist_ok=True)
    return path


def shoot(page, path: Path) -> Path:
    """A PNG of what the window shows now (not the whole page), the mouse moved off the
    tab bar (no tooltip over the page), after the next paint."""
    size = page.viewport_size
    page.mouse.move(size["width"] / 2, size["height"] - 2)
    next_paint(page)
    page.screenshot(path=str(path), full_page=False)
    return path
