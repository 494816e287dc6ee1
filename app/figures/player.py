"""A player that runs in the browser: all frames' data are sent once, a browser-side
timer (requestAnimationFrame) advances the frame, and no server round trip happens per
frame.

``browser_player(n_frames, ...)`` returns a ``BrowserPlayer``: Bokeh widgets (labelled
play/pause, single steps back and forward, back to the start, speed 0.1x-4x, loop, a
frame slider, the time readout and the list of keyboard shortcuts) and ``frame``, a
view-less model whose ``value`` is the current frame. Figures follow the player by
attaching their own ``CustomJS`` to it::

    player = browser_player(n_frames, times=tau)
    player.on_frame(CustomJS(args=..., code="const i = cb_obj.value; ..."))
    layout = column(figure, player.layout)
    player.install(doc)          # keyboard shortcuts (and autoplay) once the page is ready

Inside Panel, where the Bokeh document is Panel's, call ``player.ready()`` from the server
once the page is loaded (``pn.state.onload``): it changes a property the browser watches.
The slider and readout follow a playing animation at most every ``UI_MS`` ms, the figures
every frame. The readout is a text node (``app.figures.live_text``), not a ``Div``'s text:
a ``Div`` that changes has BokehJS lay out and repaint the whole page.
Keyboard: Space play/pause, <- -> one frame, Up/Down faster/slower, Home first frame,
L loop. The keys go to the player last used (or last made ready) and are ignored while an
input, select or text area has the focus; Space and Enter on a focused button press that
button. L, a letter, acts only while one of the player's own controls has the focus
(``CONTROL_CLASS``): typed elsewhere (speech input, a screen reader's keys) it does
nothing (WCAG 2.1.4). Autoplay is skipped when the reader asked for less motion
(``prefers-reduced-motion: reduce``); Play still starts the player. Hidden -- its tab
left, or the browser's tab in the background -- a playing player pauses (within ``UI_MS``):
no frame is drawn unseen and its sound stops with it.

Sound (``app.figures.sound.add_sound``, off by default) adds a toggle to the player's row
and plays each frame as a tone: pitch from the support's speed on the slab |v_R| (220-880
Hz, log scale, over the trajectory's own range), left/right from the sideways friction
F_f,y (pan -1..1 over its own largest |F_f,y|); the mapping (``TONES_JS``) runs in the page.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from bokeh.events import DocumentReady
from bokeh.layouts import column, row
from bokeh.core.properties import Int
from bokeh.model import DataModel
from bokeh.models import Button, ColumnDataSource, CustomJS, Div, Select, Slider, Toggle
from bokeh.models.dom import HTML

from .live_text import live_div, live_html

__all__ = ["BrowserPlayer", "PlayerFrame", "browser_player", "SPEEDS", "SHORTCUTS"]

#: Playback speeds (multiples of ``fps`` frames per second).
SPEEDS = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0)
SHORTCUTS = (("Space", "play / pause"), ("← →", "one frame back / forward"),
             ("↑ ↓", "faster / slower"), ("Home", "first frame"),
             ("L", "loop on / off (on the player's buttons)"))
#: CSS class of the player's controls: the letter key L acts only while one has the focus.
CONTROL_CLASS = "mp-player-control"
PLAY, PAUSE = "▶ Play", "‖ Pause"
#: Play's green, dark enough for its white label (5.1:1, WCAG 1.4.3; Bokeh's is 2.5:1).
PLAY_FILL = "#2E7D32"
PLAY_CSS = (f".bk-btn-success {{ background-color: {PLAY_FILL}; border-color: {PLAY_FILL}; "
            "color: #FFFFFF; }")

# The player's state lives in the page (window.__mpf_players, keyed by the frame model's
# id); every callback first makes sure it exists, so whichever runs first sets it up.
# The frame model has no view: changing it costs only the figures that follow it. The
# slider and the readout (DOM) follow at most every UI_MS while playing.
_PRELUDE = f"""
const CONTROL = {CONTROL_CLASS!r};
""" + """
const reg = (window.__mpf_players = window.__mpf_players || {});
let st = reg[frame.id];
if (st === undefined) {
  st = reg[frame.id] = {raf: null, last: null, pos: frame.value, ticks: 0, drawn: 0, ui_t: 0};
  st.speed = () => parseFloat(speed.value);
  st.ui = (force) => {
    const now = performance.now();
    if (!force && now - st.ui_t < ui_ms) return;
    st.ui_t = now;
    const i = frame.value;
    readout.setv({html: `frame ${i + 1} / ${n} · ${label} = ${timeline.data.t[i].toFixed(2)}`}, {sync: false});
    // A slider view built but not drawn yet (a page sent in a patch is drawn over several
    // turns) throws on a new value (BokehJS's _update_title before render); the model keeps
    // the value and its first draw shows it. Uncaught, it would stop the timer.
    try { if (slider.value !== i) slider.setv({value: i}, {sync: false}); } catch (error) {}
  };
  // Frames shown; the timer keeps its fractional position, a step or a jump does not.
  st.show = (f, force) => { if (frame.value !== f) { frame.setv({value: f}, {sync: false}); st.drawn += 1; } st.ui(force); };
  st.set = (f) => { st.pos = f; st.show(f, true); };
  // Hidden -- its tab left, its page in the background -- the player pauses: no frame is
  // drawn unseen and no tone sounds on (app.figures.sound). Its play button's element
  // (found once by its data-player) is checked at most every ui_ms while playing.
  st.el = null;
  st.seen_t = 0;
  st.shown = () => {
    if (document.hidden) return false;
    if (st.el === null || !st.el.isConnected) {
      const find = (root) => {
        const el = root.querySelector(`[data-player="${frame.id}"]`);
        if (el) return el;
        for (const host of root.querySelectorAll("*"))
          if (host.shadowRoot) { const found = find(host.shadowRoot); if (found) return found; }
        return null;
      };
      st.el = find(document);
      if (st.el === null) return true;  // not drawn yet
    }
    // Not drawn (display: none) or hidden (an inactive tab is visibility: hidden).
    return st.el.getClientRects().length > 0 && getComputedStyle(st.el).visibility !== "hidden";
  };
  st.pause = () => { if (play.active) play.active = false; };
  st.tick = (now) => {
    if (now - st.seen_t >= ui_ms) {
      st.seen_t = now;
      if (!st.shown()) { st.raf = null; st.pause(); return; }
    }
    st.ticks += 1;
    if (st.last === null) st.last = now;
    st.pos += (now - st.last) / 1000 * fps * st.speed();
    st.last = now;
    let f = Math.floor(st.pos);
    if (f > n - 1) {
      if (loop.active) { st.pos = st.pos % n; f = Math.floor(st.pos); }
      else { st.set(n - 1); play.active = false; return; }
    }
    st.show(f, false);
    st.raf = window.requestAnimationFrame(st.tick);
  };
  st.start = () => {
    if (st.raf !== null) return;
    st.pos = (frame.value >= n - 1 && !loop.active) ? 0 : frame.value;
    st.last = null;
    st.raf = window.requestAnimationFrame(st.tick);
  };
  st.stop = () => {
    if (st.raf !== null) window.cancelAnimationFrame(st.raf);
    st.raf = null;
    st.pos = frame.value;
    st.ui(true);
  };
  st.step = (d) => { play.active = false; st.set(Math.min(n - 1, Math.max(0, frame.value + d))); };
  st.faster = (d) => {
    const values = speed.options.map((o) => Array.isArray(o) ? o[0] : o);
    const k = values.indexOf(speed.value);
    speed.value = values[Math.min(values.length - 1, Math.max(0, k + d))];
  };
  st.key = (e) => {
    // The element the key is for (inside a widget's shadow root, not its host).
    const path = e.composedPath ? e.composedPath() : [];
    const target = path[0] || e.target;
    const tag = (target && target.tagName) || "";
    if (["INPUT", "SELECT", "TEXTAREA"].includes(tag) || e.altKey || e.ctrlKey || e.metaKey) return;
    // Keys on a slider move the slider, not the animation.
    if (path.some((el) => el && el.getAttribute && (el.getAttribute("role") === "slider" ||
        (el.classList && el.classList.contains("noUi-handle"))))) return;
    const k = e.key;
    // Space and Enter press the focused button (a tab, a preset), never the player's.
    if (["BUTTON", "A", "SUMMARY"].includes(tag) && [" ", "Spacebar", "Enter"].includes(k)) return;
    if (k === " " || k === "Spacebar") play.active = !play.active;
    else if (k === "ArrowRight") st.step(1);
    else if (k === "ArrowLeft") st.step(-1);
    else if (k === "ArrowUp") st.faster(1);
    else if (k === "ArrowDown") st.faster(-1);
    else if (k === "Home") st.step(-n);
    else if ((k === "l" || k === "L") && path.some((el) => el && el.classList &&
             el.classList.contains(CONTROL))) loop.active = !loop.active;
    else return;
    e.preventDefault();
  };
}
if (!window.__mpf_keys) {
  window.__mpf_keys = true;
  document.addEventListener("visibilitychange", () => {
    if (document.hidden) for (const p of Object.values(window.__mpf_players)) p.pause();
  });
  document.addEventListener("keydown", (e) => {
    const p = window.__mpf_players[window.__mpf_active];
    if (p) p.key(e);
  });
}
window.__mpf_active = frame.id;
"""

#: The frame slider's handle: touch-sized (at least 30 px, the page's ``--mp-handle`` when
#: larger: 44 px on a phone) and kept inside the slider's box at both ends.
HANDLE_CSS = """
.noUi-horizontal .noUi-handle {
  width: max(30px, var(--mp-handle, 30px)) !important;
  height: max(30px, var(--mp-handle, 30px)) !important;
  right: calc(max(30px, var(--mp-handle, 30px)) / -2) !important;
  top: calc((var(--mp-track, 8px) - max(30px, var(--mp-handle, 30px))) / 2 - 1px) !important;
}
.noUi-target {
  width: calc(100% - max(30px, var(--mp-handle, 30px))) !important;
  margin-left: calc(max(30px, var(--mp-handle, 30px)) / 2) !important;
}
"""
#: The speed menu as tall as the page's buttons (44 px on a phone and in projector mode).
SELECT_CSS = "select { min-height: var(--mp-button, 31px) !important; }"

#: Longest interval between updates of the slider and readout while playing [ms]: DOM
#: work (style, layout) that the frames need more. (The readouts are text nodes: as a
#: Div's text, each change laid the whole page out again, half the page's work.)
UI_MS = 250
#: Milliseconds after a served page is up before the player says it is ready (``ready``): the
#: change must reach the browser after the player's models, which a page sends a turn or
#: two later (a page built once opened, a result's new figures).
READY_DELAY_MS = 300


class PlayerFrame(DataModel):
    """The player's current frame: figures follow ``value`` with ``js_on_change``."""

    value = Int(0)


