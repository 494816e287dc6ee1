"""Uniform-orientation arrays: the regime map (Fig. 5a/5b) and the load curves (Fig. 6).

``regime_map_figure`` draws a precomputed ``model.runs.shipped_map.RegimeMap`` on log axes as
cells coloured by F_T,x/(mu0 F_N) (5a, paper or duration-weighted average) or D_y/D_x
(5b), labels the paper's four regimes and marks the current (k_r, k_theta).
``load_figure`` draws F_T,x/(mu0 F_N) against F_N for the four regimes and the current
springs.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import ColorBar, LinearColorMapper, Range1d, Span
from bokeh.palettes import Cividis256, Viridis256

from model.contact.params import REGIMES

from ..state import K_MID
from .common import BLACK, GREY, REGIME_COLORS, VERMILION, new_figure, source

MAP_QUANTITIES = {
    "5a": ("FTx_over_mu0FN", "Uniform array F_T,x/(μ₀F_N)"),
    "5b": ("Dy_over_Dx", "Uniform array D_y/D_x"),
}
AVERAGE_COLUMNS = {"paper": "FTx_over_mu0FN", "duration": "FTx_over_mu0FN_duration"}


def map_title(quantity: str, regime_map=None, average: str = "paper") -> str:
    """The map's title: its quantity (and average), and the load of the map on show; the
    average and the load on a second line (one line runs out of a phone's figure)."""
    F_N = (regime_map.metadata.get("F_N", 1.0) if regime_map is not None else None)
    parts = ([f"{'duration-weighted' if average == 'duration' else 'Eq. 10'} average"]
             if quantity == "5a" else []) + ([f"F_N = {F_N:g}"] if F_N is not None else [])
    second = f"\n{', '.join(parts)}" if parts else ""
    return f"{MAP_QUANTITIES[quantity][1]} (Fig. {quantity}){second}"
K_AXIS = (0.008, 3.8)


def _edges(k):
    """Cell edges of a log grid of centres ``k``."""
    lk = np.log10(np.asarray(k, float))
    mid = (lk[1:] + lk[:-1]) / 2
    return 10 ** np.concatenate(([lk[0] - (mid[0] - lk[0])], mid, [lk[-1] + (lk[-1] - mid[-1])]))


def map_column(quantity: str, average: str = "paper") -> str:
    return AVERAGE_COLUMNS[average] if quantity == "5a" else MAP_QUANTITIES[quantity][0]


def map_data(regime_map, quantity: str = "5a", average: str = "paper") -> dict:
    """Cells of the map, one row per (k_r, k_theta), with ``value`` the shown quantity
    (no cells while there is no map)."""
    if regime_map is None:
        return {"regime_map": {k: [] for k in ("k_r", "k_theta", "left", "right", "bottom",
                                               "top", "value", "FTx", "FTx_duration", "DyDx",
                                               "Nc")}}
    er, et = _edges(regime_map.k_r), _edges(regime_map.k_theta)
    i, j = np.meshgrid(np.arange(regime_map.k_r.size), np.arange(regime_map.k_theta.size),
                       indexing="ij")
    i, j = i.ravel(), j.ravel()
    value = np.asarray(getattr(regime_map, map_column(quantity, average)), float)[i, j]
    return {"regime_map": {
        "k_r": regime_map.k_r[i], "k_theta": regime_map.k_theta[j],
        "left": er[i], "right": er[i + 1], "bottom": et[j], "top": et[j + 1], "value": value,
        "FTx": regime_map.FTx_over_mu0FN[i, j],
        "FTx_duration": regime_map.FTx_over_mu0FN_duration[i, j],
        "DyDx": regime_map.Dy_over_Dx[i, j], "Nc": regime_map.Nc_over_Nc0[i, j]}}


def value_range(values) -> tuple[float, float]:
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    return (float(v.min()), float(v.max())) if v.size else (0.0, 1.0)


def map_now(k_r: float, k_theta: float) -> dict:
    return {"regime_now": {"k_r": [k_r], "k_theta": [k_theta]}}


def regime_map_figure(regime_map, quantity: str = "5a", average: str = "paper",
                      current=None, width: int = 560, height: int = 480):
    """Fig. 5a/5b on log axes; ``current`` = (k_r, k_theta) is marked."""
    data = map_data(regime_map, quantity, average)["regime_map"]
    lo, hi = value_range(data["value"])
    fig = new_figure("regime_map", map_title(quantity, regime_map, average), width, height,
                     x_axis_type="log", y_axis_type="log", x_range=Range1d(*K_AXIS),
                     y_range=Range1d(*K_AXIS), x_axis_label="k_r (radial stiffness)",
                     y_axis_label="k_θ (torsional stiffness)",
                     tooltips=[("k_r, k_θ", "@k_r{0.000}, @k_theta{0.000}"),
                               ("F_T,x/(μ₀F_N) paper", "@FTx{0.0000}"),
                               ("duration-weighted", "@FTx_duration{0.0000}"),
                               ("D_y/D_x", "@DyDx{0.0000}"), ("N_c/N_c0", "@Nc{0.00}")])
    mapper = LinearColorMapper(palette=Viridis256 if quantity == "5a" else Cividis256,
                               low=lo, high=hi, name="regime_map_colors")
    cells = fig.quad("left", "right", "bottom", "top", source=source("regime_map", data),
                     fill_color={"field": "value", "transform": mapper}, line_color=None)
    fig.hover.renderers = [cells]
    fig.add_layout(ColorBar(color_mapper=mapper, width=12, name="regime_map_colorbar"), "right")
    # Where the page's regime text switches (quadrants about the log-midpoint of the axes).
    for dimension in ("width", "height"):
        fig.add_layout(Span(location=K_MID, dimension=dimension, line_color="white",
                            line_dash="dashed", line_width=2, line_alpha=0.9,
                            name=f"regime_boundary_{dimension}"))
    names = list(REGIMES)
    fig.scatter([REGIMES[n].k_r for n in names], [REGIMES[n].k_theta for n in names],
                marker="diamond", size=12, fill_color="white", line_color=BLACK)
    offsets = {"pendulum": (-1, 1), "slider": (1, -1), "stiff": (-1, -1), "soft": (1, 1)}
    fig.text([REGIMES[n].k_r for n in names], [REGIMES[n].k_theta for n in names], names,
             x_offset=[10 * offsets[n][0] for n in names],
             y_offset=[-12 * offsets[n][1] for n in names],
             text_align=["right" if offsets[n][0] < 0 else "left" for n in names],
             text_baseline="middle", text_font_size="13px", text_font_style="bold",
             text_color="white", background_fill_color=BLACK, background_fill_alpha=0.55)
    now = map_now(*(current if current is not None else (math.nan, math.nan)))
    fig.scatter("k_r", "k_theta", source=source("regime_now", now["regime_now"]),
                marker="circle_cross", size=18, fill_color=VERMILION, fill_alpha=0.6,
                line_color="white", line_width=2)
    return fig


def load_regimes_data(curves=None, average: str = "paper") -> dict:
    """The four regimes' Fig. 6 curves: ``curves`` maps regime -> {F_N: uniform-array row}."""
    curves = {r: c for r, c in (curves or {}).items() if c}
    regimes = [r for r in REGIMES if r in curves]
    col = AVERAGE_COLUMNS[average]
    return {"load_regimes": {"xs": [sorted(curves[r]) for r in regimes],
                             "ys": [[curves[r][f][col] for f in sorted(curves[r])]
                                    for r in regimes],
                             "regime": regimes, "color": [REGIME_COLORS[r] for r in regimes]}}


def load_curve_data(points: dict, average: str = "paper") -> dict:
    """The current springs' curve: ``points`` maps F_N -> uniform-array row."""
    F = sorted(points)
    col = AVERAGE_COLUMNS[average]
    return {"load_curve": {"F_N": F, "value": [points[f][col] for f in F],
                           "error": [points[f]["quadrature_error_FTx"] for f in F]}}


def load_now(F_N: float, value=None) -> dict:
    v = [] if value is None or not math.isfinite(value) else [value]
    return {"load_now": {"F_N": [F_N] if v else [], "value": v}}


def load_figure(regimes=None, points=None, current=None, average: str = "paper",
                width: int = 620, height: int = 440):
    """Fig. 6: uniform-array F_T,x/(mu0 F_N) against F_N (log axis) for the regimes
    (``regimes``: regime -> {F_N: row}) and the current springs (``points``: {F_N: row});
    ``current`` is (F_N, value) for the current springs and load."""
    fig = new_figure("load", "Uniform array F_T,x/(μ₀F_N) vs load F_N (Fig. 6)", width,
                     height, x_axis_type="log", x_range=Range1d(0.08, 12.5),
                     x_axis_label="F_N (normal load)", y_axis_label="F_T,x / (μ₀ F_N)",
                     tooltips=[("F_N", "@F_N{0.000}"), ("F_T,x/(μ₀F_N)", "@value{0.0000}")])
    reg = source("load_regimes", load_regimes_data(regimes, average)["load_regimes"])
    fig.multi_line("xs", "ys", source=reg, line_color="color", line_width=3, line_alpha=0.95,
                   line_dash="dashed", legend_field="regime")
    curve = source("load_curve", load_curve_data(points or {}, average)["load_curve"])
    line = fig.line("F_N", "value", source=curve, line_color=BLACK, line_width=3,
                    legend_label="current k_r, k_θ")
    fig.scatter("F_N", "value", source=curve, size=7, color=BLACK)
    now = load_now(*(current if current is not None else (1.0, None)))
    fig.scatter("F_N", "value", source=source("load_now", now["load_now"]), size=14,
                fill_color=VERMILION, line_color=BLACK, legend_label="current F_N")
    fig.add_layout(Span(location=1.0, dimension="width", line_color=GREY, line_dash="dotted"))
    fig.hover.renderers = [line]
    fig.legend.location = "bottom_left"
    fig.legend.label_text_font_size = "11px"
    return fig
