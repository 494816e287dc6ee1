"""Projector mode as a class sees it: at 1280x720 and 1920x1080 with ``?projector=1``, on
every tab, the page never scrolls sideways, the main figure is drawn at least as large as
in normal mode, every figure's text is at least the projector minimum, legends, titles,
colour bars lie inside their figure, no figure's title and no button's caption runs out
of its box, and the headline is above the fold. Projected or not, the top view's arrow
labels and the polar diagrams' ring and angle labels lie inside their figure (a glyph's
text: inside its frame) and do not overlap, named ticks ("W so far", "its split") do not
run into each other and colour scales have a readable length. Every tab, normal and projected, on both
screens, is saved as a screenshot to ``$MICROPILLAR_SCREENSHOTS`` (default: a temporary
folder) for a person to look at, as the pages go from tab to tab.

Sizes are read in the page: the Bokeh views' boxes (``Bokeh.index``), their frames (the
drawn plot area) and their annotations' boxes.
"""
from __future__ import annotations

import re

import pytest

from app.figures.common import MIN_TEXT_PX, PROJECTOR_SCALE

from . import page_tools as pt
from . import phone_tools, still

pytestmark = [pytest.mark.browser, pytest.mark.timeout(600)]

SCREENS = {"1280x720": {"width": 1280, "height": 720},
           "1920x1080": {"width": 1920, "height": 1080}}
#: tab key -> (tab-bar label, its main figure or None)
TABS = {"support": ("One support", "scene"), "array": ("Array", "array_top"),
        "polar": ("Orientation (polar)", "polar_FTx"), "map": ("Regime map", "regime_map"),
        "load": ("Load", "load"), "equations": ("Equations", None),
        "design": ("Design", "design_map")}
PROJECTOR_MIN_PX = MIN_TEXT_PX * PROJECTOR_SCALE
#: A colour scale's length (px) at the least: a bar a reader can read colours off.
MIN_COLOUR_SCALE_PX = 120

# The visible figures: page box, frame (drawn plot area, in the figure's canvas), and the
# boxes of their legends, titles and colour bars; the text boxes of the top view's arrow
# labels (from the label data through the frame's scales, measured with the label font).
_FIGURES_JS = """() => {
  const out = {};
  const ctx = document.createElement("canvas").getContext("2d");
  for (const m of Bokeh.documents[0].all_models) {
    if (!("x_range" in m) || !("renderers" in m)) continue;
    const v = Bokeh.index.find_one(m);
    if (!v || !v.el.checkVisibility({visibilityProperty: true, opacityProperty: true}))
      continue;
    const r = v.el.getBoundingClientRect();
    if (r.width < 1 || r.height < 1) continue;
    const f = v.frame.bbox;
    const parts = [];
    for (const [model, view] of v.renderer_views) {
      if (!["Legend", "Title", "ColorBar"].includes(model.type) || !view.bbox) continue;
      const b = view.bbox;
      const empty = model.type === "Legend" && !model.items.some((i) => i.visible !== false);
      if (!(b.width > 0 && b.height > 0 && !empty)) continue;
      const part = {what: model.type, box: [b.left, b.top, b.width, b.height]};
      if (model.type === "ColorBar") {  // its drawn length: its panel's, or the one it was given
        const across = model.orientation === "horizontal" ||
          (model.orientation === "auto" && b.width > b.height);
        const given = across ? model.width : model.height;
        part.length = typeof given === "number" ? given : across ? b.width : b.height;
      }
      parts.push(part);
    }
    const labels = [];
    for (const a of m.center) {
      if (a.name !== "scene_arrow_labels") continue;
      const data = a.source.data instanceof Map ? Object.fromEntries(a.source.data) : a.source.data;
      const size = parseFloat(a.text_font_size.value ?? a.text_font_size);
      ctx.font = `${size}px sans-serif`;
      const xs = v.frame.x_scale, ys = v.frame.y_scale;
      for (let i = 0; i < data.text.length; i++) {
        const w = ctx.measureText(data.text[i]).width, h = size;
        const x = xs.compute(data.x[i]), y = ys.compute(data.y[i]);
        const left = data.align[i] === "right" ? x - w : data.align[i] === "center" ? x - w / 2 : x;
        const top = data.baseline[i] === "top" ? y : data.baseline[i] === "bottom" ? y - h : y - h / 2;
        labels.push({text: data.text[i], box: [left, top, w, h]});
      }
    }
    // The polar diagrams' ring and angle labels: text glyphs, drawn clipped to the frame.
    for (const r of m.renderers) {
      const g = r.glyph, src = r.data_source;
      if (!g || g.type !== "Text" || !/_(ring|angle)_labels$/.test((src && src.name) || ""))
        continue;
      const data = src.data instanceof Map ? Object.fromEntries(src.data) : src.data;
      const size = parseFloat(g.text_font_size.value ?? g.text_font_size);
      ctx.font = `${size}px ${g.text_font.value ?? g.text_font}`;
      const xs = v.frame.x_scale, ys = v.frame.y_scale;
      for (let i = 0; i < data.text.length; i++) {
        const w = ctx.measureText(data.text[i]).width;
        const x = xs.compute(data.x[i]), y = ys.compute(data.y[i]);
        labels.push({text: data.text[i], box: [x - w / 2, y - size / 2, w, size], clip: true});
      }
    }
    // Named ticks under the plot ("W so far", "its split"): their text boxes, across.
    const ticks = [];
    for (const axis of m.below) {
      const names = axis.major_label_overrides, fixed = axis.ticker && axis.ticker.ticks;
      if (!names || !fixed || !(names instanceof Map ? names.size : Object.keys(names).length))
        continue;
      const name = (t) => names instanceof Map ? (names.get(t) ?? names.get(String(t))) : names[t];
      const size = parseFloat(axis.major_label_text_font_size.value ?? axis.major_label_text_font_size);
      ctx.font = `${size}px sans-serif`;
      for (const t of fixed) {
        const text = name(t);
        if (text == null) continue;
        const w = ctx.measureText(text).width, x = v.frame.x_scale.compute(t);
        ticks.push({text, box: [x - w / 2, 0, w, size]});
      }
    }
    out[m.name] = {page: [r.left, r.top, r.width, r.height],
                   frame: [f.left, f.top, f.width, f.height], parts, labels, ticks};
  }
  return out;
}"""


