"""True polar diagrams of fixed-orientation arrays against theta0 (Fig. 11a-c).

The radius is the quantity, the polar angle is theta0 (0 = the sliding direction +x).
The sweep covers theta0 in [0, pi]; mirror symmetry (y -> -y) gives the other half:
F_T,x/(mu0 F_N) and D_y/D_x are even in theta0, F_T,y/(mu0 F_N) is odd. A quantity that
takes negative values is drawn about an inner ring (radius = value - r_lo), which is
labelled, so the zero ring stands out. Grid rings and spokes are drawn here, in data
coordinates (x = r cos theta0, y = r sin theta0).
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import DataRange1d

from .common import (BLACK, BLUE, GREY, MIN_TEXT_PX, ORANGE, PROJECTOR_SCALE, VERMILION,
                     legend_above, new_figure, source)

#: An odd quantity's curve is drawn in two colours by sign, with these legend labels: its
#: radius is measured from the bold zero ring, so negative values lie inside it.
SIGN_LABELS = {"pos": ("{name} > 0 (+y): outside ring", BLUE),
               "neg": ("{name} < 0 (−y): inside ring", ORANGE)}
SIGN_NAMES = {"FTy": "F_T,y"}

#: key -> (column of the orientation sweep, title, parity in theta0)
QUANTITIES = {
    "FTx": ("FTx_over_mu0FN", "F_T,x/(μ₀F_N) vs θ₀ (Fig. 11a)", "even"),
    "DyDx": ("Dy_over_Dx", "D_y/D_x vs θ₀ (Fig. 11b)", "even"),
    "FTy": ("FTy_over_mu0FN", "F_T,y/(μ₀F_N) vs θ₀ (Fig. 11c)", "odd"),
}
SPOKES_DEG = tuple(range(0, 360, 30))
#: The angle labels' distance from the centre, and half the side of the square shown, in
#: rim radii (the square leaves room for an angle label of ``LABEL_FONT_PX``).
ANGLE_LABEL_R, EXTENT_R = 1.1, 1.34
#: The rings' values are written along this ray (degrees), between the 0 and 30 degree
#: spokes: there the labels lie one beside the next, and apart from the angle labels.
RING_LABEL_DEG = 15
#: The ring labels are laid out for a frame (px) and text (px), with a gap (px) around each
#: label: every ``s``-th ring is labelled, the smallest ``s`` whose labels run into none
#: another nor an angle label. The figures fill their place on the page; the tightest is
#: the Design tab's at 1280x720, ~170 px wide with 12 px text: this frame with the
#: projector's text is as tight (tests/browser/test_projector.py checks both modes).
LABEL_FRAME_PX, LABEL_FONT_PX, LABEL_GAP_PX = 250, MIN_TEXT_PX * PROJECTOR_SCALE, 2
#: Characters' widths (em) in DejaVu Sans, the widest of the usual sans-serif fonts; any
#: other character counts as ``WIDE_EM``.
CHAR_EM, WIDE_EM = {**dict.fromkeys("0123456789", 0.64), ".": 0.32, "-": 0.37, "e": 0.62,
                    "°": 0.5}, 0.84


def full_circle(theta0, values, parity: str):
    """(theta, values) on [0, 2 pi) from a half sweep on [0, pi], closed into a loop."""
    theta0, values = np.asarray(theta0, float), np.asarray(values, float)
    sign = 1.0 if parity == "even" else -1.0
    theta = np.concatenate((theta0, 2 * math.pi - theta0[::-1]))
    vals = np.concatenate((values, sign * values[::-1]))
    if theta.size:
        theta, vals = np.append(theta, theta[0] + 2 * math.pi), np.append(vals, vals[0])
    return theta, vals


def _nice(x: float) -> float:
    """The smallest of 1, 2, 2.5, 5 times a power of ten that is >= x > 0."""
    power = 10.0 ** math.floor(math.log10(x))
    return next(m * power for m in (1, 2, 2.5, 5, 10) if m * power >= x * (1 - 1e-12))


def radial_axis(values, parity: str) -> tuple[float, float, list]:
    """(r_lo, r_hi, ring values): the value at the centre, at the rim, and grid rings."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    top = float(np.max(np.abs(v))) if v.size else 1.0
    top = top if top > 0 else 1.0
    odd = parity == "odd" or bool(v.size and v.min() < 0)
    best = None
    lo, hi = (2, 3) if odd else (3, 6)  # rings on each side of the centre
    for k in range(lo, hi + 1):
        step = _nice(top / k)
        n = max(1, math.ceil(top / step - 1e-9))
        if lo <= n <= hi and (best is None or n * step < best[0] * best[1] - 1e-12):
            best = (n, step)
    if best is None:
        best = (hi, _nice(top / hi))
    n, step = best
    if odd:
        return -n * step, n * step, [k * step for k in range(-n, n + 1)]
    return 0.0, n * step, [k * step for k in range(1, n + 1)]


