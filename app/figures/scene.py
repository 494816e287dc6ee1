"""The support scene, seen from above (Eqs. 1-6): pivot, rest position, the mass's path
during the contact coloured by tau, and -- at one instant -- the mass, its radial spring,
the twist of its torsional spring from theta0 to theta, the sliding slab (striped, so its
motion shows; its edges marked when they are out of view) whose trailing edge passes the
support at the end of contact (Eq. 9), and three arrows at the mass: the slab's velocity
(+x, unit speed), the relative velocity v_R = v - (1, 0) of the mass on the slab, and the
friction force on the mass (over f_N, Eq. 4).

``scene_figure`` draws it from a ``model.TimeSeries``; ``scene_data`` and ``scene_frame``
give the source data for a new trajectory and for one animation frame.

The axes are to scale (a true top view) unless the path is far longer one way than the
other (a stretched slider): then each axis fits the path and the plot says "not to scale".
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import (Arrow, Band, ColorBar, Label, LabelSet, LinearColorMapper, Range1d,
                          VeeHead)
from bokeh.palettes import Viridis256

from .common import (BLACK, annotation, BLUE, GREY, ORANGE, SKY, VERMILION, animated,
                     legend_below,
                     legend_stand_ins, new_figure, pass_on_visible, source)

SLAB_REACH = 1e6  # the slab's extent across the plot (it is wider than any orbit)
#: Beyond this ratio of the path's width to height, the axes are not to scale.
MAX_ASPECT = 4.0
#: A support stretched beyond this many r0 gets a warning on the plot.
STRETCH_WARNING = 3.0
#: Stripes drawn across the slab per view width (they move with it).
STRIPES = 9
#: Arrow lengths in units of the view's half width: per unit speed, per unit force / f_N.
ARROW_SCALE = 0.28
FORCE_COLOR, VREL_COLOR, SLAB_COLOR = VERMILION, "#6A3D9A", BLUE


def _extent(series) -> float:
    if series is None:
        return 1.0
    return float(max(1.0, np.nanmax(np.hypot(series.x, series.y))))


def view_box(series, params) -> tuple[float, float, float, float, bool]:
    """(x0, x1, y0, y1, to_scale): the region shown -- the path, the unit circle, the
    pivot and the rest position, padded; square when the path allows (to scale)."""
    xs, ys = [-1.0, 1.0], [-1.0, 1.0]
    if series is not None and len(series.tau):
        xs += [float(np.nanmin(series.x)), float(np.nanmax(series.x))]
        ys += [float(np.nanmin(series.y)), float(np.nanmax(series.y))]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    w, h = x1 - x0, y1 - y0
    to_scale = max(w, h) <= MAX_ASPECT * min(w, h)
    if to_scale:  # a square around the centre: equal scales on a square plot
        side = max(w, h)
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        x0, x1, y0, y1 = cx - side / 2, cx + side / 2, cy - side / 2, cy + side / 2
    pad_x, pad_y = 0.12 * (x1 - x0), 0.12 * (y1 - y0)
    return x0 - pad_x, x1 + pad_x, y0 - pad_y, y1 + pad_y, to_scale


def _notes(series, params, to_scale: bool) -> str:
    notes = [] if to_scale else ["axes not to scale"]
    if series is not None and len(series.r):
        r_max = float(np.nanmax(series.r))
        if r_max > STRETCH_WARNING:
            notes.append(f"stretched to {r_max:.3g} r₀: beyond a real pillar")
    return "; ".join(notes)


def scene_data(series, params) -> dict:
    """Sources fixed for one trajectory: the coloured path, pivot and rest position,
    the rest orientation, the unit circle (the unstretched radial spring), the view."""
    c, s = math.cos(params.theta0), math.sin(params.theta0)
    ext = _extent(series)
    phi = np.linspace(0.0, 2 * math.pi, 121)
    to_scale = view_box(series, params)[-1]
    data = {
        "scene_points": {"x": [0.0, c], "y": [0.0, s], "what": ["pivot", "rest position"],
                         "marker": ["square", "circle"]},
        "scene_rest_line": {"x": [0.0, c * 1.25 * ext ** 0.25], "y": [0.0, s * 1.25 * ext ** 0.25]},
        "scene_circle": {"x": np.cos(phi), "y": np.sin(phi)},
        "scene_notes": {"x": [0.0], "y": [0.0], "text": [_notes(series, params, to_scale)]},
    }
    # The path's segments and their colour (tau/tau_out): only what is drawn is sent.
    if series is None or len(series.tau) < 2:
        data["orbit"] = {k: [] for k in ("x0", "y0", "x1", "y1", "t")}
    else:
        tau = np.asarray(series.tau)
        data["orbit"] = {"x0": series.x[:-1], "y0": series.y[:-1], "x1": series.x[1:],
                         "y1": series.y[1:], "t": tau[:-1] / max(tau[-1], 1e-300)}
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


_EMPTY_FRAME = {
    "scene_mass": {"x": [], "y": [], "tau": []}, "scene_spring": {"x": [], "y": []},
    "scene_twist": {"x": [], "y": []},
    "scene_slab": {"y": [], "left": [], "right": []},
    "scene_stripes": {"xs": [], "ys": []},
    "scene_edges": {"x": [], "y": [], "text": [], "align": []},
    "scene_arrows": {"x0": [], "y0": [], "x1": [], "y1": [], "color": []},
    "scene_arrow_labels": {"x": [], "y": [], "text": [], "color": [], "align": [],
                           "baseline": []},
}


def scene_frame(series, params, i: int) -> dict:
    """Sources of animation frame ``i``: mass, radial spring, twist arc, slab position
    and stripes, the slab's edges when out of view, and the three arrows at the mass."""
    if series is None or len(series.tau) == 0:
        return {k: dict(v) for k, v in _EMPTY_FRAME.items()}
    i = int(min(max(i, 0), len(series.tau) - 1))
    x, y, tau, theta = (float(series.x[i]), float(series.y[i]), float(series.tau[i]),
                        float(series.theta[i]))
    ext = _extent(series)
    sx, sy = _zigzag(x, y, 0.05 * ext ** 0.5)
    # Twist of the torsional spring, theta0 -> theta (a spiral when it exceeds a turn).
    span = theta - params.theta0
    phi = np.linspace(params.theta0, theta, max(2, int(abs(span) / 0.05) + 2))
    rho = 0.3 * ext ** 0.25 * (1 + 0.08 * np.abs(phi - params.theta0) / (2 * math.pi))
    # The slab moves at unit speed: trailing edge at x(0) - L0 + tau, leading edge at
    # x(0) + tau; the contact ends when the trailing edge reaches the mass (Eq. 9).
    x_start = float(series.x[0])
    left, right = x_start - params.L0 + tau, x_start + tau
    vx0, vx1, vy0, vy1, _ = view_box(series, params)
    return {
        "scene_mass": {"x": [x], "y": [y], "tau": [tau]},
        "scene_spring": {"x": sx, "y": sy},
        "scene_twist": {"x": rho * np.cos(phi), "y": rho * np.sin(phi)},
        "scene_slab": {"y": [-SLAB_REACH, SLAB_REACH], "left": [left, left],
                       "right": [right, right]},
        "scene_stripes": _stripes(left, right, vx0, vx1, vy0, vy1),
        "scene_edges": _edges(left, right, vx0, vx1, vy0, vy1),
        **_arrows(series, i, vx0, vx1, vy0, vy1),
    }


