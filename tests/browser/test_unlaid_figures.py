"""Frames played before a figure was laid out. A figure on a tab not shown yet, or on a slow
page before its first layout, has no drawn size yet, and BokehJS throws on reading it
("Figure.inner_width is unset"). The Array tab's frame code reads the top view's size to
follow the slab on a narrow screen: it must wait for the size instead of failing every
frame (seen on a page opened with ``?tab=array&play=1`` on a busy machine)."""
from __future__ import annotations

import pytest
from bokeh.embed import file_html
from bokeh.layouts import column
from bokeh.resources import INLINE

from app.figures.array_scene import array_scene
from app.figures.player import browser_player
from model import REGIMES
from model.arrays.array_motion import array_motion

pytestmark = [pytest.mark.browser, pytest.mark.timeout(120)]


def _page_html() -> str:
    """The array scene, following the slab (as on a phone), and its player."""
    motion = array_motion(REGIMES["slider"], n_supports=30, n_frames=40)
    player = browser_player(motion.n_frames)
    scene = array_scene(motion, player, responsive=True)
    return file_html(column(player.layout, scene), INLINE, "array frames")


def test_the_array_plays_before_its_top_view_is_laid_out(page, page_log):
    page.set_content(_page_html(), wait_until="load")
    page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0")
    # The frame code given a top view as it is before its first layout: a copy of the
    # figure that no view has drawn yet.
    moved = page.evaluate("""async () => {
      const doc = Bokeh.documents[0];
      const frame = doc.get_model_by_name("player_frame");
      const now = doc.get_model_by_name("array_supports");
      const code = [...frame.js_property_callbacks["change:value"]]
        .find((cb) => cb.code.includes("inner_width"));
      const top = code.args.top;
      const unlaid = new top.constructor({x_range: top.x_range, y_range: top.y_range});
      code.args = {...code.args, top: unlaid};
      const before = Array.from(now.data.mx);
      for (const f of [10, 20, 30]) {  // CustomJS runs its code asynchronously
        frame.value = f;
        await new Promise((resolve) => setTimeout(resolve, 50));
      }
      return {unlaid: unlaid.properties.inner_width.is_unset,
              changed: now.data.mx.some((x, i) => x !== before[i])};
    }""")
    assert moved["unlaid"], "the copy of the top view was laid out: the case is not tested"
    assert page_log.errors == [], page_log.errors
    assert moved["changed"], f"the frames did not move the supports: {moved}"