def _label_box(x: float, y: float, text: str) -> tuple:
    """The box (px, with the gap around it) of a label centred on (x, y) px."""
    half_w = sum(CHAR_EM.get(ch, WIDE_EM) for ch in text) * LABEL_FONT_PX / 2 + LABEL_GAP_PX
    half_h = LABEL_FONT_PX / 2 + LABEL_GAP_PX
    return (x - half_w, y - half_h, x + half_w, y + half_h)


def _overlap(a: tuple, b: tuple) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def label_boxes(axis, indices) -> tuple[list, list]:
    """The boxes (px, with their gap, about the centre) of the values of the rings
    ``indices`` of ``axis`` and of the angle labels, as ``labelled_rings`` lays them out."""
    r_lo, r_hi, rings = axis
    px = LABEL_FRAME_PX / (2 * EXTENT_R * (r_hi - r_lo))  # px per unit of value
    c, s = math.cos(math.radians(RING_LABEL_DEG)), math.sin(math.radians(RING_LABEL_DEG))
    a = ANGLE_LABEL_R * (r_hi - r_lo) * px
    values = [_label_box((rings[i] - r_lo) * px * c, (rings[i] - r_lo) * px * s,
                         f"{rings[i]:g}") for i in indices]
    angles = [_label_box(a * math.cos(math.radians(d)), a * math.sin(math.radians(d)),
                         f"{d}°") for d in SPOKES_DEG]
    return values, angles


def labelled_rings(axis) -> list[int]:
    """The indices of the rings of ``axis`` (``radial_axis``) whose values are written.

    Every ``s``-th ring, counted from the zero ring of an odd quantity or else from the rim
    (so both are always labelled), for the smallest ``s`` whose labels on the ray at
    ``RING_LABEL_DEG`` run into neither each other nor an angle label, in a frame of
    ``LABEL_FRAME_PX`` with text of ``LABEL_FONT_PX`` (``label_boxes``). (A larger frame
    or the screen's smaller text leaves more room.)
    """
    r_lo, _, rings = axis
    n = len(rings)
    first = rings.index(0.0) if r_lo < 0 and 0.0 in rings else n - 1
    for step in range(1, n + 1):
        chosen = [i for i in range(n) if (first - i) % step == 0]
        values, angles = label_boxes(axis, chosen)
        if not any(_overlap(b, o) for j, b in enumerate(values) for o in values[:j] + angles):
            return chosen
    return [first]


def grid_data(key: str, axis) -> dict:
    """Rings (every ``labelled_rings`` one labelled with its value), spokes every 30 degrees
    and angle labels."""
    r_lo, r_hi, rings = axis
    R = r_hi - r_lo
    phi = np.linspace(0, 2 * math.pi, 121)
    ring_r = [v - r_lo for v in rings]
    spokes = np.radians(SPOKES_DEG)
    label_angle = math.radians(RING_LABEL_DEG)
    labelled = labelled_rings(axis)
    return {
        f"polar_{key}_rings": {"xs": [r * np.cos(phi) for r in ring_r],
                               "ys": [r * np.sin(phi) for r in ring_r],
                               "value": list(rings),
                               "width": [2.0 if v == 0 and r_lo < 0 else 1.0 for v in rings]},
        f"polar_{key}_spokes": {"xs": [[0.0, R * math.cos(a)] for a in spokes],
                                "ys": [[0.0, R * math.sin(a)] for a in spokes]},
        f"polar_{key}_ring_labels": {"x": [ring_r[i] * math.cos(label_angle) for i in labelled],
                                     "y": [ring_r[i] * math.sin(label_angle) for i in labelled],
                                     "text": [f"{rings[i]:g}" for i in labelled]},
        f"polar_{key}_angle_labels": {"x": [ANGLE_LABEL_R * R * math.cos(a) for a in spokes],
                                      "y": [ANGLE_LABEL_R * R * math.sin(a) for a in spokes],
                                      "text": [f"{d}°" for d in SPOKES_DEG]},
    }


def polar_data(key: str, theta0, values, cover=()) -> tuple[dict, tuple]:
    """Sources of one polar diagram from a half sweep, and its radial axis (which also
    covers the values ``cover``: a compared state's curve)."""
    parity = QUANTITIES[key][2]
    theta, vals = full_circle(theta0, values, parity)
    axis = radial_axis(np.concatenate((vals, np.asarray(cover, float))), parity)
    r = np.clip(vals - axis[0], 0.0, None)
    curve = {"x": r * np.cos(theta), "y": r * np.sin(theta),
             "theta0_deg": np.degrees(theta) % 360, "value": vals}
    signs = {}
    if parity == "odd":
        for sign, keep in (("pos", vals >= 0), ("neg", vals <= 0)):
            # Keep the neighbours of a kept point, so each part reaches the zero ring.
            near = keep | np.roll(keep, 1) | np.roll(keep, -1)
            signs[f"polar_{key}_{sign}"] = {
                "x": np.where(near, curve["x"], np.nan), "y": np.where(near, curve["y"], np.nan),
                "theta0_deg": curve["theta0_deg"], "value": vals}
    return {f"polar_{key}": curve, **signs, **grid_data(key, axis)}, axis


