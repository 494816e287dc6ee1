"""What the page does in the browser itself: the address bar, coarse slider keys and the
screen width.

``PageBehaviour`` is an invisible ``JSComponent`` placed once in the page:

* **Address bar and history.** ``search`` is written by the server (the state's
  ``?k_r=...``, with the result a change brings); the browser pushes it as a history
  entry once it has settled for ``SETTLE_MS`` and only when it differs from the address
  bar (on opening, the address is rewritten in place, as the page read it).
  Back/Forward (``popstate``) send the entry's search string back as ``popped``
  (``pops`` counts them, so the same entry twice is seen twice); the page then restores
  that state and writes it back as ``replace_search``, which replaces the entry (no new
  one, so Forward still works). ``acked`` tells which steps the server has restored; an
  address the server wrote before the latest step arrives late and is dropped, so quick
  Back/Back/Forward never rewrites the wrong entry. Panel's own ``pn.state.location``
  pushes on every change and never reports Back, which is why it is not used for this.
* **PageUp/PageDown on a slider** move it by a tenth of its range (rounded to its step),
  whatever its arrow-key step; noUiSlider's own page step is 5 arrow steps and cannot be
  changed after Bokeh creates it.
* **"Figure (SVG)" buttons** (``app.views.export.svg_button``, CSS class
  ``SVG_BUTTON_CLASS``): a click saves the button's figures (``svg_exports``, by the
  button's ``export-<css>`` class) through the server's page code
  (``window.mp_export_svg``, ``app/edge.py``); without it, the reader is pointed to the
  toolbar's save tool. Answered here, in the click itself: the browser allows the
  downloads it starts.
* **Narrow screens.** ``narrow`` is True when the page is first shown on a screen
  narrower than ``NARROW_PX`` (a phone): the page folds its controls away there.
"""
from __future__ import annotations

import param
from panel.custom import JSComponent

#: Widest screen (CSS px) that gets the phone layout; the stylesheet uses the same bound.
NARROW_PX = 700
#: The address bar's new state becomes a history entry once it has settled this long (ms):
#: one entry per state the reader stopped at, not one per key press of a drag.
SETTLE_MS = 400

#: The "Figure (SVG)" buttons (``app.views.export.svg_button``), by their CSS class
#: (``export-<css>``): the figures each saves, by their Bokeh ``name`` (none: every figure
#: on screen).
SVG_EXPORTS = {"page-svg": (), "map-svg": ("regime_map",), "load-svg": ("load",),
               "array-svg": ("array_top", "array_live_panel")}
#: The CSS class that marks a "Figure (SVG)" button for the page's code.
SVG_BUTTON_CLASS = "svg-export"


