"""A playing player draws its own tab and nothing else: its frames and readouts change no
element outside that tab (no other tab, not the controls or the headline). A readout
written as a Bokeh ``Div``'s text, a label or range that relayouts the page, would touch
every view of the page several times a second and halve the frames shown (see
``benchmarks/bench_served_player.py``). Paused, the readouts show the exact frame."""
from __future__ import annotations

import re

import pytest

from . import page_tools as pt

pytestmark = [pytest.mark.browser, pytest.mark.timeout(300)]

# Records every DOM change (attributes, children, text) in the document and in every shadow
# root, with the CSS classes of the shadow hosts above its target (the tab it is in).
_WATCH_JS = """() => {
  const records = window.__mpChanges = [];
  const hosts = (node) => {
    const out = [];
    for (let n = node; n; ) {
      if (n.classList) out.push(...n.classList);
      const root = n.getRootNode();
      n = root && root.host ? root.host : n.parentNode;
    }
    return out;
  };
  const observer = window.__mpObserver = new MutationObserver((list) => {
    for (const r of list) records.push({type: r.type, attr: r.attributeName,
      at: performance.now(),
      where: hosts(r.target), what: (r.target.className && String(r.target.className)) ||
        r.target.nodeName});
  });
  const seen = new Set();
  const visit = (root) => {
    if (seen.has(root)) return;
    seen.add(root);
    observer.observe(root, {subtree: true, childList: true, attributes: true,
                            characterData: true});
    for (const el of root.querySelectorAll("*")) if (el.shadowRoot) visit(el.shadowRoot);
  };
  visit(document);
  return seen.size;
}"""

_STOP_JS = "() => { window.__mpObserver.disconnect(); return window.__mpChanges; }"


def _frame(page, player):
    return page.evaluate(f"""() => {{ for (const d of Bokeh.documents) for (const m of d.all_models)
        if (m.name === "{player}_frame") return m.value; return null; }}""")


def _model(page, name, attr):
    return page.evaluate(f"""() => {{ for (const d of Bokeh.documents) for (const m of d.all_models)
        if (m.name === "{name}") return m.{attr}; return null; }}""")


def _set_play(page, player, on: bool):
    page.evaluate(f"""() => {{ for (const d of Bokeh.documents) for (const m of d.all_models)
        if (m.name === "{player}_play") m.active = {str(on).lower()}; }}""")


def _quiet(page, quiet_ms: int = 1500, timeout_s: float = 90.0) -> None:
    """Wait until the page's DOM has not changed for ``quiet_ms`` (results still arriving
    from the server change it)."""
    page.evaluate(_WATCH_JS)
    pt.wait_for(page, lambda: page.evaluate(f"""() => {{ const r = window.__mpChanges;
        return performance.now() - (r.length ? r[r.length - 1].at : 0) > {quiet_ms}; }}"""),
        timeout_s=timeout_s, what="the page to stop changing")
    page.evaluate(_STOP_JS)


def _play_and_watch(page, player, frames: int = 40, tries: int = 5):
    """Play, record the page's DOM changes over ``frames`` frames of playback (at least
    1.5 s: several readout writes), pause; returns the records and the paused frame. A
    window in which the server sent the page something (a result arriving) is tried
    again: the server may change any part of the page."""
    received = page.__mp_received
    _quiet(page)
    _set_play(page, player, True)
    start = _frame(page, player)
    pt.wait_for(page, lambda: _frame(page, player) != start, timeout_s=20,
                what=f"{player} to start")
    # Play's own label change lays the page out once: done before the window opens.
    page.get_by_role("button", name="‖ Pause").first.wait_for(timeout=30_000)
    page.wait_for_timeout(500)
    for _ in range(tries):
        before = len(received)
        roots = page.evaluate(_WATCH_JS)
        assert roots > 50, f"only {roots} roots watched: not the dashboard?"
        first = _frame(page, player)
        page.wait_for_timeout(1500)
        pt.wait_for(page, lambda: abs(_frame(page, player) - first) >= frames, timeout_s=60,
                    what=f"{frames} frames of {player}")
        records = page.evaluate(_STOP_JS)
        if len(received) == before:
            break
    _set_play(page, player, False)
    page.wait_for_timeout(400)  # the readouts settle on the paused frame
    return records, _frame(page, player)


