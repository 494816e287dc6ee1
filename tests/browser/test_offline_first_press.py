"""The offline page readies its support's figures for the first key press
(``app/offline/support.js``, ``rehearse``): once idle it draws a neighbouring contact and
the current one again in each of a few animation frames, so that V8 has compiled BokehJS's
paths before the reader's first press. What the reader sees must not change, and a key
press must never wait for it or be overwritten by it."""
from __future__ import annotations

import math

import pytest

from .offline_tools import (DRAWN, UNIFORM, Offline,  # noqa: F401 (fixtures)
                            explorer_file, offline)

#: The support's drawn data: the top view's path, Fig. 7's forces, the player's frames.
SHOWN = """() => { const source = (name) => [...Bokeh.documents[0].all_models].find((m) =>
    m.name === name && m.data !== undefined && m.selected !== undefined);
  const col = (name, key) => Array.from(source(name).data[key]);
  return {x1: col("orbit", "x1"), F_x: col("forces", "F_x"), tau: col("support_frames", "tau"),
          mass: col("scene_mass", "x")}; }"""
#: The contact the state shows, computed again in the page.
WANT = """(deg) => { const r = explorer.simulate({k_r: 3, k_theta: 0.01, F_N: 1,
  theta0: deg * Math.PI / 180, beta: explorer.result.params.beta, samples: 400});
  return {x1: Array.from(r.series.x).slice(1), F_x: Array.from(r.series.F_x)}; }"""


def test_the_rehearsal_leaves_the_figures_as_they_were(offline):
    offline.open()
    page = offline.page
    n = page.evaluate("MicropillarSupportFigures.REHEARSALS")
    assert n >= 4
    # At every animation frame of the rehearsal the figures show the state's contact. The
    # page itself waits for the uniform array (after which the page goes idle and the
    # rehearsal starts) and then looks at every frame, from wherever the rehearsal has got
    # to: each step waits for a frame, so the steps are spread over frames, not made in
    # one task.
    watched = page.evaluate(f"""async () => {{ const seen = [];
      const shown = {SHOWN};
      const until = performance.now() + 120000;
      while (!({UNIFORM} >= 1) && performance.now() < until)
        await new Promise((done) => setTimeout(done, 5));
      const start = explorer.rehearsed;
      while (explorer.rehearsed < {n}) {{
        await new Promise((done) => requestAnimationFrame(done));
        seen.push(shown());
        if (seen.length > 600) break;
      }}
      seen.push(shown());  // and once it is over
      return {{uniform: {UNIFORM}, start, seen}}; }}""")
    assert watched["uniform"] >= 1, "the uniform array was not drawn within 120 s"
    frames = watched["seen"]
    assert page.evaluate("explorer.rehearsed") == n
    assert len(frames) - 1 >= (n - watched["start"]) // 2, watched["start"]
    want = page.evaluate(WANT, 90)
    for shown in frames:
        assert shown["x1"] == pytest.approx(want["x1"], abs=1e-12)
        assert shown["F_x"] == pytest.approx(want["F_x"], abs=1e-12)
    assert all(f == frames[0] for f in frames)  # the player's frame too
    assert page.evaluate("explorer.state.theta0_deg") == 90
    assert offline.errors == []


def test_a_key_press_stops_the_rehearsal_and_is_drawn(offline):
    offline.open()
    page = offline.page
    page.wait_for_function(f"{UNIFORM} >= 1", timeout=120_000)
    drawn = page.evaluate(DRAWN)
    # As the reader would, mid-rehearsal (its second step made): theta0 to 120 degrees.
    at = page.evaluate("""async () => {
      await new Promise((done) => { const wait = () => explorer.rehearsed >= 2 ? done()
          : requestAnimationFrame(wait); wait(); });
      const at = explorer.rehearsed;
      explorer.set({theta0_deg: 120});
      return at; }""")
    page.wait_for_function(f"{DRAWN} > {drawn} && !explorer.pending()")
    page.wait_for_timeout(300)  # the rehearsal's next frames, were it still running
    n = page.evaluate("MicropillarSupportFigures.REHEARSALS")
    assert at < n and page.evaluate("explorer.rehearsed") <= at + 1 < n
    assert page.evaluate("explorer.result.params.theta0") == pytest.approx(math.radians(120),
                                                                           rel=1e-12)
    shown, want = page.evaluate(SHOWN), page.evaluate(WANT, 120)
    assert shown["x1"] == pytest.approx(want["x1"], abs=1e-12)
    assert shown["F_x"] == pytest.approx(want["F_x"], abs=1e-12)
    assert offline.errors == []
