"""Shared look of the dashboard's Bokeh figures, and in-place updates of their data.

Every figure function builds a complete figure from plain data; its data sources carry
``name``s so a view can later replace their ``.data`` in place (no new figure, so zoom and
axes are kept and nothing flickers; a source whose data did not change is not sent again)
and browser tests can find them in ``Bokeh.documents[0]``. ``style`` switches a figure
between screen and projector mode.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import (ColorBar, ColumnDataSource, CompositeRenderer, CustomJS, GlyphRenderer,
                          Label, LabelSet, Legend, Span, Text, Title)
from bokeh.plotting import figure

#: Okabe-Ito colours: distinguishable with colour-blindness and on a projector.
BLUE, ORANGE, GREEN, VERMILION = "#0072B2", "#E69F00", "#009E73", "#D55E00"
PURPLE, SKY, YELLOW, BLACK, GREY = "#CC79A7", "#56B4E9", "#F0E442", "#000000", "#777777"
REGIME_COLORS = {"pendulum": BLUE, "slider": VERMILION, "stiff": GREEN, "soft": PURPLE}

TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
LINE = 2.0
#: Smallest text on a figure (px, screen mode): readable on a phone as on a laptop.
MIN_TEXT_PX = 12
#: Text sizes in projector mode: this many times the screen's.
PROJECTOR_SCALE = 1.5


def new_figure(name: str, title: str, width: int, height: int, tools: str = TOOLS, **kwargs):
    """A figure with the dashboard's tools (save included) and styling."""
    fig = figure(name=name, title=title, width=width, height=height, tools=tools,
                 toolbar_location="right", **kwargs)
    fig.toolbar.logo = None
    fig.toolbar.autohide = True
    fig.title.text_font_size = f"{MIN_TEXT_PX + 1}px"
    style(fig, False)
    return fig


def source(name: str, data: dict) -> ColumnDataSource:
    return ColumnDataSource(data=data, name=name)


def sources(fig) -> dict:
    """The named data sources of ``fig`` (glyphs' and annotations'): name -> source."""
    named = {}
    for model in _renderers(fig):
        src = model.data_source if isinstance(model, GlyphRenderer) else getattr(model, "source", None)
        if isinstance(src, ColumnDataSource) and src.name:
            named[src.name] = src
    return named


def _renderers(fig):
    """Everything ``fig`` draws: its renderers (glyphs, an annotation placed among them),
    its annotations and the parts of a group of them (``animated_group``)."""
    found = []

    def walk(models):
        for model in models:
            found.append(model)
            if isinstance(model, CompositeRenderer):
                walk(model.renderers)
    walk((*fig.renderers, *fig.center, *fig.above, *fig.below, *fig.left, *fig.right))
    return tuple(found)


def annotation(fig, name: str):
    """The annotation (Label, Span, ...) of ``fig`` called ``name``, or None."""
    for model in _renderers(fig):
        if not isinstance(model, GlyphRenderer) and getattr(model, "name", None) == name:
            return model
    return None


def update(named: dict, data: dict) -> None:
    """Replace the data of named sources: ``named`` from ``sources``, ``data`` name -> dict.

    A source whose new columns equal those it holds is left alone: Bokeh would send its
    every column to the page again (a message part per array), for nothing."""
    for name, columns in data.items():
        if not same_columns(named[name].data, columns):
            named[name].data = columns


def same_columns(old: dict, new: dict) -> bool:
    """Whether two sources' data are equal: the same columns, each of the same kind
    (array or list) and values (NaN counts as a change)."""
    if old.keys() != new.keys():
        return False
    for key, value in new.items():
        before = old[key]
        if isinstance(value, np.ndarray) or isinstance(before, np.ndarray):
            if not (isinstance(value, np.ndarray) and isinstance(before, np.ndarray)
                    and value.dtype == before.dtype and np.array_equal(value, before)):
                return False
        elif type(value) is not type(before) or not _equal(value, before):
            return False
    return True


def _equal(a, b) -> bool:
    try:
        return bool(a == b)
    except ValueError:  # lists holding arrays: compared member by member
        return len(a) == len(b) and all(np.array_equal(x, y) for x, y in zip(a, b))


