"""The Array tab's keys (``app.figures.array_scene``), which stay still while the array
plays: legends written in HTML and the friction direction's colour scale in a figure of
its own. Neither is repainted with the top view's canvas on a frame.
"""
from __future__ import annotations

from bokeh.models import ColorBar, FixedTicker
from bokeh.plotting import figure

__all__ = ["html_key", "colorbar_figure"]


def html_key(items) -> str:
    """A legend in HTML: it is not repainted with the canvas on every frame.

    ``items``: (kind, colour, dash, width, label) with kind "line", "box", "dot" or "square".
    """
    parts = []
    for kind, color, dash, lw, label in items:
        if kind == "line":
            swatch = (f"<span style='display:inline-block;width:30px;vertical-align:middle;"
                      f"border-top:{max(lw, 1)}px {dash} {color}'></span>")
        elif kind == "box":
            swatch = (f"<span style='display:inline-block;width:22px;height:12px;"
                      f"vertical-align:middle;background:{color};opacity:0.35'></span>")
        else:
            radius = "50%" if kind == "dot" else "0"
            swatch = (f"<span style='display:inline-block;width:11px;height:11px;"
                      f"vertical-align:middle;border-radius:{radius};background:{color};"
                      f"border:1px solid #000'></span>")
        parts.append(f"<span style='white-space:nowrap;margin-right:14px'>{swatch} {label}</span>")
    return " ".join(parts)


def colorbar_figure(mapper, width, responsive: bool = False):
    """The colour scale in a figure of its own, which stays still during playback: with a
    copy of the glyphs' colour mapper (a shared one tells the bar to redraw, and its figure
    to lay itself out again, each time the glyphs map their colours: every frame)."""
    mapper = type(mapper)(**mapper.properties_with_values(include_defaults=False))
    fig = figure(width=width, height=74, toolbar_location=None, x_axis_type=None,
                 y_axis_type=None, outline_line_color=None, min_border=0,
                 name="array_colorbar_figure")
    fig.scatter([0], [0], visible=False)  # a figure needs a renderer
    fig.grid.visible = False
    fig.add_layout(ColorBar(color_mapper=mapper, orientation="horizontal", height=14,
                            width="auto" if responsive else min(420, width - 40),
                            title="friction direction [° from +x]", location="top_left",
                            title_text_font_size="13px", major_label_text_font_size="13px",
                            name="array_colorbar", padding=4,
                            ticker=FixedTicker(ticks=[-90, -45, 0, 45, 90])), "above")
    return fig
