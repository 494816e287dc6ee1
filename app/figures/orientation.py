"""Supports of fixed-orientation arrays (Fig. 10): their paths and fluctuations.

* ``components_figure`` -- two components (x, y or v_x, v_y) against tau for several
  theta0 (Fig. 10a-d);
* ``radius_figure`` -- r (in r0) against tau for both regimes and several theta0 (10e);
* ``rms_figure`` -- Delta theta_rms and Delta r_rms against theta0 (10f).

``curves`` map a label (e.g. ``"θ₀ = π/4"``) to a ``TimeSeries``; ``tables`` map a regime
to the columns of ``model.orientation_table``.
"""
from __future__ import annotations

import numpy as np
from bokeh.models import Range1d

from .common import BLACK, BLUE, GREEN, REGIME_COLORS, VERMILION, new_figure, source

CURVE_COLORS = (BLUE, VERMILION, GREEN, BLACK)
DASHES = ("solid", "dashed", "dotdash", "dotted")
LABELS = {"x": "x̃", "y": "ỹ", "v_x": "ṽ_x", "v_y": "ṽ_y", "r": "r̃"}


def components_data(curves: dict, pair=("x", "y")) -> dict:
    """Sources of Fig. 10a-d: one per (theta0 label, component)."""
    return {f"{pair[k]}_{i}": {"tau": s.tau, "value": getattr(s, pair[k])}
            for i, s in enumerate(curves.values()) for k in range(2)}


def components_figure(curves: dict, pair=("x", "y"), title: str = "", width: int = 560,
                      height: int = 400):
    """Fig. 10a-d: ``pair`` of components against tau, a colour per theta0, solid for the
    first component and dashed for the second."""
    name = "_".join(pair)
    fig = new_figure(f"components_{name}", title, width, height, x_axis_label="τ",
                     y_axis_label=f"{LABELS[pair[0]]}, {LABELS[pair[1]]}")
    data = components_data(curves, pair)
    for i, label in enumerate(curves):
        for k, dash in ((0, "solid"), (1, "dashed")):
            key = f"{pair[k]}_{i}"
            fig.line("tau", "value", source=source(key, data[key]), line_width=2,
                     line_color=CURVE_COLORS[i % 4], line_dash=dash,
                     legend_label=f"{LABELS[pair[k]]}, {label}")
    fig.legend.location = "top_left"
    fig.legend.label_text_font_size = "10px"
    fig.legend.click_policy = "hide"
    return fig


def radius_figure(curves: dict, width: int = 560, height: int = 400):
    """Fig. 10e: r (in r0, log axis) against tau; ``curves`` map (regime, theta0 label)
    to a ``TimeSeries``; colour by regime, dash by theta0."""
    fig = new_figure("radius", "Support length r̃ during contact (Fig. 10e)", width, height,
                     y_axis_type="log", x_axis_label="τ", y_axis_label="r̃ = r / r₀")
    dash = {}
    for i, ((regime, label), s) in enumerate(curves.items()):
        dash.setdefault(label, DASHES[len(dash) % 4])
        fig.line("tau", "r", source=source(f"radius_{i}", {"tau": s.tau, "r": s.r}),
                 line_width=2, line_color=REGIME_COLORS.get(regime, BLACK),
                 line_dash=dash[label], legend_label=f"{regime}, {label}")
    fig.legend.location = "top_left"
    fig.legend.label_text_font_size = "10px"
    fig.legend.click_policy = "hide"
    return fig


def rms_data(tables: dict) -> dict:
    """Fig. 10f sources: per regime, theta0 in degrees with Delta theta_rms, Delta r_rms."""
    return {f"rms_{regime}": {"theta0_deg": np.degrees(np.asarray(t["theta0"], float)),
                              "dtheta_rms": np.asarray(t["dtheta_rms"], float),
                              "dr_rms": np.asarray(t["dr_rms"], float)}
            for regime, t in tables.items()}


def rms_figure(tables: dict, width: int = 560, height: int = 400):
    """Fig. 10f: Delta theta_rms (solid, radians) and Delta r_rms (dashed, in r0) of the
    fixed arrays against theta0, a colour per regime, on a log axis."""
    fig = new_figure("rms", "RMS fluctuations over the contact (Fig. 10f)", width, height,
                     y_axis_type="log", x_range=Range1d(0, 180),
                     x_axis_label="θ₀ (degrees)", y_axis_label="Δθ_rms (rad), Δr̃_rms")
    for regime, data in rms_data(tables).items():
        src = source(regime, data)
        name, color = regime[4:], REGIME_COLORS.get(regime[4:], BLACK)
        fig.line("theta0_deg", "dtheta_rms", source=src, line_color=color, line_width=2,
                 legend_label=f"Δθ_rms, {name}")
        fig.line("theta0_deg", "dr_rms", source=src, line_color=color, line_width=2,
                 line_dash="dashed", legend_label=f"Δr̃_rms, {name}")
    fig.xaxis.ticker = list(range(0, 181, 30))
    fig.legend.location = "bottom_right"
    fig.legend.label_text_font_size = "10px"
    fig.legend.click_policy = "hide"
    return fig
