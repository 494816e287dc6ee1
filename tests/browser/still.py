"""Waiting for the page to hold still: its next painted frame, or a reading of it that
stops changing (a layout after a resize), instead of a fixed wait."""
from __future__ import annotations


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