@dataclass
class BrowserPlayer:
    """The widgets of a browser-side player; ``frame.value`` is the current frame."""

    frame: PlayerFrame
    slider: Slider
    play: Toggle
    back: Button
    forward: Button
    first: Button
    speed: Select
    loop: Toggle
    readout: HTML
    shortcuts: Div
    layout: object
    autoplay: bool
    _ready_js: CustomJS
    timeline: ColumnDataSource = None

    def set_times(self, times) -> None:
        """New times for the frames (a new trajectory): in the page the readout follows
        them at the frame on show (which the page alone knows: a paused player keeps its
        frame)."""
        times = np.asarray(times, float)
        if times.shape != (self.n_frames,):
            raise ValueError(f"times has {times.size} values; give one per frame "
                             f"({self.n_frames})")
        self.timeline.data = {"t": times}

    @property
    def n_frames(self) -> int:
        return int(self.slider.end) + 1

    def on_frame(self, callback: CustomJS) -> None:
        """Run ``callback`` whenever the frame changes (``cb_obj.value`` is the frame)."""
        self.frame.js_on_change("value", callback)

    def install(self, doc) -> None:
        """Keyboard shortcuts (and autoplay) once the standalone page is ready."""
        doc.js_on_event(DocumentReady, self._ready_js)

    def ready(self) -> None:
        """The same from the server (inside Panel): a property change the browser sees."""
        self.play.tags = [*self.play.tags, "ready"]


