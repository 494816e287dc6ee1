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


def _dejavu_width(text: str, px: float) -> float:
    """The drawn width (px) of ``text`` in DejaVu Sans, the font matplotlib ships."""
    from matplotlib import font_manager
    from PIL import ImageFont
    path = font_manager.findfont(font_manager.FontProperties(family="DejaVu Sans"))
    return ImageFont.truetype(path, 100).getlength(text) * px / 100


def _drawn_boxes(axis, indices, frame_px, font_px):
    """Text boxes (px, centred, no gap) of the ring labels ``indices`` and the angle labels
    of ``axis`` in a square frame of ``frame_px`` showing +-``polar.extent(axis)``."""
    px = frame_px / (2 * polar.extent(axis))
    R = axis[1] - axis[0]
    c, s = (f(math.radians(polar.RING_LABEL_DEG)) for f in (math.cos, math.sin))

    def box(x, y, text):
        w = _dejavu_width(text, font_px)
        return (x - w / 2, y - font_px / 2, x + w / 2, y + font_px / 2)
    rings = [box((axis[2][i] - axis[0]) * px * c, (axis[2][i] - axis[0]) * px * s,
                 f"{axis[2][i]:g}") for i in indices]
    a = polar.ANGLE_LABEL_R * R * px
    angles = [box(a * math.cos(math.radians(d)), a * math.sin(math.radians(d)), f"{d}°")
              for d in polar.SPOKES_DEG]
    return rings, angles


def _clash(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


AXES = [(values, parity) for parity, cases in (
    ("even", ([1.1], [0.97], [0.19], [23.0], [3e-5], [0.5], [4.2], [0.0031, -0.0007], [7.3],
              [0.012], [0.33], [1.0], [145.0])),
    ("odd", ([-0.14, 0.14], [-0.09, 0.09], [0.05], [2.2e-7, -1e-7], [0.7], [-31.0])))
    for values in cases]


def test_the_ring_labels_run_into_nothing_with_projector_text():
    """Drawn in DejaVu Sans (wider than the usual sans-serif fonts) at the projector's text
    size, in the frame the layout is made for: no two ring labels touch, none touches
    an angle label, every angle label lies in the frame; the zero ring of an odd quantity
    and the rim of an even one are labelled, and every other ring at a fixed step."""
    for values, parity in AXES:
        axis = polar.radial_axis(values, parity)
        chosen = polar.labelled_rings(axis)
        rings, angles = _drawn_boxes(axis, chosen, polar.LABEL_FRAME_PX, polar.LABEL_FONT_PX)
        where = f"{[f'{v:g}' for v in axis[2]]}: labelled {[axis[2][i] for i in chosen]}"
        for j, b in enumerate(rings):
            assert not any(_clash(b, o) for o in rings[:j] + angles), where
        half = polar.LABEL_FRAME_PX / 2
        assert all(-half <= b[0] and b[2] <= half for b in angles), where
        odd = axis[0] < 0
        assert axis[2].index(0.0) in chosen if odd else len(axis[2]) - 1 in chosen, where
        steps = set(np.diff(chosen))
        assert len(steps) <= 1, where
        assert len(chosen) >= 2, f"{where}: a scale needs two labels"


def test_the_ring_labels_are_as_many_as_fit():
    """One ring more at the next smaller step would run into a label: the step is the
    smallest that fits (as laid out, with the gap, in the layout's own widths)."""
    for values, parity in AXES:
        axis = polar.radial_axis(values, parity)
        chosen = polar.labelled_rings(axis)
        step = int(chosen[1] - chosen[0]) if len(chosen) > 1 else len(axis[2])
        if step == 1:
            continue
        first = axis[2].index(0.0) if axis[0] < 0 else len(axis[2]) - 1
        denser = [i for i in range(len(axis[2])) if (first - i) % (step - 1) == 0]
        texts, angles = polar.label_boxes(axis, denser)
        boxes = texts + angles
        assert any(_clash(boxes[j], o) for j in range(len(denser)) for o in boxes[:j]
                   + boxes[len(denser):]), f"{axis[2]}: step {step - 1} would fit"
