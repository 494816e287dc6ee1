"""The Design tab's figures: a real pillar array on the regime map, and an orientation
distribution over the Fig. 11a polar curve of its springs.

``design_map_figure`` is Fig. 5a (``regime_map_figure``) with the design's point, the
point the model computed when the design lies beyond the model range (scaled along its
speed line), and the speed line itself (both k~ scale as 1/V0^2: a diagonal of the
log-log map). Its log axes widen to show a point outside the paper's [0.01, 3]^2.
``design_polar_figure`` is Fig. 11a (``polar_figure``) with the distribution's density
(scaled to the rim) and its point masses as spokes.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import Range1d

from model.designs.distributions import from_dict, rotated
from model.contact.regimes import MODEL_RANGE

from .arrays import K_AXIS, regime_map_figure
from .common import BLACK, GREEN, ORANGE, VERMILION, source
from .polar import polar_data, polar_figure

#: Samples of the density around the circle.
DENSITY_N = 361


def map_axis(*values) -> tuple[float, float]:
    """A log axis holding the paper's map and ``values`` (a factor 3 to spare), within
    the model range."""
    v = [x for x in values if x is not None and math.isfinite(x) and x > 0]
    lo = min([K_AXIS[0], *(x / 3 for x in v)])
    hi = max([K_AXIS[1], *(x * 3 for x in v)])
    return max(lo, MODEL_RANGE[0] / 3), min(hi, MODEL_RANGE[1] * 3)


def design_map_data(point: dict | None, cover: dict | None = None) -> tuple[dict, tuple, tuple]:
    """Sources of the design on the map, and the x (k_r) and y (k_theta) axis ranges (which
    also hold the point ``cover``: a compared design's)."""
    empty = {"design_point": {"k_r": [], "k_theta": [], "label": [], "note": []},
             "design_computed": {"k_r": [], "k_theta": []},
             "design_line": {"k_r": [], "k_theta": [], "V0": []}}
    extra = (cover or {}).get("point") or {}
    if point is None:
        return empty, map_axis(extra.get("k_r")), map_axis(extra.get("k_theta"))
    p, c, line = point["point"], point["computed"], point["speed_line"]
    xr, yr = map_axis(p["k_r"], extra.get("k_r")), map_axis(p["k_theta"], extra.get("k_theta"))
    data = dict(empty)
    # A design beyond the axes (real pillars lie at k~ ~ 1e6-1e7) is drawn at their edge,
    # with an arrow and its values written beside it.
    x, y = on_axis(p["k_r"], xr), on_axis(p["k_theta"], yr)
    off = (x, y) != (p["k_r"], p["k_theta"])
    data["design_point"] = {
        "k_r": [x], "k_theta": [y], "label": [f"V₀ = {point['V0_m_per_s']:.3g} m/s"],
        "note": [f"off the map {_arrow(p['k_r'], x)}{_arrow(p['k_theta'], y, True)}\n"
                 f"k̃_r = {_e(p['k_r'])}\nk̃_θ = {_e(p['k_theta'])}" if off else ""]}
    if c is not None and c.get("scale", 1.0) < 1.0:
        data["design_computed"] = {"k_r": [c["k_r"]], "k_theta": [c["k_theta"]]}
    data["design_line"] = {"k_r": list(line["k_r"]), "k_theta": list(line["k_theta"]),
                           "V0": list(line["V0_m_per_s"])}
    return data, xr, yr


#: How far inside a log axis's end an off-axis point is drawn (a factor).
EDGE = 1.6


def on_axis(value: float, axis: tuple[float, float]) -> float:
    """``value`` if it lies on the log ``axis``, else just inside the end it lies beyond."""
    lo, hi = axis
    return hi / EDGE if value > hi / EDGE else lo * EDGE if value < lo * EDGE else value


def _e(x: float) -> str:
    """Two figures, with a short exponent: 5.5e6."""
    return f"{x:.2g}".replace("e+0", "e").replace("e+", "e").replace("e-0", "e-")


def _arrow(value: float, shown: float, vertical: bool = False) -> str:
    if value == shown:
        return ""
    if vertical:
        return "↑" if value > shown else "↓"
    return "→" if value > shown else "←"


def design_map_figure(regime_map, point: dict | None = None, width: int = 330,
                      height: int = 300):
    """Fig. 5a with the design's point and speed line (see the module docstring)."""
    fig = regime_map_figure(regime_map, "5a", "paper", None, width, height)
    fig.title.text = "The design on Fig. 5a (F_N = 1)"  # fits the narrow plot
    fig.name = "design_map"  # not the Regime map tab's figure
    data, xr, yr = design_map_data(point)
    fig.x_range = Range1d(*xr)
    fig.y_range = Range1d(*yr)
    line = fig.line("k_r", "k_theta", source=source("design_line", data["design_line"]),
                    line_color=ORANGE, line_width=2.5, line_dash="dashed",
                    legend_label="as V₀ changes")
    fig.scatter("k_r", "k_theta", source=source("design_computed", data["design_computed"]),
                marker="square", size=11, fill_color=GREEN, line_color=BLACK,
                legend_label="computed (scaled)")
    star = source("design_point", data["design_point"])
    fig.scatter("k_r", "k_theta", source=star, marker="star", size=20, fill_color=VERMILION,
                line_color=BLACK, legend_label="this design")
    fig.text("k_r", "k_theta", text="note", source=star, text_align="right",
             text_baseline="top", x_offset=-4, y_offset=12, text_font_size="12px",
             text_color=BLACK, background_fill_color="white", background_fill_alpha=0.85)
    fig.hover.renderers = [*fig.hover.renderers, line]
    fig.hover.tooltips = [*fig.hover.tooltips, ("V₀ [m/s]", "@V0{0.000e}")]
    # Too small a plot for a legend over the cells: the view's text names the marks.
    fig.legend.visible = False
    return fig


def density_data(distribution: dict | None, psi_deg: float, rim: float,
                 suffix: str = "") -> dict:
    """The distribution seen at ``psi_deg`` as a closed curve of radius rim * p / max p and
    its point masses as spokes of length rim * weight / max weight (sources named
    ``design_density``, ``design_atoms``, with ``suffix`` appended)."""
    curve = {"x": [], "y": [], "theta0_deg": [], "value": []}
    atoms = {"xs": [], "ys": [], "weight": []}
    if distribution is None:
        return {f"design_density{suffix}": curve, f"design_atoms{suffix}": atoms}
    dist = rotated(from_dict(distribution), math.radians(psi_deg))
    theta = np.linspace(0.0, 2 * math.pi, DENSITY_N)
    p = np.asarray(dist.density(theta), float)
    if dist.continuous_mass > 0 and np.nanmax(p) > 0:
        r = rim * p / np.nanmax(p)
        curve = {"x": r * np.cos(theta), "y": r * np.sin(theta),
                 "theta0_deg": np.degrees(theta), "value": p * math.pi / 180}
    pairs = dist.atoms()
    if pairs:
        top = max(w for _, w in pairs)
        atoms = {"xs": [[0.0, rim * w / top * math.cos(t)] for t, w in pairs],
                 "ys": [[0.0, rim * w / top * math.sin(t)] for t, w in pairs],
                 "weight": [w for _, w in pairs]}
    return {f"design_density{suffix}": curve, f"design_atoms{suffix}": atoms}


def design_polar_data(sweep, distribution: dict | None, psi_deg: float,
                      cover=None) -> tuple[dict, tuple]:
    """Fig. 11a of ``sweep`` (a SweepResult or None) with the distribution drawn over it;
    the radial axis also covers the sweep ``cover`` (a compared design's)."""
    theta0 = [] if sweep is None else sweep.columns["theta0"]
    values = [] if sweep is None else sweep.columns["FTx_over_mu0FN"]
    more = [] if cover is None else cover.columns["FTx_over_mu0FN"]
    data, axis = polar_data("FTx", theta0, values, more)
    data.update(density_data(distribution, psi_deg, axis[1] - axis[0]))
    return data, axis


def design_polar_figure(sweep=None, distribution: dict | None = None, psi_deg: float = 0.0,
                        width: int = 330, height: int = 320):
    """Fig. 11a of the design's springs with the orientation density over it."""
    data, axis = design_polar_data(sweep, distribution, psi_deg)
    theta0 = [] if sweep is None else sweep.columns["theta0"]
    values = [] if sweep is None else sweep.columns["FTx_over_mu0FN"]
    fig = polar_figure("FTx", theta0, values, None, width, height)
    fig.title.text = "Fig. 11a F_T,x/(μ₀F_N); orange: p(θ₀)"  # fits a projected plot
    fig.name = "design_polar"  # not the Orientation tab's figure
    fig.patch("x", "y", source=source("design_density", data["design_density"]),
              fill_color=ORANGE, fill_alpha=0.3, line_color=ORANGE, line_width=1.5)
    fig.multi_line("xs", "ys", source=source("design_atoms", data["design_atoms"]),
                   line_color=ORANGE, line_width=5, line_alpha=0.8)
    return fig