# Visible buttons whose text is wider than the button, or that are wider than the box the
# layout gave them (drawn over their neighbour): [text, text or button width, box width].
_CUT_BUTTONS_JS = """() => {
  const out = [];
  const walk = (root) => {
    for (const el of root.querySelectorAll(".bk-btn")) {
      if (!el.checkVisibility()) continue;
      const host = el.getRootNode().host, r = el.getBoundingClientRect();
      const box = host ? host.getBoundingClientRect() : r;
      if (el.scrollWidth > el.clientWidth + 1)
        out.push([el.textContent.trim(), el.scrollWidth, el.clientWidth]);
      else if (r.right > box.right + 1)
        out.push([el.textContent.trim(), r.width, box.width]);
    }
    for (const el of root.querySelectorAll("*")) if (el.shadowRoot) walk(el.shadowRoot);
  };
  walk(document);
  return out;
}"""


def _inside(inner, outer, slack=1.0) -> bool:
    return (inner[0] >= outer[0] - slack and inner[1] >= outer[1] - slack
            and inner[0] + inner[2] <= outer[0] + outer[2] + slack
            and inner[1] + inner[3] <= outer[1] + outer[3] + slack)


def _overlap(a, b) -> bool:
    return (a[0] < b[0] + b[2] and b[0] < a[0] + a[2]
            and a[1] < b[1] + b[3] and b[1] < a[1] + a[3])


def _show(page, url: str, tab: str, switch: bool = False) -> dict:
    """Open ``url`` on ``tab`` (``switch``: the page shows ``url`` already; its tab bar
    opens ``tab``, as a class goes from tab to tab); the visible figures at rest."""
    if switch:
        pt.open_tab(page, "^" + re.escape(TABS[tab][0]), tab)
    else:
        pt.wait_for_app(page, f"{url}&tab={tab}" if "?" in url else f"{url}?tab={tab}", 90_000)
    main = TABS[tab][1]
    if main:
        pt.wait_for_plot(page, main, 60_000)
    else:  # the equations, typeset by MathJax once shown
        page.locator(".equations mjx-container").first.wait_for(state="visible")
    pt.settle(page, quiet_ms=1000, timeout_ms=30_000)
    page.wait_for_timeout(500)
    return page.evaluate(_FIGURES_JS)


