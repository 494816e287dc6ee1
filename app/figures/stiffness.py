"""Uniform arrays against the radial stiffness: the contact count (Fig. 8a) and the split
of the slab work (Eq. 12, Fig. 8b).

Both take the rows of ``model.stiffness_sweep`` as plain columns (``k_theta``, ``k_r``,
``Nc_over_Nc0``, ``Dx_over_W``, ...), one curve per k_theta.
"""
from __future__ import annotations

import numpy as np
from bokeh.models import Range1d, Span
from bokeh.palettes import Viridis256

from .common import BLACK, GREY, new_figure, source
from .histories import ENERGY_COLORS, ENERGY_LABELS

#: Eq. (12) terms as columns of ``stiffness_sweep``.
SPLIT_COLUMNS = ("Dx_over_W", "Dy_over_W", "Uel_over_W", "K_over_W")


def _curves(columns: dict, value: str) -> dict:
    """One line per k_theta: ``xs`` (k_r), ``ys`` (``value``), label and colour."""
    kt_all = np.asarray(columns["k_theta"], float)
    k_theta = np.unique(kt_all)
    idx = np.linspace(0, 255, max(k_theta.size, 2)).astype(int)[:k_theta.size]
    xs, ys = [], []
    for kt in k_theta:
        rows = kt_all == kt
        order = np.argsort(np.asarray(columns["k_r"], float)[rows])
        xs.append(np.asarray(columns["k_r"], float)[rows][order])
        ys.append(np.asarray(columns[value], float)[rows][order])
    return {"xs": xs, "ys": ys, "k_theta": [f"k_θ = {kt:g}" for kt in k_theta],
            "color": [Viridis256[i] for i in idx]}


def contact_count_data(columns: dict) -> dict:
    """Fig. 8a sources: N_c/N_c0 against k_r, one line per k_theta."""
    return {"contact_count": _curves(columns, "Nc_over_Nc0")}


def contact_count_figure(columns: dict, width: int = 560, height: int = 420):
    """Fig. 8a: uniform-array N_c/N_c0 = <tau_out>/L0 against k_r (log axis), per k_theta."""
    fig = new_figure("contact_count", "Contact count N_c/N_c0 vs k_r, F_N = 1 (Fig. 8a)",
                     width, height, x_axis_type="log", x_range=Range1d(0.008, 3.8),
                     x_axis_label="k_r (radial stiffness)", y_axis_label="N_c / N_c0")
    src = source("contact_count", contact_count_data(columns)["contact_count"])
    fig.multi_line("xs", "ys", source=src, line_color="color", line_width=2,
                   legend_field="k_theta")
    fig.add_layout(Span(location=1.0, dimension="width", line_color=GREY, line_dash="dotted"))
    fig.legend.location = "top_right"
    fig.legend.label_text_font_size = "11px"
    return fig


def work_split_data(columns: dict, k_theta: float) -> dict:
    """Fig. 8b sources: D_x/W, D_y/W, U_el/W, K/W against k_r at one k_theta."""
    rows = np.isclose(np.asarray(columns["k_theta"], float), k_theta)
    k_r = np.asarray(columns["k_r"], float)[rows]
    order = np.argsort(k_r)
    data = {"k_r": k_r[order]}
    for name in SPLIT_COLUMNS:
        data[name] = np.asarray(columns[name], float)[rows][order]
    return {"work_split": data}


def work_split_figure(columns: dict, k_theta: float = 0.03, width: int = 560,
                      height: int = 420):
    """Fig. 8b: the split of the slab work W = D_x + D_y + U_el + K (Eq. 12) against k_r."""
    fig = new_figure("work_split", f"Slab work split vs k_r, k_θ = {k_theta:g}, F_N = 1 "
                     "(Fig. 8b)", width, height, x_axis_type="log",
                     x_range=Range1d(0.008, 3.8), y_range=Range1d(0, 1.05),
                     x_axis_label="k_r (radial stiffness)", y_axis_label="fraction of W")
    src = source("work_split", work_split_data(columns, k_theta)["work_split"])
    for name, color, label in zip(SPLIT_COLUMNS, ENERGY_COLORS, ENERGY_LABELS):
        fig.line("k_r", name, source=src, line_color=color, line_width=2, legend_label=label)
        fig.scatter("k_r", name, source=src, color=color, size=5, legend_label=label)
    fig.add_layout(Span(location=1.0, dimension="width", line_color=BLACK, line_dash="dotted"))
    fig.legend.location = "center_right"
    fig.legend.label_text_font_size = "11px"
    fig.legend.click_policy = "hide"
    return fig