class PageBehaviour(JSComponent):
    """Browser-side behaviour of the page (address bar, history, slider page keys,
    SVG buttons)."""

    search = param.String(default="", doc="the state's URL search string, '?k_r=...'")
    replace_search = param.String(default="", doc="a search string that replaces the current "
                                  "history entry (a restored state written canonically)")
    popped = param.String(default="", doc="the search string of the entry Back/Forward showed")
    pops = param.Integer(default=0, doc="how many Back/Forward steps the page has seen")
    acked = param.Integer(default=0, doc="the Back/Forward steps the server has restored: "
                          "an address written before the latest step is stale and dropped")
    narrow = param.Boolean(default=False, doc="first shown on a screen < NARROW_PX wide")
    page_fraction = param.Number(default=0.1, bounds=(0.01, 1.0),
                                 doc="PageUp/PageDown move a slider by this part of its range")
    svg_exports = param.Dict(default={f"export-{css}": list(names)
                                      for css, names in SVG_EXPORTS.items()}, constant=True,
                             doc="the figures each SVG button saves, by its CSS class")

    _esm = """
    function sliderOf(path) {
      // The slider's own element (the first shadow host on the path from the handle) and
      // the Bokeh slider model carrying its CSS classes (``ctl-k_r``, ...).
      if (!window.Bokeh || !path.some((el) => el.classList && el.classList.contains("noUi-handle")))
        return null;
      const host = path.find((el) => el.shadowRoot);
      if (!host) return null;
      for (const doc of Bokeh.documents) {
        for (const m of doc.all_models) {
          if (!/Slider$/.test(m.type) || typeof m.value !== "number") continue;
          const classes = m.css_classes || [];
          if (classes.length && classes.every((c) => host.classList.contains(c))) return m;
        }
      }
      return null;
    }

    export function render({ model, el }) {
      el.style.display = "none";
      let settling = null;  // the address waiting to settle (push)
      const onPop = () => {
        clearTimeout(settling);  // an address of the state left behind: not an entry
        model.popped = window.location.search;
        model.pops = model.pops + 1;
      };
      const onKey = (event) => {
        if (event.key !== "PageUp" && event.key !== "PageDown") return;
        const slider = sliderOf(event.composedPath());
        if (slider === null || slider.disabled) return;
        event.preventDefault();
        event.stopPropagation();
        const span = slider.end - slider.start;
        const sign = event.key === "PageUp" ? 1 : -1;
        const step = slider.step > 0 ? slider.step : span / 100;
        let value = slider.value + sign * model.page_fraction * span;
        value = slider.start + Math.round((value - slider.start) / step) * step;
        value = Math.min(Math.max(value, slider.start), slider.end);
        slider.value = value;
        if ("value_throttled" in slider) slider.value_throttled = value;
      };
      const onClick = (event) => {
        // A "Figure (SVG)" button: its host carries SVG_CLASS and its export-<css> class.
        const path = event.composedPath();
        if (!path.some((el) => el.tagName === "BUTTON")) return;
        const host = path.find((el) => el.classList && el.classList.contains("SVG_CLASS"));
        const table = model.svg_exports;  // an object, or a Map as BokehJS may decode it
        const names = (c) => (table instanceof Map ? table.get(c) : table[c]);
        const key = host && [...host.classList].find((c) => names(c) !== undefined);
        if (!key) return;
        if (typeof window.mp_export_svg === "function")
          window.mp_export_svg([...names(key)], "");
        else alert("Save a figure with the save tool of its toolbar.");
      };
      const write = (search, replace) => {
        if (!search || search === window.location.search) return;
        // Written before the server saw the latest Back/Forward: it would overwrite the
        // entry now shown (or cut off the Forward entries), so it is dropped.
        if (model.acked < model.pops) return;
        const url = window.location.pathname + search + window.location.hash;
        if (replace) window.history.replaceState({}, "", url);
        else window.history.pushState({}, "", url);
      };
      // The server writes the address with each answer: the history gets an entry once
      // the address and the reader's input have settled for SETTLE_MS (one per state the
      // reader stopped at; keys held or pressed in a run restart the wait).
      const settle = () => {
        clearTimeout(settling);
        settling = setTimeout(() => { settling = null; write(model.search, false); }, SETTLE_MS);
      };
      const push = settle;
      const onInput = () => { if (settling !== null) settle(); };
      const replace = () => { clearTimeout(settling); write(model.replace_search, true); };
      window.addEventListener("popstate", onPop);
      window.addEventListener("keydown", onKey, true);
      window.addEventListener("click", onClick);
      for (const kind of ["keydown", "pointerdown", "pointerup"])
        window.addEventListener(kind, onInput, true);
      model.on("search", push);
      model.on("replace_search", replace);
      model.on("remove", () => {
        window.removeEventListener("popstate", onPop);
        window.removeEventListener("keydown", onKey, true);
        window.removeEventListener("click", onClick);
        for (const kind of ["keydown", "pointerdown", "pointerup"])
          window.removeEventListener(kind, onInput, true);
      });
      model.narrow = window.innerWidth < NARROW;
      write(model.search, true);  // the address as the page reads it, with no new entry
    }
    """.replace("NARROW", str(NARROW_PX)).replace("SETTLE_MS", str(SETTLE_MS)) \
        .replace("SVG_CLASS", SVG_BUTTON_CLASS)
