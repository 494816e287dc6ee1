"""What a phone user meets, measured in the page: a real phone's emulation (Playwright's
``is_mobile``, touch, device scale factor 3) and scans of the page's text sizes and tap
targets, shadow roots included (Bokeh and Panel draw their widgets inside shadow DOM)."""
from __future__ import annotations

#: A 390 x 844 phone (an iPhone 12-14 class screen), emulated as Chromium does a phone.
PHONE = {"viewport": {"width": 390, "height": 844}, "is_mobile": True, "has_touch": True,
         "device_scale_factor": 3}
#: Smallest text (CSS px) and smallest tap target (CSS px, both sides) on a phone.
MIN_TEXT_PX = 12
MIN_TARGET_PX = 44

# Visible text nodes whose computed font size is below ``min`` and visible controls a
# finger taps (buttons, selects, inputs, slider handles, the controls' card header)
# smaller than ``target`` either way: [{text or what, size, box}]. Elements outside the
# page's width count too (they would have to be scrolled to).
_SCAN_JS = """([min, target]) => {
  const small = [], tiny = [];
  const TAPPABLE = "button, select, input:not([type=hidden]), textarea, .noUi-handle, " +
                   "summary, a[href], .card-header";
  const shown = (el) => {
    for (let e = el; e; e = e.parentElement || (e.getRootNode && e.getRootNode().host)) {
      const s = getComputedStyle(e);
      if (s.display === "none" || s.visibility === "hidden" || s.opacity === "0") return false;
    }
    return true;
  };
  const walk = (root) => {
    for (const el of root.querySelectorAll("*")) {
      if (el.shadowRoot) walk(el.shadowRoot);
      if (["SCRIPT", "STYLE", "TITLE"].includes(el.tagName)) continue;
      for (const node of el.childNodes) {
        if (node.nodeType !== 3 || !node.textContent.trim()) continue;
        const range = document.createRange();
        range.selectNodeContents(node);
        const r = range.getBoundingClientRect();
        if (r.width < 1 || r.height < 1 || !shown(el)) continue;
        const size = parseFloat(getComputedStyle(el).fontSize);
        if (size < min) small.push({text: node.textContent.trim().slice(0, 40), size,
                                    box: [r.left, r.top, r.width, r.height]});
      }
      if (el.matches(TAPPABLE)) {
        const r = el.getBoundingClientRect();
        if (r.width < 1 || r.height < 1 || !shown(el)) continue;
        if (el.matches("input[type=checkbox], input[type=radio]")) continue;  // in a label
        if (Math.min(r.width, r.height) < target - 0.5)
          tiny.push({what: (el.getAttribute("title") || el.textContent || el.className ||
                            el.tagName).trim().slice(0, 40),
                     size: [Math.round(r.width), Math.round(r.height)],
                     box: [r.left, r.top, r.width, r.height]});
      }
    }
  };
  walk(document);
  return {small, tiny, meta: (document.querySelector('meta[name="viewport"]') || {}).content || null,
          scroll_width: document.scrollingElement.scrollWidth, width: window.innerWidth};
}"""


def scan(page, min_text: float = MIN_TEXT_PX, min_target: float = MIN_TARGET_PX) -> dict:
    """``small`` texts, ``tiny`` tap targets, the viewport ``meta`` tag's content, the page's
    ``scroll_width`` and the window's ``width``."""
    return page.evaluate(_SCAN_JS, [min_text, min_target])


# Font sizes (px) of the text drawn on the canvas of every visible Bokeh figure: titles,
# axis labels and ticks, legends, colour bars, labels and text glyphs.
_CANVAS_TEXT_JS = """() => {
  const out = [];
  const px = (v) => {
    const s = (v && typeof v === "object") ? v.value : v;
    return (typeof s === "string" && s.endsWith("px")) ? parseFloat(s) : null;
  };
  for (const m of Bokeh.documents[0].all_models) {
    if (!("x_range" in m) || !("renderers" in m)) continue;
    const view = Bokeh.index.find_one(m);
    if (!view || !view.el || view.el.getBoundingClientRect().width === 0) continue;
    const add = (what, v) => { const s = px(v); if (s !== null) out.push({figure: m.name, what, size: s}); };
    if (m.title && m.title.text) add("title", m.title.text_font_size);
    for (const a of [...m.left, ...m.right, ...m.above, ...m.below, ...m.center]) {
      if ("major_label_text_font_size" in a) add(a.type + " ticks", a.major_label_text_font_size);
      if ("axis_label_text_font_size" in a && a.axis_label) add(a.type + " label", a.axis_label_text_font_size);
      if ("title_text_font_size" in a && a.title) add(a.type + " title", a.title_text_font_size);
      if ("label_text_font_size" in a) add(a.type, a.label_text_font_size);
      if ("text_font_size" in a) add(a.type + " " + (a.name || ""), a.text_font_size);
    }
    for (const r of m.renderers) {
      if (r.glyph && "text_font_size" in r.glyph) add("text " + (r.name || ""), r.glyph.text_font_size);
    }
  }
  return out;
}"""


def canvas_text_sizes(page) -> list[dict]:
    """[{figure, what, size}] of the text on the visible figures' canvases."""
    return page.evaluate(_CANVAS_TEXT_JS)


# Visible figures whose title (its longest line, measured in its font) is wider than the
# figure: [name, title, the title's right end, the figure's width] (CSS px).
_CUT_TITLES_JS = """() => {
  const out = [], ctx = document.createElement("canvas").getContext("2d");
  const value = (p) => (p && typeof p === "object" && "value" in p) ? p.value : p;
  for (const m of Bokeh.documents[0].all_models) {
    if (!("x_range" in m) || !("renderers" in m) || !m.title || !m.title.text) continue;
    const v = Bokeh.index.find_one(m);
    if (!v || !v.el.checkVisibility({visibilityProperty: true, opacityProperty: true})) continue;
    const r = v.el.getBoundingClientRect();
    if (r.width < 1 || r.height < 1) continue;
    const t = m.title, view = v.renderer_views.get(t);
    ctx.font = `${value(t.text_font_style)} ${value(t.text_font_size)} ${value(t.text_font)}`;
    const width = Math.max(...String(t.text).split("\\n").map((l) => ctx.measureText(l).width));
    const left = view && view.bbox ? view.bbox.left : 0;
    if (left + width > r.width + 1)
      out.push([m.name, t.text, Math.round(left + width), Math.round(r.width)]);
  }
  return out;
}"""


def cut_titles(page) -> list:
    """The visible figures whose title runs out of the figure (``_CUT_TITLES_JS``)."""
    return page.evaluate(_CUT_TITLES_JS)
