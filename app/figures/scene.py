"""The support scene (Eqs. 1-6): pivot, rest position, the mass's path during the contact
coloured by tau, and -- at one instant -- the mass, its radial spring, the twist of its
torsional spring from theta0 to theta, and the sliding slab whose trailing edge passes
the support at the end of contact (Eq. 9).

``scene_figure`` draws it from a ``model.TimeSeries``; ``scene_data`` and ``scene_frame``
give the source data for a new trajectory and for one animation frame.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import ColorBar, DataRange1d, Label, LinearColorMapper
from bokeh.palettes import Viridis256

from .common import BLACK, GREY, ORANGE, SKY, VERMILION, new_figure, source

SLAB_REACH = 1e6  # the slab's extent across the plot (it is wider than any orbit)


def _extent(series) -> float:
    if series is None:
        return 1.0
    return float(max(1.0, np.nanmax(np.hypot(series.x, series.y))))


def scene_data(series, params) -> dict:
    """Sources fixed for one trajectory: the coloured path, pivot and rest position,
    the rest orientation and the unit circle (the unstretched radial spring)."""
    c, s = math.cos(params.theta0), math.sin(params.theta0)
    ext = _extent(series)
    phi = np.linspace(0.0, 2 * math.pi, 121)
    data = {
        "scene_points": {"x": [0.0, c], "y": [0.0, s], "what": ["pivot", "rest position"],
                         "marker": ["square", "circle"]},
        "scene_rest_line": {"x": [0.0, c * 1.25 * ext ** 0.25], "y": [0.0, s * 1.25 * ext ** 0.25]},
        "scene_circle": {"x": np.cos(phi), "y": np.sin(phi)},
    }
    if series is None or len(series.tau) < 2:
        data["orbit"] = {k: [] for k in ("x0", "y0", "x1", "y1", "tau", "t")}
    else:
        tau = np.asarray(series.tau)
        data["orbit"] = {"x0": series.x[:-1], "y0": series.y[:-1], "x1": series.x[1:],
                         "y1": series.y[1:], "tau": tau[:-1],
                         "t": tau[:-1] / max(tau[-1], 1e-300)}
    return data


def _zigzag(x: float, y: float, amplitude: float, coils: int = 7):
    """A spring drawn from the pivot to (x, y)."""
    r = math.hypot(x, y)
    if r == 0:
        return [0.0], [0.0]
    ex, ey = x / r, y / r
    u = np.concatenate(([0.0, 0.15], np.linspace(0.15, 0.85, 2 * coils + 1)[1:-1], [0.85, 1.0]))
    w = np.zeros_like(u)
    w[2:-2] = amplitude * np.where(np.arange(w.size - 4) % 2 == 0, 1.0, -1.0)
    return (u * r * ex - w * ey).tolist(), (u * r * ey + w * ex).tolist()


def scene_frame(series, params, i: int) -> dict:
    """Sources of animation frame ``i``: mass, radial spring, twist arc, slab position."""
    if series is None or len(series.tau) == 0:
        empty = {"x": [], "y": []}
        return {"scene_mass": {"x": [], "y": [], "tau": []}, "scene_spring": empty,
                "scene_twist": empty, "scene_slab": {"left": [], "right": [], "bottom": [],
                                                     "top": []}}
    i = int(min(max(i, 0), len(series.tau) - 1))
    x, y, tau, theta = (float(series.x[i]), float(series.y[i]), float(series.tau[i]),
                        float(series.theta[i]))
    ext = _extent(series)
    sx, sy = _zigzag(x, y, 0.05 * ext ** 0.5)
    # Twist of the torsional spring, theta0 -> theta (a spiral when it exceeds a turn).
    span = theta - params.theta0
    phi = np.linspace(params.theta0, theta, max(2, int(abs(span) / 0.05) + 2))
    rho = 0.3 * ext ** 0.25 * (1 + 0.08 * np.abs(phi - params.theta0) / (2 * math.pi))
    x_start = float(series.x[0])
    return {
        "scene_mass": {"x": [x], "y": [y], "tau": [tau]},
        "scene_spring": {"x": sx, "y": sy},
        "scene_twist": {"x": rho * np.cos(phi), "y": rho * np.sin(phi)},
        # The slab moves at unit speed: trailing edge at x(0) - L0 + tau, leading edge at
        # x(0) + tau; the contact ends when the trailing edge reaches the mass (Eq. 9).
        "scene_slab": {"left": [x_start - params.L0 + tau], "right": [x_start + tau],
                       "bottom": [-SLAB_REACH], "top": [SLAB_REACH]},
    }


def time_text(series, i: int) -> str:
    if series is None or len(series.tau) == 0:
        return ""
    i = int(min(max(i, 0), len(series.tau) - 1))
    return f"τ = {series.tau[i]:.3g} of τ_out = {series.tau[-1]:.4g}"


def scene_figure(series, params, frame: int = 0, width: int = 340, height: int = 330):
    """The support and its path during one contact (dimensionless lengths, r0 = 1)."""
    data = {**scene_data(series, params), **scene_frame(series, params, frame)}
    fig = new_figure("scene", "Support: path coloured by τ/τ_out", width, height,
                     match_aspect=True, x_axis_label="x / r₀", y_axis_label="y / r₀")
    src = {name: source(name, cols) for name, cols in data.items()}
    slab = fig.quad("left", "right", "bottom", "top", source=src["scene_slab"],
                    fill_color=SKY, fill_alpha=0.15, line_color=SKY, line_width=2,
                    legend_label="slab")
    circle = fig.line("x", "y", source=src["scene_circle"], line_color=GREY, line_dash="dotted",
                      line_width=1)
    fig.line("x", "y", source=src["scene_rest_line"], line_color=GREY, line_dash="dashed",
             line_width=1.5, legend_label="θ₀")
    mapper = LinearColorMapper(palette=Viridis256, low=0.0, high=1.0)
    orbit = fig.segment("x0", "y0", "x1", "y1", source=src["orbit"], line_width=2.5,
                        line_color={"field": "t", "transform": mapper})
    fig.line("x", "y", source=src["scene_twist"], line_color=ORANGE, line_width=2,
             legend_label="twist")
    spring = fig.line("x", "y", source=src["scene_spring"], line_color=BLACK, line_width=1.5,
                      legend_label="spring")
    points = fig.scatter("x", "y", source=src["scene_points"], marker="marker", size=9,
                         fill_color="white", line_color=BLACK, line_width=2)
    mass = fig.scatter("x", "y", source=src["scene_mass"], size=13, fill_color=VERMILION,
                       line_color=BLACK, line_width=1.5, legend_label="mass")
    fig.x_range = DataRange1d(renderers=[orbit, circle, points, mass, spring], range_padding=0.15)
    fig.y_range = DataRange1d(renderers=[orbit, circle, points, mass, spring], range_padding=0.15)
    fig.add_layout(ColorBar(color_mapper=mapper, width=8, title="τ/τ_out",
                            title_text_font_size="10px", major_label_text_font_size="10px",
                            name="scene_colorbar"), "right")
    fig.add_layout(Label(x=6, y=6, x_units="screen", y_units="screen", name="scene_time",
                         text=time_text(series, frame), text_font_size="12px",
                         background_fill_color="white", background_fill_alpha=0.8))
    legend = fig.legend[0]
    legend.orientation = "horizontal"
    legend.location = "top_left"
    legend.label_text_font_size = "10px"
    legend.background_fill_alpha = 0.6
    legend.click_policy = "hide"
    legend.padding = 1
    legend.spacing = 4
    legend.margin = 2
    legend.glyph_width = 14
    legend.label_standoff = 2
    fig.center = [m for m in fig.center if m is not legend]
    fig.add_layout(legend, "below")
    slab.level = "underlay"
    return fig
