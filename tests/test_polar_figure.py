"""The polar diagrams (app/figures/polar.py): an odd quantity drawn in two colours by sign,
equal scales in a figure of any shape."""
import math

import numpy as np

from app.figures import polar


def test_an_odd_quantity_is_split_by_sign_and_each_part_reaches_the_zero_ring():
    theta = np.linspace(0, math.pi, 37)
    values = 0.1 * np.sin(theta) * np.cos(theta)  # > 0 below 90 deg, < 0 above
    data, axis = polar.polar_data("FTy", theta, values)
    curve, pos, neg = (data[f"polar_FTy{s}"] for s in ("", "_pos", "_neg"))
    full = np.asarray(curve["value"])
    x_pos, x_neg = np.asarray(pos["x"]), np.asarray(neg["x"])
    assert np.all(np.isfinite(x_pos[full > 0])) and np.all(np.isfinite(x_neg[full < 0]))
    # Away from sign changes a point belongs to one part only.
    inside = (full < -1e-3) & (np.roll(full, 1) < 0) & (np.roll(full, -1) < 0)
    assert inside.any() and np.all(np.isnan(x_pos[inside]))
    # Negative values lie inside the zero ring, positive ones outside.
    r = np.hypot(curve["x"], curve["y"])
    zero = -axis[0]
    assert np.all(r[full < 0] < zero + 1e-12) and np.all(r[full > 0] > zero - 1e-12)


def test_even_quantities_have_no_sign_parts_and_the_figure_keeps_equal_scales():
    theta = np.linspace(0, math.pi, 19)
    data, axis = polar.polar_data("FTx", theta, 0.9 + 0.05 * np.cos(theta))
    assert "polar_FTx_pos" not in data
    fig = polar.polar_figure("FTx", theta, 0.9 + 0.05 * np.cos(theta))
    assert fig.match_aspect
    corners = [r.data_source.data for r in fig.renderers
               if r.data_source.name == "polar_FTx_extent"][0]
    E = polar.extent(axis)
    assert corners == {"x": [-E, E], "y": [-E, E]}
    polar.set_extent(fig, (0.0, 2.0, [1.0, 2.0]))
    corners = [r.data_source.data for r in fig.renderers
               if r.data_source.name == "polar_FTx_extent"][0]
    assert corners["x"][1] == polar.extent((0.0, 2.0, [1.0, 2.0]))


def test_the_odd_diagram_has_a_legend_for_each_sign():
    theta = np.linspace(0, math.pi, 19)
    fig = polar.polar_figure("FTy", theta, 0.1 * np.sin(2 * theta))
    labels = [item.label["value"] for legend in fig.above if hasattr(legend, "items")
              for item in legend.items]
    assert any("F_T,y > 0" in s and "outside" in s for s in labels), labels
    assert any("F_T,y < 0" in s and "inside" in s for s in labels), labels