class Shown:
    """The module's page of a screen size, on the address and tab a test asks for. A page
    opened on an address goes from tab to tab with its tab bar; the tests that only read it
    leave it as it was shown, so a test asking for the address and tab it shows reads it as
    it is. Each (mode, tab) shown is photographed once, as first shown, into ``photos``
    (``folder``/``<tab>_<normal|projector>_<size>.png``)."""

    def __init__(self, page, folder=None, size: str = "", photos: dict | None = None):
        self.page, self.url, self.tab, self.figures = page, None, None, None
        self.folder, self.size = folder, size
        self.photos = {} if photos is None else photos

    def show(self, url: str, tab: str) -> dict:
        """The page on ``url`` at ``tab``; its visible figures at rest."""
        if (url, tab) != (self.url, self.tab):
            switch, self.tab = url == self.url, None  # a failed show leaves nothing taken
            self.url = None
            self.figures = _show(self.page, url, tab, switch)
            self.url, self.tab = url, tab
            mode = "projector" if "projector=1" in url else "normal"
            if self.folder is not None and (mode, tab) not in self.photos:
                self.photos[mode, tab] = still.shoot(
                    self.page, self.folder / f"{tab}_{mode}_{self.size}.png")
        return self.figures

    def changed(self) -> None:
        """The page was changed (scrolled, clicked): it is opened again when next asked."""
        self.url = self.tab = None


@pytest.fixture(scope="module")
def folder():
    return still.shots_dir()


@pytest.fixture(scope="module", params=list(SCREENS))
def screen(request, browser, app_url, folder):
    """Per screen size: every tab's figures in normal mode, and a projector-mode page."""
    size, photos = SCREENS[request.param], {}
    normal = browser.new_context(viewport=size)
    shown = Shown(normal.new_page(), folder, request.param, photos)
    measured = {tab: shown.show(app_url, tab) for tab in TABS}
    normal.close()
    projected = browser.new_context(viewport=size)
    projected.set_default_timeout(60_000)
    yield size, measured, Shown(projected.new_page(), folder, request.param, photos)
    projected.close()


@pytest.mark.parametrize("tab", list(TABS))
def test_projector_mode_helps_every_tab(screen, app_url, tab):
    size, normal, shown = screen
    figures, page = shown.show(f"{app_url}?projector=1", tab), shown.page
    found = phone_tools.scan(page, min_text=0, min_target=0)
    assert found["scroll_width"] <= size["width"], \
        f"{tab}: the page scrolls sideways ({found['scroll_width']} > {size['width']} px)"

    headline = page.locator(".headline").first
    if headline.is_visible():
        box = headline.bounding_box()
        assert box["y"] + min(box["height"], 40) <= size["height"], f"{tab}: headline below the fold"

    main = TABS[tab][1]
    if main:
        assert main in figures, f"{tab}: {main} not shown (shown: {sorted(figures)})"
        _, _, w, h = figures[main]["frame"]
        _, _, w0, h0 = normal[tab][main]["frame"]
        print(f"{tab} {size['width']}x{size['height']}: {main} drawn {w:.0f}x{h:.0f} px "
              f"projected, {w0:.0f}x{h0:.0f} px normal")
        # The area at least as large; its shorter side may give a little to the larger
        # headline above it, never much (a sliver is no larger figure).
        assert w * h >= 0.97 * w0 * h0 and min(w, h) >= 0.85 * min(w0, h0), \
            f"{tab}: {main} is drawn smaller projected ({w:.0f}x{h:.0f}) than normal ({w0:.0f}x{h0:.0f})"
        top = figures[main]["page"][1]
        assert top < size["height"] * 0.5, f"{tab}: {main} starts at {top:.0f} px"

    small = [t for t in phone_tools.canvas_text_sizes(page)
             if t["figure"] in figures and t["size"] < PROJECTOR_MIN_PX - 0.5]
    assert not small, f"{tab}: figure text under {PROJECTOR_MIN_PX:g} px projected: {small[:6]}"

    for name, fig in figures.items():
        canvas = [0, 0, fig["page"][2], fig["page"][3]]
        out = [p for p in fig["parts"] if not _inside(p["box"], canvas)]
        assert not out, f"{tab}: {name}'s {[p['what'] for p in out]} run out of the figure: {out}"
    for mode, drawn in (("projected", figures), ("normal", normal.get(tab, {}))):
        for name, fig in drawn.items():
            canvas = [0, 0, fig["page"][2], fig["page"][3]]
            labels = fig["labels"]
            for label in labels:  # a glyph's text is clipped to the frame, a label to the canvas
                room = fig["frame"] if label.get("clip") else canvas
                assert _inside(label["box"], room), \
                    f"{tab} ({mode}): {name}'s label {label} is cut off"
            for i, a in enumerate(labels):
                for b in labels[i + 1:]:
                    assert not _overlap(a["box"], b["box"]), (
                        f"{tab} ({mode}): {name}'s labels {a['text']!r} and {b['text']!r} "
                        f"overlap: {a}, {b}")
    for mode, drawn in (("projected", figures), ("normal", normal.get(tab, {}))):
        for name, fig in drawn.items():
            for bar in (p for p in fig["parts"] if p["what"] == "ColorBar"):
                assert bar["length"] >= MIN_COLOUR_SCALE_PX, \
                    f"{tab} ({mode}): {name}'s colour scale is {bar['length']:.0f} px long"
            ticks = fig["ticks"]
            for i, a in enumerate(ticks):
                for b in ticks[i + 1:]:
                    assert not _overlap(a["box"], b["box"]), \
                        f"{tab} ({mode}): {name}'s ticks {a['text']!r} and {b['text']!r} overlap"
    titles = phone_tools.cut_titles(page)
    assert not titles, f"{tab}: figure titles run out of their figure projected: {titles}"
    cut = page.evaluate(_CUT_BUTTONS_JS)
    assert not cut, f"{tab}: button text runs out of its button projected: {cut}"