#: The level of what a player moves every frame (``animated``).
ANIMATED = "overlay"


def animated(*models) -> None:
    """Mark what a player moves every frame (glyph renderers, annotations): BokehJS draws
    it on the plot's overlay layer, a canvas of its own that it repaints alone when only
    such models changed -- the axes, grid, legend, colour bar and still glyphs are not
    painted again each frame (their text, each drawing reading the page's CSS, was most of
    a frame's work). Annotations there are clipped to the plot area; glyphs are not, so a
    moving glyph's data must stay inside the plot's ranges."""
    for model in models:
        model.level = ANIMATED


def animated_group(fig, *models, name: str | None = None) -> Span:
    """Draw ``models`` (``fig``'s glyph renderers and annotations, bottom first) as
    ``animated``, clipped to the plot area as still glyphs are, so they may leave the
    plot's view (a sliding slab, a zoomed plot): on the overlay layer BokehJS clips
    annotations, not glyphs, so they are drawn as the parts of an annotation that draws
    nothing itself (a ``Span`` without a location; Bokeh's ``CompositeRenderer.renderers``,
    painted inside their group's clip). The group takes the place of the first of them
    among ``fig``'s renderers; returns it."""
    moved = {model.id for model in models}
    at = next((k for k, r in enumerate(fig.renderers) if r.id in moved), len(fig.renderers))
    group = Span(location=None, renderers=list(models), name=name)
    animated(group, *models)
    fig.center = [m for m in fig.center if m.id not in moved]
    kept = [r for r in fig.renderers if r.id not in moved]
    fig.renderers = [*kept[:at], group, *kept[at:]]  # none of them before the first
    return group


def legend_stand_ins(fig) -> None:
    """Legend entries of ``fig`` that name an ``animated`` glyph name a still stand-in
    instead: a Bokeh legend draws its entries anew (new elements, a page layout) whenever a
    renderer it names or that renderer's data changes, i.e. every frame. The stand-in
    shares the glyph, draws nothing in the plot and hides or shows the glyph with it
    (``click_policy="hide"``). (The legends are read from the plot's panels,
    ``fig.legend``, not by walking every model the figure refers to: that walk was a tenth
    of the page's build.)"""
    for legend in fig.legend:
        for item in legend.items:
            item.renderers = [stand_in(fig, r) if r.level == ANIMATED else r
                              for r in item.renderers]


def stand_in(fig, renderer: GlyphRenderer) -> GlyphRenderer:
    """A renderer of ``renderer``'s glyph that a legend draws and the plot does not: its
    rows (at least one) have every number NaN and keep their text (colours, labels of a
    ``legend_field``). Its visibility is passed on to ``renderer``."""
    data = renderer.data_source.data
    rows = max(1, max((len(v) for v in data.values()), default=0))
    columns = {k: [v[i] if i < len(v) and isinstance(v[i], str) else math.nan
                   for i in range(rows)] for k, v in data.items()}
    still = GlyphRenderer(data_source=ColumnDataSource(columns), glyph=renderer.glyph,
                          visible=renderer.visible)
    fig.renderers.append(still)
    pass_on_visible(still, renderer)
    return still


def pass_on_visible(model, to) -> None:
    """``to`` is shown and hidden with ``model`` (a legend's stand-in). The callback finds
    ``to`` by its id, not as an argument: a legend follows every model its entries refer
    to, callbacks' arguments included, and ``to`` changes every frame."""
    model.js_on_change("visible", CustomJS(code=f"""
        const to = cb_obj.document.get_model_by_id({to.id!r});
        if (to && to.visible !== cb_obj.visible) to.visible = cb_obj.visible;"""))


def _base_width(glyph) -> float | None:
    for tag in glyph.tags:
        if isinstance(tag, str) and tag.startswith("lw:"):
            return float(tag[3:])
    width = getattr(glyph, "line_width", None)
    if not isinstance(width, (int, float)):
        return None
    glyph.tags = [*glyph.tags, f"lw:{width}"]
    return float(width)