def _stripes(left, right, vx0, vx1, vy0, vy1) -> dict:
    """Lines across the slab, fixed to it, inside the view: they slide with the slab."""
    spacing = (vx1 - vx0) / STRIPES
    first = left + math.ceil((vx0 - left) / spacing) * spacing if left < vx0 else left
    xs = np.arange(first, min(right, vx1) + 1e-12, spacing)
    return {"xs": [[float(v), float(v)] for v in xs], "ys": [[vy0, vy1] for _ in xs]}


def _edges(left, right, vx0, vx1, vy0, vy1) -> dict:
    """Labels at the view's border for slab edges out of view, with their distance."""
    y = vy0 + 0.93 * (vy1 - vy0)
    out = {"x": [], "y": [], "text": [], "align": []}
    if left < vx0 and right > vx0:
        out["x"].append(vx0)
        out["text"].append(f"◀ trailing edge {vx0 - left:.2g} r₀")
        out["align"].append("left")
        out["y"].append(y)
    if right > vx1 and left < vx1:
        out["x"].append(vx1)
        out["text"].append(f"leading edge {right - vx1:.2g} r₀ ▶")
        out["align"].append("right")
        out["y"].append(y)
    return out


def _arrows(series, i, vx0, vx1, vy0, vy1) -> dict:
    """Slab velocity (+x, drawn on the slab above the mass), relative velocity of the mass
    on the slab v_R = v - (1, 0), and the friction force on the mass over f_N (Eq. 4)."""
    x, y = float(series.x[i]), float(series.y[i])
    # Scaled by each axis's span, so arrows look alike on any view (directions are true
    # when the axes are to scale).
    sx, sy = ARROW_SCALE * 0.5 * (vx1 - vx0), ARROW_SCALE * 0.5 * (vy1 - vy0)
    vrx, vry = float(series.v_x[i]) - 1.0, float(series.v_y[i])
    fx, fy = float(series.F_x[i]), float(series.F_y[i])
    ys = y + 0.12 * (vy1 - vy0)
    arrows = [((x, ys), (x + sx, ys), SLAB_COLOR, "slab V₀"),
              ((x, y), (x + sx * vrx, y + sy * vry), VREL_COLOR, "v_R"),
              ((x, y), (x + sx * fx, y + sy * fy), FORCE_COLOR, "friction")]
    keep = [a for a in arrows if math.hypot(a[1][0] - a[0][0], a[1][1] - a[0][1]) > 1e-9]
    return {
        "scene_arrows": {"x0": [a[0][0] for a in keep], "y0": [a[0][1] for a in keep],
                         "x1": [a[1][0] for a in keep], "y1": [a[1][1] for a in keep],
                         "color": [a[2] for a in keep]},
        "scene_arrow_labels": _arrow_labels(keep, vx0, vx1, vy0, vy1),
    }


