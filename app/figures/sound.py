"""Sound for the browser-side player: the support's motion heard, off until asked for.

The page maps each frame of one contact to a tone (``TONES_JS``, the mapping, defined here
once and run in the browser from the frames it already holds, so a slider move sends no
sound data):

* pitch follows the support's speed on the slab |v_R| (``v_R = v - (1, 0)``, Eq. 4):
  the trajectory's own slowest frame sounds at ``PITCH_HZ[0]`` (220 Hz), its fastest at
  ``PITCH_HZ[1]`` (880 Hz), on a log scale (equal steps of speed are equal musical
  intervals), so sticking (|v_R| near 0) is a low steady note and slipping a rising one;
  a trajectory of constant speed sounds at the geometric mean;
* the tone is panned by the sideways friction on the support F_f,y / f_N (Eq. 4): left
  for -y, right for +y, scaled by the trajectory's own largest |F_f,y| so the pan spans
  [-1, 1] and no sideways friction stays in the middle.

``add_sound(player, frames)`` puts a ``Toggle`` (``SOUND_LABEL``, named ``SOUND_NAME`` for
screen readers) in the player's row and attaches Web Audio to the player's per-frame
callback (``player.on_frame``): no server round trip per frame. ``frames`` is the player's
``support_frames`` source (columns ``v_R`` and ``F_y``, one row per frame). The
``AudioContext`` is made only when the reader switches the sound on (browsers allow audio
after a gesture), the tone is silent while the player is paused, and switching it off
stops the oscillator and closes the context. The page exposes ``window.__mp_sound``
(read-only: ``running``, ``frequency``, ``pan``, ``frame``, ``context``, ``oscillator_hz``,
``gain``) so a test can hear what a reader hears.
"""
from __future__ import annotations

from bokeh.models import ColumnDataSource, CustomJS, Toggle

from .player import CONTROL_CLASS, BrowserPlayer

__all__ = ["PITCH_HZ", "SOUND_NAME", "SOUND_LABEL", "TONES_JS", "add_sound"]

#: Tone at the trajectory's slowest and fastest |v_R| [Hz] (a log scale between them).
PITCH_HZ = (220.0, 880.0)
#: Loudness of the tone while playing (gain of the Web Audio graph, 1 = full scale).
GAIN = 0.08
#: Time constant of the glide to each frame's pitch, pan and loudness [s] (no clicks).
GLIDE_S = 0.02
SOUND_LABEL = "♪ Sound"
#: The toggle's accessible name (and tooltip).
SOUND_NAME = "Sound: pitch follows the support's speed, left/right the sideways friction"


#: Each frame's tone from the frames' speeds and sideways forces: a JavaScript function
#: ``(v_R, F_y, lo, hi) -> {hz, pan}`` (see the module; ``lo, hi = PITCH_HZ``).
TONES_JS = """
(function (v_R, F_y, lo, hi) {
  const n = v_R.length, speed = Array.from(v_R, Math.abs), hz = new Array(n),
        pan = new Array(n);
  let vmin = Infinity, vmax = -Infinity, largest = 0;
  for (let i = 0; i < n; i++) {
    vmin = Math.min(vmin, speed[i]); vmax = Math.max(vmax, speed[i]);
    largest = Math.max(largest, Math.abs(F_y[i]));
  }
  const span = vmax - vmin;
  for (let i = 0; i < n; i++) {
    const u = span > 0 ? (speed[i] - vmin) / span : 0.5;
    hz[i] = lo * Math.pow(hi / lo, u);
    pan[i] = largest > 0 ? Math.min(1, Math.max(-1, F_y[i] / largest)) : 0;
  }
  return {hz: hz, pan: pan};
})"""