def _scale_text(model, scale: float) -> None:
    """Scale a text size in px, remembering the screen size in ``tags``."""
    base = next((t for t in model.tags if isinstance(t, str) and t.startswith("fs:")), None)
    if base is None:
        size = model.text_font_size
        size = size.get("value") if isinstance(size, dict) else size
        if not (isinstance(size, str) and size.endswith("px")):
            return
        base = f"fs:{size[:-2]}"
        model.tags = [*model.tags, base]
    model.text_font_size = f"{round(float(base[3:]) * scale)}px"


def legend_above(fig) -> None:
    """Move the figure's legends out of the plot area to a compact row above it, so they
    hide no curve (e.g. F_f,y under a legend in the lower right)."""
    for legend in [m for m in fig.center if isinstance(m, Legend)]:
        fig.center = [m for m in fig.center if m is not legend]
        legend.update(orientation="horizontal", location="top_left", padding=1, spacing=8,
                      margin=0, glyph_width=16, label_standoff=3, border_line_alpha=0,
                      background_fill_alpha=0)
        fig.add_layout(legend, "above")


#: Ticks wanted on an axis: fewer in projector mode, where the labels are larger.
TICKS = {False: 6, True: 4}


def style(fig, projector: bool) -> None:
    """Screen (False) or projector (True) look: font sizes, line widths, grid contrast,
    tick density, legends and colour bars."""
    scale = PROJECTOR_SCALE if projector else 1.0
    label = tick = f"{round(MIN_TEXT_PX * scale)}px"
    title = f"{round((MIN_TEXT_PX + 1) * scale)}px"
    for axis in (*fig.xaxis, *fig.yaxis):
        if hasattr(axis.ticker, "desired_num_ticks"):
            axis.ticker.desired_num_ticks = TICKS[projector]
        axis.axis_label_text_font_size = label
        axis.major_label_text_font_size = tick
        axis.axis_label_text_font_style = "normal"
        axis.axis_label_text_color = BLACK if projector else "#333333"
        axis.major_label_text_color = BLACK if projector else "#444444"
        axis.axis_line_width = 2 if projector else 1
    if isinstance(fig.title, Title):
        fig.title.text_font_size = title
    for grid in (*fig.xgrid, *fig.ygrid):
        grid.grid_line_color = "#999999" if projector else "#e5e5e5"
    layouts = _renderers(fig)
    for legend in (m for m in layouts if isinstance(m, Legend)):
        legend.label_text_font_size = tick
        legend.background_fill_alpha = 0.9 if projector else 0.7
    for renderer in (r for r in layouts if isinstance(r, GlyphRenderer)):
        base = _base_width(renderer.glyph)
        if base is not None:
            renderer.glyph.line_width = base * (2.0 if projector else 1.0)
        if isinstance(renderer.glyph, Text):
            _scale_text(renderer.glyph, scale)
    for text in (m for m in layouts if isinstance(m, (Label, LabelSet))):
        _scale_text(text, scale)
    for bar in (m for m in layouts if isinstance(m, ColorBar)):
        bar.major_label_text_font_size = tick
        bar.title_text_font_size = label
        # its thickness: a horizontal bar's length is its width (set by its figure)
        thickness = 14 if projector else 8
        if bar.orientation == "horizontal":
            bar.height = thickness
        else:
            bar.width = thickness
    if fig.outline_line_color is not None:  # a key drawn without a frame keeps none
        fig.outline_line_color = BLACK if projector else "#dddddd"


def legend_below(fig, spacing: int = 6) -> None:
    """The legend in one row under the plot, where it hides no curve or glyph."""
    legend = fig.legend[0]
    legend.orientation = "horizontal"
    legend.label_text_font_size = f"{MIN_TEXT_PX}px"
    legend.background_fill_alpha = 0.6
    legend.click_policy = "hide"
    legend.padding = 1
    legend.spacing = spacing
    legend.margin = 2
    legend.glyph_width = 14
    legend.label_standoff = 2
    fig.center = [m for m in fig.center if m is not legend]
    fig.add_layout(legend, "below")