def _outside(records, tab_class):
    return [r for r in records if tab_class not in r["where"]]


def _open(page, app_url, tab, player):
    page.__mp_received = received = []  # messages from the server
    page.on("websocket", lambda ws: ws.on("framereceived", lambda payload: received.append(1)))
    pt.wait_for_app(page, f"{app_url}?tab={tab}")
    page.wait_for_function(f"""() => Bokeh.documents.some((d) => [...d.all_models].some(
        (m) => m.name === "{player}_play"))""", timeout=120_000)
    pt.settle(page)
    page.wait_for_timeout(1000)


def test_the_array_player_changes_nothing_outside_its_tab(page, page_log, app_url):
    _open(page, app_url, "array", "array_player")
    records, frame = _play_and_watch(page, "array_player")
    outside = _outside(records, "array-tab")
    assert records, "nothing changed in the page while the array played"
    assert outside == [], (f"{len(outside)} changes outside the Array tab while it played, "
                           f"e.g. {outside[:5]}")
    # Paused: the readout gives the paused frame's count (the model's, in the series).
    counts = _model(page, "array_series", "data.N_c")
    readout = _model(page, "array_readout", "html")
    assert f"N_c = {int(counts[frame])}</b>" in readout, (frame, readout)
    assert page_log.errors == [], page_log.errors


def test_the_support_player_changes_nothing_outside_its_tab(page, page_log, app_url):
    _open(page, app_url, "support", "support_player")
    records, frame = _play_and_watch(page, "support_player")
    outside = _outside(records, "support-tab")
    assert records, "nothing changed in the page while the support played"
    assert outside == [], (f"{len(outside)} changes outside the One support tab while it "
                           f"played, e.g. {outside[:5]}")
    # Paused: the player's readout and the energy readout name the paused frame.
    n = len(_model(page, "support_player_times", "data.t"))
    assert re.search(rf"frame {frame + 1} / {n}\b", _model(page, "support_player_readout", "html"))
    tau = _model(page, "support_frames", "data.tau")[frame]
    shown = re.search(r"τ = ([\d.]+):", _model(page, "energy_live_readout", "html"))
    assert shown and abs(float(shown.group(1)) - tau) <= 0.006, (frame, tau, shown)
    # A step forward is drawn and read out too.
    page.keyboard.press("ArrowRight")
    pt.wait_for(page, lambda: _frame(page, "support_player") == frame + 1, timeout_s=5,
                what="one step forward")
    page.wait_for_timeout(300)
    assert f"frame {frame + 2} / {n}" in _model(page, "support_player_readout", "html")
    # A move while paused: the scene stays at the frame on show, and so does the readout,
    # with that frame's time in the new contact.
    times = _model(page, "support_player_times", "data.t")
    pt.move_slider(page, pt.slider_handle(page, title_pattern="F_N"), presses=2)
    pt.wait_for(page, lambda: _model(page, "support_player_times", "data.t") != times,
                timeout_s=60, what="the new contact's times")
    page.wait_for_timeout(300)
    new_tau = _model(page, "support_player_times", "data.t")[frame + 1]
    readout = _model(page, "support_player_readout", "html")
    assert f"frame {frame + 2} / {n} · τ = {new_tau:.2f}" in readout, (frame, new_tau, readout)
    assert _frame(page, "support_player") == frame + 1
    assert page_log.errors == [], page_log.errors