def browser_player(n_frames: int, times=None, fps: float = 30.0, autoplay: bool = False,
                   loop: bool = True, time_label: str = "τ", width: int = 720,
                   name: str = "player", ui_ms: float = UI_MS,
                   responsive: bool = False) -> BrowserPlayer:
    """A browser-side player over ``n_frames`` frames (see the module docstring).

    ``times`` (length ``n_frames``) labels the frames in the readout; at speed 1x the
    player shows ``fps`` frames per second. ``ui_ms``: the slider and readout follow a
    playing animation at most this often (0: every frame, which costs layout work).
    ``responsive``: the buttons wrap and the slider stretches with the page (phones).
    """
    if isinstance(n_frames, bool) or not isinstance(n_frames, (int, np.integer)) or n_frames < 2:
        raise ValueError(f"n_frames={n_frames!r} must be a whole number >= 2")
    if not (isinstance(fps, (int, float)) and 1 <= fps <= 240):
        raise ValueError(f"fps={fps!r} must be a number of frames per second in [1, 240]")
    times = np.arange(n_frames, dtype=float) if times is None else np.asarray(times, float)
    if times.shape != (n_frames,):
        raise ValueError(f"times has {times.size} values; give one per frame ({n_frames})")
    big = dict(height=44, styles={"font-size": "16px"})
    frame = PlayerFrame(value=0, name=f"{name}_frame")
    slider = Slider(start=0, end=n_frames - 1, value=0, step=1, title="frame",
                   show_value=False, width=max(200, width - 260), name=f"{name}_slider",
                   css_classes=[CONTROL_CLASS], height=44, margin=(4, 10, 4, 10))
    play = Toggle(label=PLAY, active=False, button_type="success", width=120, name=f"{name}_play",
                  css_classes=[CONTROL_CLASS], stylesheets=[PLAY_CSS], **big)
    # The page finds the player's element by it (hidden, the player pauses).
    play.html_attributes = {"title": "Play or pause (Space)", "data-player": frame.id}
    back = Button(label="◀ Step", width=96, name=f"{name}_back", css_classes=[CONTROL_CLASS],
                  html_attributes={"title": "One frame back (←)"},
                  **big)
    forward = Button(label="Step ▶", width=96, name=f"{name}_forward",
                     css_classes=[CONTROL_CLASS],
                     html_attributes={"title": "One frame forward (→)"}, **big)
    first = Button(label="|◀ Start", width=96, name=f"{name}_first", css_classes=[CONTROL_CLASS],
                   html_attributes={"title": "Back to the first frame (Home)"}, **big)
    speed = Select(title="speed", value="1", width=90, name=f"{name}_speed",
                   css_classes=[CONTROL_CLASS],
                   options=[(f"{s:g}", f"{s:g}×") for s in SPEEDS],
                   html_attributes={"title": "Playback speed (↑ faster, ↓ slower)"},
                   styles={"font-size": "15px"}, stylesheets=[SELECT_CSS])
    loop_t = Toggle(label="⟳ Loop", active=loop, width=96, name=f"{name}_loop",
                    css_classes=[CONTROL_CLASS],
                    html_attributes={"title": "Start again at the end (L)"}, **big)
    # The frames' times live in a data source, so a new trajectory can relabel them.
    timeline = ColumnDataSource({"t": times}, name=f"{name}_times")
    # The readout's text is a dom.HTML node (app.figures.live_text): a change redraws it
    # alone, not the page.
    readout_box = live_div(_readout(0, n_frames, times[0], time_label), name=f"{name}_readout",
                           width=210, styles={"font-size": "15px"})
    readout = live_html(readout_box)
    shortcuts = Div(text="Keys: " + " · ".join(f"<b>{k}</b> {v}" for k, v in SHORTCUTS),
                    name=f"{name}_keys", styles={"font-size": "13px", "color": "#444",
                                                 # hidden where the page says so (projector)
                                                 "display": "var(--mp-keys, block)"})
    args = dict(frame=frame, slider=slider, readout=readout, play=play, speed=speed,
                loop=loop_t, fps=float(fps), n=int(n_frames), timeline=timeline,
                label=time_label, ui_ms=float(ui_ms))
    play.js_on_change("active", CustomJS(args=args, code=_PRELUDE + f"""
        play.label = play.active ? {PAUSE!r} : {PLAY!r};
        if (play.active) st.start(); else st.stop();"""))
    back.js_on_event("button_click", CustomJS(args=args, code=_PRELUDE + "st.step(-1);"))
    forward.js_on_event("button_click", CustomJS(args=args, code=_PRELUDE + "st.step(1);"))
    first.js_on_event("button_click", CustomJS(args=args, code=_PRELUDE + "st.step(-n);"))
    loop_t.js_on_change("active", CustomJS(args=args, code=_PRELUDE))
    # New times (a new trajectory): the readout names the frame on show at its new time.
    timeline.js_on_change("data", CustomJS(args=args, code=_PRELUDE + "st.ui(true);"))
    speed.js_on_change("value", CustomJS(args=args, code=_PRELUDE))
    # The slider dragged: jump there (the timer, when playing, goes on from there).
    slider.js_on_change("value", CustomJS(args=args, code=_PRELUDE + """
        if (slider.value !== frame.value) st.set(slider.value);"""))
    # Autoplay. In a page sent in a patch, BokehJS draws the views over several turns, and
    # the play button's view throws on a change before it is drawn: then try again soon.
    ready_js = CustomJS(args=dict(**args, autoplay=bool(autoplay)), code=_PRELUDE + """
        // A reader who asked the system for less motion starts the player by hand.
        const still = window.matchMedia && matchMedia("(prefers-reduced-motion: reduce)").matches;
        const go = () => {
          if (!autoplay || still || play.active) return;
          try { play.active = true; }
          catch (error) { play.setv({active: false}, {silent: true}); st.stop(); setTimeout(go, 100); }
        };
        go();""")
    play.js_on_change("tags", ready_js)
    wrap = {"styles": {"flex-wrap": "wrap"}, "sizing_mode": "stretch_width"} if responsive else {}
    if responsive:  # one row that wraps: buttons, then the slider taking what is left
        slider.sizing_mode = "stretch_width"
        slider.width = None
        slider.min_width = 160
        slider.stylesheets = [HANDLE_CSS]  # touch-sized (phones, projectors)
        layout = column(row(play, back, forward, first, speed, loop_t, slider, readout_box, **wrap),
                        shortcuts, name=f"{name}_layout", sizing_mode="stretch_width")
    else:
        layout = column(row(play, back, forward, first, speed, loop_t),
                        row(slider, readout_box), shortcuts, name=f"{name}_layout")
    return BrowserPlayer(frame=frame, slider=slider, play=play, back=back, forward=forward, first=first,
                         speed=speed, loop=loop_t, readout=readout, shortcuts=shortcuts,
                         layout=layout, autoplay=bool(autoplay), _ready_js=ready_js,
                         timeline=timeline)


def _readout(i, n, t, label) -> str:
    return f"frame {i + 1} / {n} · {label} = {t:.2f}"