# The sound's state lives in the page (window.__mp_sound_reg, keyed by the toggle's id);
# every callback makes sure it exists first.
_PRELUDE = """
const reg = (window.__mp_sound_reg = window.__mp_sound_reg || {});
let s = reg[toggle.id];
if (s === undefined) {
  s = reg[toggle.id] = {ctx: null, osc: null, panner: null, amp: null, hz: null, pan: null,
                        frame: -1, from: null, tones: null};
  // Each frame's tone, worked out again only when the frames change.
  s.tone = () => {
    const d = frames.data;
    if (s.from !== d) {
      s.from = d;
      s.tones = (d.v_R && d.v_R.length && d.F_y && d.F_y.length === d.v_R.length)
        ? TONES(d.v_R, d.F_y, pitch[0], pitch[1]) : null;
    }
    return s.tones;
  };
  s.level = () => (toggle.active && play.active) ? gain : 0;
  s.apply = () => {
    if (s.ctx === null) return;
    const d = s.tone(), t = s.ctx.currentTime;
    if (d !== null) {
      const i = Math.min(Math.max(frame.value, 0), d.hz.length - 1);
      s.frame = i; s.hz = d.hz[i]; s.pan = d.pan[i];
      s.osc.frequency.setTargetAtTime(s.hz, t, glide);
      s.panner.pan.setTargetAtTime(s.pan, t, glide);
    }
    s.amp.gain.setTargetAtTime(s.level(), t, glide);
  };
  s.open = () => {
    const AC = window.AudioContext || window.webkitAudioContext;
    if (!AC || s.ctx !== null) return;
    s.ctx = new AC();
    s.osc = s.ctx.createOscillator();
    s.panner = s.ctx.createStereoPanner();
    s.amp = s.ctx.createGain();
    s.amp.gain.value = 0;
    s.osc.connect(s.amp).connect(s.panner).connect(s.ctx.destination);
    s.osc.start();
    if (s.ctx.state === "suspended") s.ctx.resume();
    s.apply();
  };
  s.close = () => {
    if (s.ctx === null) return;
    try { s.osc.stop(); } catch (error) {}
    s.osc.disconnect();
    s.ctx.close();
    s.ctx = s.osc = s.panner = s.amp = null;
  };
  // The button's pressed state for screen readers (its accessible name is set by the page):
  // whether the sound is on, however it changed (a click, the keyboard, the page itself),
  // on every button drawn for the toggle (a button drawn again later: app.views.access).
  s.pressed = () => {
    const visit = (root) => {
      for (const el of root.querySelectorAll("*")) {
        if (!el.shadowRoot) continue;
        if (el.getAttribute("data-sound") === toggle.id) {
          for (const button of el.shadowRoot.querySelectorAll("button"))
            if (button.getAttribute("aria-pressed") !== String(toggle.active))
              button.setAttribute("aria-pressed", String(toggle.active));
        }
        visit(el.shadowRoot);
      }
    };
    visit(document);
  };
  window.__mp_sound = Object.freeze({
    get running() { return s.ctx !== null && s.ctx.state === "running" && s.level() > 0; },
    get frequency() { return s.ctx === null ? null : s.hz; },
    get pan() { return s.ctx === null ? null : s.pan; },
    get frame() { return s.frame; },
    get oscillator_hz() { return s.osc === null ? null : s.osc.frequency.value; },
    get gain() { return s.amp === null ? null : s.amp.gain.value; },
    get context() { return s.ctx === null ? "none" : s.ctx.state; },
  });
}
"""
_PRELUDE = _PRELUDE.replace("TONES(", TONES_JS.strip() + "(")


def add_sound(player: BrowserPlayer, frames: ColumnDataSource) -> Toggle:
    """A sound toggle in ``player``'s row, playing ``frames`` (the player's frames, columns
    ``v_R`` and ``F_y``, one row per frame; replace its data for a new trajectory)."""
    toggle = Toggle(label=SOUND_LABEL, active=False, width=110, height=44,
                    name=f"{player.frame.name.removesuffix('_frame')}_sound",
                    css_classes=[CONTROL_CLASS], styles={"font-size": "16px"},
                    html_attributes={"title": SOUND_NAME, "data-aria-label": SOUND_NAME})
    toggle.html_attributes = {**toggle.html_attributes, "data-sound": toggle.id}
    args = dict(toggle=toggle, play=player.play, frame=player.frame, frames=frames,
                pitch=list(PITCH_HZ), gain=GAIN, glide=GLIDE_S)
    toggle.js_on_change("active", CustomJS(args=args, code=_PRELUDE + """
        if (toggle.active) s.open(); else s.close();
        s.pressed();"""))
    follow = CustomJS(args=args, code=_PRELUDE + "s.apply();")
    player.on_frame(follow)
    player.play.js_on_change("active", follow)
    frames.js_on_change("data", follow)
    buttons = player.layout.children[0]
    at = buttons.children.index(player.loop) + 1
    buttons.children = [*buttons.children[:at], toggle, *buttons.children[at:]]
    return toggle