# Counts, while the player plays, how often each canvas layer of each figure is cleared
# (BokehJS clears a layer to repaint it) and how many elements the legends get anew. A
# layer is named after the figure's element (``layers``, by its ``figure-`` class) and
# after the plot it draws (``plots``, by the plot's name).
_LAYERS_JS = """async ([player, ms]) => {
  const clears = new Map(), C = CanvasRenderingContext2D.prototype, clear = C.clearRect;
  C.clearRect = function (...a) { clears.set(this.canvas, (clears.get(this.canvas) || 0) + 1);
                                  return clear.apply(this, a); };
  let legends = 0;
  const observer = new MutationObserver((list) => { for (const r of list)
    if ([...r.addedNodes].some((n) => n.nodeType === 1)) legends += 1; });
  const visit = (root) => { for (const el of root.querySelectorAll("*")) if (el.shadowRoot) {
    if (el.classList.contains("bk-Legend")) observer.observe(el.shadowRoot, {childList: true, subtree: true});
    visit(el.shadowRoot); } };
  visit(document);
  let frame = null, frames = 0;
  for (const d of Bokeh.documents) for (const m of d.all_models)
    if (m.name === player + "_frame") frame = m;
  frame.connect(frame.properties.value.change, () => frames++);
  await new Promise((r) => setTimeout(r, ms));
  C.clearRect = clear;
  observer.disconnect();
  const out = {frames, legends, layers: {}, plots: {}};
  const plots = new Map();
  for (const d of Bokeh.documents) for (const m of d.all_models) {
    const view = m.name && typeof m.output_backend === "string" ? Bokeh.index.find_one(m) : null;
    if (view && view.canvas_view) {
      plots.set(view.canvas_view.primary.canvas, `${m.name}:0`);
      plots.set(view.canvas_view.overlays.canvas, `${m.name}:1`);
    }
  }
  for (const [canvas, n] of clears) {
    const plot = plots.get(canvas);
    if (plot) out.plots[plot] = (out.plots[plot] || 0) + n;
    let host = canvas, figure = null;
    while (figure === null) {
      const root = host.getRootNode();
      if (!root || !root.host) break;
      host = root.host;
      figure = [...host.classList].find((c) => c.startsWith("figure-")) || null;
    }
    // A plot's canvas layers: [0] the still drawing, [1] the overlay (what moves).
    const layer = [...canvas.getRootNode().querySelectorAll("canvas.bk-layer:not(.bk-glyph)")]
      .indexOf(canvas);
    const key = `${figure}:${layer}`;
    out.layers[key] = (out.layers[key] || 0) + n;
  }
  return out;
}"""


def _layers_while_playing(page, player, ms: int = 3000) -> dict:
    """``_LAYERS_JS``'s counts over ``ms`` of playback, in a window in which the server
    sent the page nothing (a result arriving may repaint anything)."""
    _quiet(page)
    _set_play(page, player, True)
    page.get_by_role("button", name="‖ Pause").first.wait_for(timeout=30_000)
    page.wait_for_timeout(500)
    for _ in range(5):
        received = len(page.__mp_received)
        seen = page.evaluate(_LAYERS_JS, [player, ms])
        if len(page.__mp_received) == received:
            break
    _set_play(page, player, False)
    return seen


def test_a_playing_support_repaints_only_what_moves(page, page_log, app_url):
    """Per frame, each figure repaints its moving layer only: the axes, grid, legends and
    still curves are not drawn again, and no legend is built anew."""
    _open(page, app_url, "support", "support_player")
    pt.wait_for(page, lambda: len((pt.read_source(page, "support_frames") or {}).get("tau", []))
                > 0, timeout_s=120, what="the player's frames")
    figures = ("figure-scene", "figure-forces", "figure-friction_law", "figure-energy_live_layout")
    seen = _layers_while_playing(page, "support_player")
    assert seen["frames"] >= 10, seen
    for fig in figures:
        assert seen["layers"].get(f"{fig}:1", 0) >= 3, f"{fig}'s moving layer was not drawn: {seen}"
        assert seen["layers"].get(f"{fig}:0", 0) == 0, \
            f"{fig}'s still drawing was repainted while the player played: {seen}"
    assert seen["legends"] == 0, f"legends built anew while the player played: {seen}"
    assert page_log.errors == [], page_log.errors


def test_a_playing_array_repaints_only_what_moves(page, page_log, app_url):
    """Per frame, the top view repaints only its moving layer (the slab, which slides out
    of the view, and the supports), the live panel only its growing curves and cursor:
    their axes, grids and titles are not drawn again, the colour scale not at all, and no
    legend is built anew."""
    _open(page, app_url, "array", "array_player")
    seen = _layers_while_playing(page, "array_player")
    assert seen["frames"] >= 10, seen
    for plot in ("array_top", "array_live_panel"):
        assert seen["plots"].get(f"{plot}:0", 0) == 0, \
            f"{plot}'s still drawing was repainted while the array played: {seen}"
        assert seen["plots"].get(f"{plot}:1", 0) >= 3, f"{plot}'s moving layer was not drawn: {seen}"
    assert not any(k.startswith("array_colorbar_figure") for k in seen["plots"]), seen
    assert seen["legends"] == 0, f"legends built anew while the array played: {seen}"
    assert page_log.errors == [], page_log.errors
