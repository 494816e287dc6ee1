"""The Design tab's friction against sliding speed (``model.lab.speed_curve``): the
structured surface's F_T,x/F_N at each computed speed V0 with its quadrature error as an
error bar (hover: the integration error too), the flat material's mu(V0) of Eq. (4), and a
measured curve of the structured sample (its ``mu_err`` as error bars); below, measured -
predicted at the measured speeds with the combined error that decides agreement
(``model.lab.friction_compare``).

``speeds_data`` and ``difference_data`` give the sources (and axis extents) for new data;
``speeds_figure`` and ``difference_figure`` draw empty figures whose named sources a view
fills (``common.update``).
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import FixedTicker, HoverTool, Range1d, Span

from .common import BLACK, BLUE, GREY, VERMILION, legend_below, new_figure, source

EMPTY = {"speeds_flat": {"v": [], "mu": []},
         "speeds_model": {"v": [], "mu": [], "lo": [], "hi": [], "quad": [], "energy": [],
                          "status": []},
         "speeds_measured": {"v": [], "mu": [], "lo": [], "hi": []},
         "speeds_difference": {"v": [], "d": [], "lo": [], "hi": [], "disagree": []}}
#: Points of the flat law's curve across the axis.
N_FLAT = 120


def _finite(values) -> list[float]:
    return [float(v) for v in values if math.isfinite(v)]


def speeds_data(points, law=None, measured=None):
    """``(data, (v_lo, v_hi), (mu_lo, mu_hi))`` for ``speeds_figure``: the arrived
    ``points`` (``SpeedPoint`` or None), the flat ``law`` (``FrictionLaw`` with its own
    V_s, or None) across the axis, and the ``measured`` ``FrictionCurve`` (or None)."""
    data = {k: dict(v) for k, v in EMPTY.items()}
    done = [p for p in points if p is not None]
    speeds = [p.V0 for p in points if p is not None] + (
        [] if measured is None else list(measured.v[measured.v > 0]))
    if not speeds and law is not None and law.V_s is not None:
        speeds = [law.V_s / 10, law.V_s * 10]
    v_lo, v_hi = (min(speeds) / 1.3, max(speeds) * 1.3) if speeds else (1e-3, 1.0)
    if law is not None and law.V_s is not None:
        v = np.geomspace(v_lo, v_hi, N_FLAT)
        data["speeds_flat"] = {"v": v, "mu": law.mu(v)}
    ok = [p for p in done if math.isfinite(p.mu_apparent)]
    err = [p.quadrature_error if math.isfinite(p.quadrature_error) else 0.0 for p in ok]
    data["speeds_model"] = {
        "v": [p.V0 for p in ok], "mu": [p.mu_apparent for p in ok],
        "lo": [p.mu_apparent - e for p, e in zip(ok, err)],
        "hi": [p.mu_apparent + e for p, e in zip(ok, err)],
        "quad": [p.quadrature_error for p in ok], "energy": [p.integration_error for p in ok],
        "status": [p.status for p in ok]}
    if measured is not None:
        shown = measured.v > 0
        e = np.zeros_like(measured.mu) if measured.mu_err is None else measured.mu_err
        data["speeds_measured"] = {"v": measured.v[shown], "mu": measured.mu[shown],
                                   "lo": (measured.mu - e)[shown], "hi": (measured.mu + e)[shown]}
    values = (_finite(data["speeds_flat"]["mu"]) + _finite(data["speeds_model"]["lo"])
              + _finite(data["speeds_model"]["hi"]) + _finite(data["speeds_measured"]["lo"])
              + _finite(data["speeds_measured"]["hi"]))
    lo, hi = (min(values), max(values)) if values else (0.0, 1.5)
    pad = 0.08 * (hi - lo) if hi > lo else 0.05 * max(abs(hi), 0.1)
    return data, (v_lo, v_hi), (lo - pad, hi + pad)


def difference_data(comparison):
    """``(data, (d_lo, d_hi))`` for ``difference_figure`` from a ``FrictionComparison``
    (or None): measured - predicted with the combined error as an error bar."""
    data = {"speeds_difference": dict(EMPTY["speeds_difference"])}
    if comparison is None:
        return data, (-0.01, 0.01)
    c = comparison
    ok = np.isfinite(c.difference)
    disagree = np.isin(c.v, np.asarray(c.disagree, dtype=float))
    data["speeds_difference"] = {
        "v": c.v[ok], "d": c.difference[ok], "lo": (c.difference - c.tolerance)[ok],
        "hi": (c.difference + c.tolerance)[ok],
        "disagree": np.where(disagree[ok], "disagrees", "agrees").tolist()}
    reach = _finite(np.abs(c.difference[ok]) + c.tolerance[ok]) or [0.01]
    top = 1.1 * max(reach)
    return data, (-top, top)


def speed_ticks(lo: float, hi: float) -> list[float]:
    """Ticks 1, 2, 5 x 10^k between ``lo`` and ``hi`` (m/s), only the decades when that makes
    more than seven, the two ends when fewer than two: a log axis spanning a decade or two
    otherwise crowds its labels."""
    k0, k1 = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    marks = [(m, m * 10.0 ** k) for k in range(k0, k1 + 1) for m in (1, 2, 5)
             if lo <= m * 10.0 ** k <= hi]
    ticks = [t for m, t in marks if len(marks) <= 7 or m == 1]
    return ticks if len(ticks) >= 2 else [float(f"{lo:.2g}"), float(f"{hi:.2g}")]


def set_speed_axis(fig, lo: float, hi: float) -> None:
    """The V0 axis of either figure from ``lo`` to ``hi`` (m/s), with ``speed_ticks``."""
    fig.x_range.update(start=lo, end=hi)
    fig.xaxis[0].ticker.ticks = speed_ticks(lo, hi)


def _speed_axis(fig) -> None:
    fig.xaxis[0].ticker = FixedTicker(ticks=speed_ticks(1e-3, 1.0))


def speeds_figure(width: int = 310, height: int = 300):
    """F_T,x/F_N and mu against V0, empty (see the module docstring)."""
    fig = new_figure("design_speeds", "Friction vs sliding speed", width, height,
                     x_axis_type="log", x_axis_label="sliding speed V₀ [m/s]",
                     y_axis_label="friction coefficient F_T,x/F_N, μ",
                     x_range=Range1d(1e-3, 1.0), y_range=Range1d(0.0, 1.5))
    fig.line("v", "mu", source=source("speeds_flat", EMPTY["speeds_flat"]), line_color=GREY,
             line_width=2, line_dash="dashed", legend_label="flat μ(V₀)")
    model = source("speeds_model", EMPTY["speeds_model"])
    fig.segment(x0="v", y0="lo", x1="v", y1="hi", source=model, line_color=BLACK)
    fig.line("v", "mu", source=model, line_color=BLACK, line_width=1.5)
    dots = fig.scatter("v", "mu", source=model, size=6, fill_color=BLACK, line_color=BLACK,
                       legend_label="pillars (model)")
    measured = source("speeds_measured", EMPTY["speeds_measured"])
    fig.segment(x0="v", y0="lo", x1="v", y1="hi", source=measured, line_color=BLUE)
    fig.scatter("v", "mu", source=measured, size=6, marker="diamond", fill_color="white",
                line_color=BLUE, legend_label="measured")
    fig.add_tools(HoverTool(renderers=[dots], tooltips=[
        ("V₀", "@v{0.000e} m/s"), ("F_T,x/F_N", "@mu{0.00000}"),
        ("quadrature error", "@quad{0.0e}"),
        ("integration error (energy)", "@energy{0.0e}"), ("status", "@status")]))
    legend_below(fig)
    fig.legend[0].ncols = 2  # two rows: a projected one-row legend is wider than the plot
    _speed_axis(fig)
    return fig


def difference_figure(width: int = 310, height: int = 170):
    """Measured - predicted against V0, empty: error bars are the combined error."""
    fig = new_figure("design_speeds_difference", "Measured − predicted", width, height,
                     x_axis_type="log", x_axis_label="sliding speed V₀ [m/s]",
                     y_axis_label="Δ(F_T,x/F_N)", x_range=Range1d(1e-3, 1.0),
                     y_range=Range1d(-0.01, 0.01))
    fig.add_layout(Span(location=0.0, dimension="width", line_color=GREY, line_dash="dotted"))
    diff = source("speeds_difference", EMPTY["speeds_difference"])
    fig.segment(x0="v", y0="lo", x1="v", y1="hi", source=diff, line_color=GREY)
    dots = fig.scatter("v", "d", source=diff, size=6, fill_color=VERMILION,
                       line_color=BLACK)
    fig.add_tools(HoverTool(renderers=[dots], tooltips=[
        ("V₀", "@v{0.000e} m/s"), ("measured − predicted", "@d{0.00000}"),
        ("", "@disagree")]))
    _speed_axis(fig)
    return fig
