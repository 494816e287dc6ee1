"""The pinned state "A" of a comparison, drawn muted under the current state "B".

``add_pinned`` gives an existing figure A's glyphs -- dashed, thinner and translucent,
drawn below B's -- with a legend above the plot naming "B (current)" and "A (pinned)";
both stay hidden (``show_pinned``) while nothing is pinned, so a page without a
comparison draws nothing more. The ``*_A`` functions give the data of A's sources, named
as B's with ``_A`` appended (``orbit_A``, ``forces_A``, ``polar_FTx_A``, ``load_curve_A``;
on the Design tab ``design_point_A``, ``design_curve_A``, ``design_density_A``,
``design_atoms_A``) so browser tests find both data sets.
"""
from __future__ import annotations

import math

import numpy as np
from bokeh.models import GlyphRenderer, Legend, LegendItem

from .common import BLUE, GREY, VERMILION, source
from .design import density_data
from .polar import QUANTITIES, full_circle

#: How A is drawn: B's line muted.
MUTED = dict(line_alpha=0.55, line_dash=[6, 3])
A_LABEL, B_LABEL = "A (pinned)", "B (current)"


def _empty(*columns) -> dict:
    return {c: [] for c in columns}


def orbit_A(series, params) -> dict:
    """A's path and rest position in the top view (Eqs. 1-6)."""
    if series is None or params is None:
        return {"orbit_A": _empty("x", "y"), "scene_points_A": _empty("x", "y")}
    return {"orbit_A": {"x": series.x, "y": series.y},
            "scene_points_A": {"x": [math.cos(params.theta0)], "y": [math.sin(params.theta0)]}}


def forces_A(series) -> dict:
    """A's Fig. 7 histories (the columns of ``histories.force_data``)."""
    if series is None:
        return {"forces_A": _empty("tau", "F_x", "F_y", "F_abs")}
    return {"forces_A": {"tau": series.tau, "F_x": series.F_x, "F_y": series.F_y,
                         "F_abs": series.F_abs}}


def polar_A(key: str, theta0, values, parity: str, axis) -> dict:
    """A's Fig. 11 curve in the radial ``axis`` of B's diagram (which covers both)."""
    if theta0 is None or len(theta0) == 0:
        return {f"polar_{key}_A": _empty("x", "y", "theta0_deg", "value")}
    theta, vals = full_circle(theta0, values, parity)
    r = np.clip(vals - axis[0], 0.0, None)
    return {f"polar_{key}_A": {"x": r * np.cos(theta), "y": r * np.sin(theta),
                               "theta0_deg": np.degrees(theta) % 360, "value": vals}}


def load_curve_A(points: dict | None, column: str) -> dict:
    """A's Fig. 6 curve: ``points`` maps F_N -> uniform-array row."""
    F = sorted(points or {})
    return {"load_curve_A": {"F_N": F, "value": [points[f][column] for f in F]}}


def design_point_A(point: dict | None) -> dict:
    """A's design on the map of the Design tab: its dimensionless point (Eq. 5)."""
    if point is None:
        return {"design_point_A": _empty("k_r", "k_theta", "label")}
    p = point["point"]
    return {"design_point_A": {"k_r": [p["k_r"]], "k_theta": [p["k_theta"]],
                               "label": [f"A: V₀ = {point['V0_m_per_s']:.3g} m/s"]}}


def design_polar_A(sweep, distribution: dict | None, psi_deg: float, axis) -> dict:
    """A's Fig. 11a curve (``sweep`` at its design's springs) and its orientation density,
    in the radial ``axis`` of B's diagram (which covers both curves)."""
    theta0 = values = None
    if sweep is not None:
        theta0, values = sweep.columns["theta0"], sweep.columns["FTx_over_mu0FN"]
    curve = polar_A("FTx", theta0, values, QUANTITIES["FTx"][2], axis)["polar_FTx_A"]
    rim = 1.0 if axis is None else axis[1] - axis[0]
    return {"design_curve_A": curve, **density_data(distribution, psi_deg, rim, "_A")}


