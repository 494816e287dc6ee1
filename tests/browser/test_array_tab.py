"""The Array tab of the served dashboard: the slab slides over ~100 supports in the
browser (autoplay from the URL), N_c changes as supports enter and leave contact, and no
message goes to the server per frame."""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(240)]


def _state(page):
    return page.evaluate("""() => {
      const d = Bokeh.documents[0], f = d.get_model_by_name("array_player_frame");
      const r = d.get_model_by_name("array_readout");
      return f ? {frame: f.value, readout: r ? r.html : ""} : null; }""")


def _wait(page, predicate, timeout_ms=60_000):
    waited = 0
    while waited < timeout_ms:
        state = _state(page)
        if state is not None and predicate(state):
            return state
        page.wait_for_timeout(200)
        waited += 200
    pytest.fail(f"timed out; last state {_state(page)}")


def test_the_array_plays_and_the_contact_count_changes(page, page_log, app_url):
    sent = []
    page.on("websocket", lambda ws: ws.on("framesent", lambda payload: sent.append(payload)))
    pt.wait_for_app(page, f"{app_url}?tab=array&play=1")
    first = _wait(page, lambda s: s["frame"] > 5)  # autoplay
    counts = set()
    before = len(sent)
    for _ in range(20):
        state = _state(page)
        found = re.search(r"N_c = (\d+)", state["readout"])
        if found:
            counts.add(int(found.group(1)))
        page.wait_for_timeout(250)
    assert _state(page)["frame"] > first["frame"], "the array animation did not advance"
    assert len(counts) >= 2, f"N_c did not change while playing: {counts}"
    assert len(sent) - before <= 2, f"{len(sent) - before} messages to the server per frame"
    assert page_log.errors == [], page_log.errors