#: Part of the view's width (from the border an arrow points to) where its label turns
#: back inside the view, and part of its height where a label flips to the other side.
LABEL_ROOM_X, LABEL_ROOM_Y = 0.3, 0.15


def _arrow_labels(arrows, vx0, vx1, vy0, vy1) -> dict:
    """Each arrow's label at its tip, running on outwards in the arrow's direction (so the
    labels of v_R and the friction, opposite arrows from the mass, part), and turned back
    near the view's border (inside the view); the slab's label above its arrow, the others
    below their tips (flipped near the top and bottom). A tip outside the view is labelled
    at the view's border. (The page draws the frames with the same rule:
    ``app.figures.live_energy``.)"""
    out = {"x": [], "y": [], "text": [], "color": [], "align": [], "baseline": []}
    room_x, room_y = LABEL_ROOM_X * (vx1 - vx0), LABEL_ROOM_Y * (vy1 - vy0)
    for (x0, _), (x, y), color, text in arrows:
        x, y = min(max(x, vx0), vx1), min(max(y, vy0), vy1)
        right = x >= x0 and x < vx1 - room_x or x < x0 and x < vx0 + room_x
        above = y < vy1 - room_y if color == SLAB_COLOR else y < vy0 + room_y
        out["x"].append(x)
        out["y"].append(y)
        out["text"].append(text)
        out["color"].append(color)
        out["align"].append("left" if right else "right")
        out["baseline"].append("bottom" if above else "top")
    return out


def time_text(series, i: int) -> str:
    if series is None or len(series.tau) == 0:
        return ""
    i = int(min(max(i, 0), len(series.tau) - 1))
    return f"τ = {series.tau[i]:.3g} of τ_out = {series.tau[-1]:.4g}"