def add_pinned(fig, kind: str, b_source: str, key: str = "") -> list:
    """Add A's glyphs of ``kind`` (scene, forces, polar, load) to ``fig`` and the A/B
    legend (B's glyph in it: the first drawn from the source ``b_source``); returns A's
    renderers, hidden."""
    b_renderer = next(r for r in fig.renderers
                      if isinstance(r, GlyphRenderer) and r.data_source.name == b_source)
    if kind == "scene":
        data = orbit_A(None, None)
        src = {n: source(n, d) for n, d in data.items()}
        renderers = [fig.line("x", "y", source=src["orbit_A"], line_color=GREY, line_width=2,
                              **MUTED),
                     fig.scatter("x", "y", source=src["scene_points_A"], size=9,
                                 fill_color="white", line_color=GREY, line_width=2)]
    elif kind == "forces":
        src = source("forces_A", forces_A(None)["forces_A"])
        renderers = [fig.line("tau", column, source=src, line_color=color, line_width=1.5,
                              **MUTED)
                     for column, color in (("F_abs", GREY), ("F_x", BLUE), ("F_y", VERMILION))]
    elif kind == "polar":
        src = source(f"polar_{key}_A", polar_A(key, None, None, "even", None)[f"polar_{key}_A"])
        renderers = [fig.line("x", "y", source=src, line_color=GREY, line_width=2, **MUTED)]
    elif kind == "load":
        src = source("load_curve_A", load_curve_A(None, "")["load_curve_A"])
        renderers = [fig.line("F_N", "value", source=src, line_color=GREY, line_width=2.5,
                              **MUTED),
                     fig.scatter("F_N", "value", source=src, size=6, color=GREY, alpha=0.7)]
    elif kind == "design_map":
        src = source("design_point_A", design_point_A(None)["design_point_A"])
        renderers = [fig.scatter("k_r", "k_theta", source=src, marker="star", size=17,
                                 fill_color=GREY, fill_alpha=0.35, line_color=GREY,
                                 line_width=1.5)]
    elif kind == "design_polar":
        data = design_polar_A(None, None, 0.0, None)
        src = {n: source(n, d) for n, d in data.items()}
        renderers = [fig.patch("x", "y", source=src["design_density_A"], fill_alpha=0.0,
                               line_color=GREY, line_width=1.5, **MUTED),
                     fig.line("x", "y", source=src["design_curve_A"], line_color=GREY,
                              line_width=2, **MUTED),
                     fig.multi_line("xs", "ys", source=src["design_atoms_A"], line_color=GREY,
                                    line_width=4, line_alpha=0.5)]
    else:
        raise ValueError(f"kind={kind!r}: choose scene, forces, polar, load, design_map or "
                         "design_polar")
    for renderer in renderers:
        renderer.visible = False
    # Under B's glyphs, which stay in front: below everything, or on the map just below
    # B's point (above the map's cells).
    rest = [r for r in fig.renderers if all(r is not a for a in renderers)]
    at = next(i for i, r in enumerate(rest) if r is b_renderer) if kind == "design_map" else 0
    fig.renderers = [*rest[:at], *renderers, *rest[at:]]
    legend = Legend(items=[LegendItem(label=B_LABEL, renderers=[b_renderer]),
                           LegendItem(label=A_LABEL, renderers=[renderers[0]])],
                    name=f"{fig.name}_compare_legend", orientation="horizontal",
                    location="top_left", padding=1, spacing=8, margin=0, glyph_width=22,
                    label_standoff=3, border_line_alpha=0, background_fill_alpha=0,
                    label_text_font_size="10px", visible=False)
    fig.add_layout(legend, "above")
    return renderers


def show_pinned(fig, renderers, on: bool) -> None:
    """Show or hide A's glyphs and the A/B legend of ``fig``."""
    for renderer in renderers:
        if renderer.visible != on:
            renderer.visible = on
    for model in fig.above:
        if getattr(model, "name", "") == f"{fig.name}_compare_legend" and model.visible != on:
            model.visible = on