def polar_now(key: str, theta0: float, value: float, axis) -> dict:
    """The current theta0 (radians) as a spoke, and its value as a marker."""
    r_lo, r_hi, _ = axis
    R = r_hi - r_lo
    c, s = math.cos(theta0), math.sin(theta0)
    marker = {"x": [], "y": [], "value": []}
    if value is not None and math.isfinite(value):
        r = max(value - r_lo, 0.0)
        marker = {"x": [r * c], "y": [r * s], "value": [value]}
    return {f"polar_{key}_now": marker,
            f"polar_{key}_spoke": {"x": [0.0, R * c], "y": [0.0, R * s]}}


def polar_figure(key: str, theta0=(), values=(), current=None, width: int = 310,
                 height: int = 330):
    """Fig. 11 (a: ``FTx``, b: ``DyDx``, c: ``FTy``) as a polar diagram.

    ``theta0``, ``values``: the half sweep on [0, pi]; ``current``: (theta0, value) to mark.
    """
    data, axis = polar_data(key, theta0, values)
    if current is not None:
        data.update(polar_now(key, *current, axis))
    else:
        data.update(polar_now(key, math.pi / 2, None, axis))
    data.update(extent_data(key, axis))
    src = {name: source(name, cols) for name, cols in data.items()}
    # The ranges cover the invisible corners of ``extent_data`` and keep equal scales on
    # x and y in a figure of any shape (match_aspect), so the diagram stays round.
    fig = new_figure(f"polar_{key}", QUANTITIES[key][1], width, height,
                     x_range=DataRange1d(range_padding=0), y_range=DataRange1d(range_padding=0),
                     match_aspect=True,
                     tooltips=[("θ₀", "@theta0_deg{0.0}°"), ("value", "@value{0.0000}")])
    fig.scatter("x", "y", source=src[f"polar_{key}_extent"], size=0, alpha=0)
    fig.axis.visible = False
    fig.grid.visible = False
    fig.multi_line("xs", "ys", source=src[f"polar_{key}_rings"], line_color=GREY,
                           line_alpha=0.6, line_width="width")
    fig.multi_line("xs", "ys", source=src[f"polar_{key}_spokes"], line_color=GREY,
                   line_alpha=0.4, line_width=1)
    # On a light ground: a ring's value stays legible where a curve passes under it.
    fig.text("x", "y", "text", source=src[f"polar_{key}_ring_labels"], text_font_size="12px",
             text_color="#444444", text_align="center", text_baseline="middle",
             background_fill_color="white", background_fill_alpha=0.7)
    fig.text("x", "y", "text", source=src[f"polar_{key}_angle_labels"],
                      text_font_size="12px", text_color="#444444", text_align="center",
                      text_baseline="middle")
    fig.line("x", "y", source=src[f"polar_{key}_spoke"], line_color=VERMILION, line_width=1.5,
             line_dash="dashed")
    odd = QUANTITIES[key][2] == "odd"
    curve = fig.line("x", "y", source=src[f"polar_{key}"], line_color=BLUE, line_width=2.5,
                     visible=not odd)
    if odd:
        for sign, (label, color) in SIGN_LABELS.items():
            fig.line("x", "y", source=src[f"polar_{key}_{sign}"], line_color=color,
                     line_width=2.5, legend_label=label.format(name=SIGN_NAMES.get(key, key)))
        legend_above(fig)
        fig.legend.orientation = "vertical"
    fig.scatter("x", "y", source=src[f"polar_{key}_now"], size=11, fill_color=VERMILION,
                line_color=BLACK)
    fig.hover.renderers = [r for r in fig.renderers
                           if r.data_source.name.startswith(f"polar_{key}")
                           and r.data_source.name.endswith(("_pos", "_neg"))] if odd else [curve]
    fig.frame_width = fig.frame_height = min(width, height) - 50  # equal scales on x and y
    return fig


def extent(axis) -> float:
    """Half the side of the square shown: the rim with room for the angle labels."""
    return EXTENT_R * (axis[1] - axis[0])


def extent_data(key: str, axis) -> dict:
    """Two invisible corners, (-E, -E) and (E, E), that the figure's ranges cover."""
    E = extent(axis)
    return {f"polar_{key}_extent": {"x": [-E, E], "y": [-E, E]}}


def set_extent(fig, axis) -> None:
    """Fit the ranges of a polar figure to a new radial axis."""
    for renderer in fig.renderers:
        name = getattr(renderer.data_source, "name", None) or ""
        if name.startswith("polar_") and name.endswith("_extent"):
            key = name.removeprefix("polar_").removesuffix("_extent")
            renderer.data_source.data = extent_data(key, axis)[name]