# Projected first: the projected Design page the tab's test (just before) opened is read.
@pytest.mark.parametrize("mode", ["projected", "normal"])
def test_design_field_captions_fit_their_fields(screen, app_url, mode):
    """The distribution editor's captions, with their help marks, stay within their own
    field, projected (larger text) or not: none runs into the next one ("θ₀, mean [°] ?"
    over "κ")."""
    size, _normal, shown = screen
    shown.show(f"{app_url}?projector=1" if mode == "projected" else app_url, "design")
    page = shown.page
    shown.changed()  # scrolled below
    page.locator(".ctl-dist_deg").first.scroll_into_view_if_needed()
    page.wait_for_timeout(300)
    boxes = page.evaluate("""(names) => {
      const out = [], fields = [];
      const walk = (root) => { for (const el of root.querySelectorAll("*")) {
        if (el.classList && names.some((n) => el.classList.contains(n))) fields.push(el);
        if (el.shadowRoot) walk(el.shadowRoot); } };
      walk(document);
      for (const field of fields) {
        const label = field.shadowRoot && field.shadowRoot.querySelector("label");
        if (!label || !label.textContent.trim()) continue;
        const f = field.getBoundingClientRect();
        // The caption's text, as drawn (its box may be the field's width).
        const range = document.createRange(); range.selectNodeContents(label);
        const t = range.getBoundingClientRect();
        out.push({text: label.textContent.trim(), field: [f.left, f.top, f.width, f.height],
                  caption: [t.left, t.top, t.width, t.height]});
      }
      return out;
    }""", [f"ctl-{n}" for n in ("dist_family", "dist_deg", "dist_kappa", "dist_psi",
                                "dist2_family", "dist2_deg", "dist2_kappa", "mix_weight")])
    assert len(boxes) >= 8, f"the distribution editor's fields were not found: {boxes}"
    for b in boxes:
        assert _inside(b["caption"], b["field"], slack=2.0), \
            f"{size} ({mode}): the caption {b['text']!r} runs out of its field: {b}"


def test_every_tab_is_photographed_normal_and_projected(screen, app_url, folder):
    """The screenshots: every tab, normal and projected (those the tests above did not
    show are shown now)."""
    _size, _normal, shown = screen
    for tab in (t for t in TABS if ("projector", t) not in shown.photos):
        shown.show(f"{app_url}?projector=1", tab)
    photos = shown.photos
    print(f"{len(photos)} screenshots in {folder}")
    assert set(photos) == {(mode, tab) for mode in ("normal", "projector") for tab in TABS}
    small = {k: p.stat().st_size for k, p in photos.items() if p.stat().st_size <= 10_000}
    assert not small, f"screenshots of (almost) nothing: {small}"