def scene_figure(series, params, frame: int = 0, width: int = 340, height: int = 330):
    """The support and its path during one contact, seen from above (lengths in r0)."""
    data = {**scene_data(series, params), **scene_frame(series, params, frame)}
    fig = new_figure("scene", "Top view: one support under the sliding slab", width, height,
                     x_axis_label="x / r₀  (slab slides along +x)", y_axis_label="y / r₀",
                     tools="save")
    src = {name: source(name, cols) for name, cols in data.items()}
    # The slab: a band between its trailing and leading edges across the whole plot
    # (clipped to the plot area as a moving glyph would not be: ``animated``); the legend
    # shows it as a box.
    slab = Band(base="y", lower="left", upper="right", dimension="width",
                source=src["scene_slab"], fill_color=SKY, fill_alpha=0.15, line_color=SKY,
                line_width=3, name="scene_slab")
    fig.renderers.insert(0, slab)  # below everything that moves
    slab_key = fig.quad([math.nan], [math.nan], [math.nan], [math.nan], fill_color=SKY,
                        fill_alpha=0.15, line_color=SKY, line_width=3, legend_label="slab")
    pass_on_visible(slab_key, slab)  # the legend hides the band
    stripes = fig.multi_line("xs", "ys", source=src["scene_stripes"], line_color=SKY,
                             line_width=1.5, line_alpha=0.55)
    circle = fig.line("x", "y", source=src["scene_circle"], line_color=GREY, line_dash="dotted",
                      line_width=1)
    fig.line("x", "y", source=src["scene_rest_line"], line_color=GREY, line_dash="dashed",
             line_width=1.5, legend_label="θ₀")
    mapper = LinearColorMapper(palette=Viridis256, low=0.0, high=1.0)
    fig.segment("x0", "y0", "x1", "y1", source=src["orbit"], line_width=2.5,
                line_color={"field": "t", "transform": mapper})
    twist = fig.line("x", "y", source=src["scene_twist"], line_color=ORANGE, line_width=2,
                     legend_label="twist")
    spring = fig.line("x", "y", source=src["scene_spring"], line_color=BLACK, line_width=1.5,
                      legend_label="spring")
    fig.scatter("x", "y", source=src["scene_points"], marker="marker", size=9,
                fill_color="white", line_color=BLACK, line_width=2)
    mass = fig.scatter("x", "y", source=src["scene_mass"], size=13, fill_color=VERMILION,
                       line_color=BLACK, line_width=1.5, legend_label="mass")
    # Fixed ranges around the path (to scale, or each axis fitted): set anew with each
    # trajectory, never recomputed while the mass moves.
    x0, x1, y0, y1, _ = view_box(series, params)
    fig.x_range, fig.y_range = Range1d(x0, x1), Range1d(y0, y1)
    fig.add_layout(Arrow(end=VeeHead(size=9, fill_color={"field": "color"},
                                     line_color={"field": "color"}),
                         x_start="x0", y_start="y0", x_end="x1", y_end="y1",
                         line_color={"field": "color"}, line_width=2.5,
                         source=src["scene_arrows"], name="scene_arrows"))
    fig.add_layout(LabelSet(x="x", y="y", text="text", text_color={"field": "color"},
                            text_align={"field": "align"}, text_baseline={"field": "baseline"},
                            source=src["scene_arrow_labels"], text_font_size="12px",
                            name="scene_arrow_labels"))
    fig.add_layout(LabelSet(x="x", y="y", text="text", text_align={"field": "align"},
                            source=src["scene_edges"], text_font_size="12px",
                            text_color=BLUE, name="scene_edges"))
    fig.add_layout(LabelSet(x=6, y=24, x_units="screen", y_units="screen", text="text",
                            source=src["scene_notes"], text_font_size="12px",
                            text_color=VERMILION, name="scene_notes"))
    # The colour bar's own copy of the path's mapper: BokehJS redraws a colour bar's image
    # whenever its mapper maps new data, i.e. with every contact's path.
    bar_mapper = LinearColorMapper(palette=Viridis256, low=0.0, high=1.0)
    fig.add_layout(ColorBar(color_mapper=bar_mapper, width=8, title="τ/τ_out",
                            title_text_font_size="12px", major_label_text_font_size="12px",
                            name="scene_colorbar"), "right")
    fig.add_layout(Label(x=6, y=6, x_units="screen", y_units="screen", name="scene_time",
                         text=time_text(series, frame), text_font_size="12px",
                         background_fill_color="white", background_fill_alpha=0.8))
    legend_below(fig, spacing=4)
    # Drawn anew every frame, over the still path, pivot and rest line (a top view looks
    # through the slab); the legend names still stand-ins.
    animated(slab, stripes, twist, spring, mass,
             *(annotation(fig, n) for n in ("scene_arrows", "scene_arrow_labels",
                                            "scene_edges", "scene_time")))
    legend_stand_ins(fig)
    return fig
