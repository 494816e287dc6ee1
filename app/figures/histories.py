"""One support's friction during a contact (Fig. 7), the friction law (Fig. 3) and the
split of the slab work (Eq. 12, Fig. 8b style).

Each ``*_figure`` draws its figure from plain data; each ``*_data`` gives the sources for
new data, and ``*_now`` the marker of the animation instant.
"""
from __future__ import annotations

import numpy as np
from bokeh.models import FactorRange, Label, Range1d, Span

from model.contact.friction import mu, mu0

from .common import (BLACK, BLUE, GREEN, GREY, PURPLE, VERMILION, animated, legend_below,
                     legend_stand_ins, new_figure, source)

ENERGY_TERMS = ("D_x", "D_y", "U_el", "K")
ENERGY_COLORS = (BLUE, VERMILION, GREEN, PURPLE)
ENERGY_LABELS = ("D_x (along x)", "D_y (transverse)", "U_el (stored)", "K (kinetic)")
V_MAX = 2.0
#: Room on Fig. 3's speed axis below |v_R| = 0 for the whole moving marker, in V_MAX.
MARKER_ROOM = 0.03


def _index(series, i):
    return int(min(max(i, 0), len(series.tau) - 1))


def force_data(series) -> dict:
    """Fig. 7 sources: F_f,x/f_N, F_f,y/f_N, |F_f|/f_N against tau."""
    if series is None:
        return {"forces": {k: [] for k in ("tau", "F_x", "F_y", "F_abs")}}
    return {"forces": {"tau": series.tau, "F_x": series.F_x, "F_y": series.F_y,
                       "F_abs": series.F_abs}}


def force_x_range(series) -> tuple[float, float]:
    """Fig. 7's tau axis: the contact, with a margin."""
    tau_out = 10.0 if series is None or len(series.tau) == 0 else float(series.tau[-1])
    return -0.02 * tau_out, 1.02 * tau_out


def force_y_range(series, m0: float) -> tuple[float, float]:
    """Fig. 7's force axis: every curve and mu0, with a margin."""
    if series is None or len(series.tau) == 0:
        lo, hi = 0.0, max(1.0, m0)
    else:
        lo = min(0.0, float(np.nanmin(series.F_x)), float(np.nanmin(series.F_y)))
        hi = max(float(np.nanmax(series.F_abs)), m0)
    pad = 0.06 * (hi - lo or 1.0)
    return lo - pad, hi + pad


def force_now(series, i: int) -> dict:
    if series is None or len(series.tau) == 0:
        return {"forces_now": {"tau": [], "F": []}}
    i = _index(series, i)
    return {"forces_now": {"tau": [series.tau[i]] * 3,
                           "F": [series.F_x[i], series.F_y[i], series.F_abs[i]]}}


def forces_figure(series, params=None, frame: int = 0, width: int = 340, height: int = 330):
    """Fig. 7: friction on the support over f_N during the contact, mu0 marked."""
    m0 = mu0(params)
    fig = new_figure("forces", "Friction during contact (Fig. 7)", width, height,
                     x_axis_label="τ", y_axis_label="F_f / f_N",
                     x_range=Range1d(*force_x_range(series)),
                     y_range=Range1d(*force_y_range(series, m0)))
    src = source("forces", force_data(series)["forces"])
    fig.line("tau", "F_abs", source=src, line_color=BLACK, line_width=2, legend_label="|F_f|")
    fig.line("tau", "F_x", source=src, line_color=BLUE, line_width=2, legend_label="F_f,x")
    fig.line("tau", "F_y", source=src, line_color=VERMILION, line_width=2,
             legend_label="F_f,y")  # over f_N, as the axis says: fits a projected plot
    now = source("forces_now", force_now(series, frame)["forces_now"])
    marker = fig.scatter("tau", "F", source=now, size=8, fill_color="white", line_color=BLACK)
    fig.add_layout(Span(location=m0, dimension="width", line_color=GREEN, line_dash="dashed",
                        line_width=2, name="forces_mu0"))
    time_line = Span(location=float(now.data["tau"][0]) if now.data["tau"] else 0.0,
                     dimension="height", line_color=GREY, line_width=1.5, name="forces_time")
    fig.add_layout(time_line)
    animated(marker, time_line)
    # At the right end, above its line: the contact's early peaks are at the left, and at
    # the end the curves lie along mu0. (Who sets a new range sets its x too: the support
    # view, the offline page's support.js.)
    fig.add_layout(Label(x=fig.x_range.end, y=m0, text=f"μ₀ = {m0:.4f}",
                         name="forces_mu0_label", text_color=GREEN, text_font_size="12px",
                         text_align="right", text_baseline="bottom", x_offset=-6, y_offset=3))
    legend_below(fig)
    return fig




def friction_law_data(params=None, v_max: float = V_MAX) -> dict:
    v = np.linspace(0.0, v_max, 301)
    return {"friction_law": {"v": v, "mu": mu(v, params)}}


def friction_now(series, i: int, params=None) -> dict:
    """The relative speed |v_R| at frame ``i`` on the friction law."""
    if series is None or len(series.tau) == 0:
        return {"friction_now": {"v": [], "mu": []}}
    i = _index(series, i)
    v = float(np.hypot(series.v_x[i] - 1.0, series.v_y[i]))
    return {"friction_now": {"v": [v], "mu": [float(mu(v, params))]}}


def friction_law_figure(series=None, params=None, frame: int = 0, width: int = 340,
                        height: int = 230, marker_room: bool = True):
    """Fig. 3: mu(|v_R|) (|v_R| in V0 = 10 V_s), mu0 = mu(1) and the current |v_R|.

    ``marker_room``: the |v_R| axis starts a little below 0, so the moving marker, which is
    not clipped to the plot (``animated``), stays whole inside it while the support sticks."""
    law_data = friction_law_data(params)["friction_law"]
    # Fixed ranges: the marker moves every frame, and a data range would be recomputed
    # (and, in a served page, sent to the server) each time.
    top = 1.08 * float(np.nanmax(law_data["mu"]))
    fig = new_figure("friction_law", "Friction law μ(v) (Fig. 3)", width, height,
                     x_axis_label="|v_R| / V₀  (= v / 10 V_s)", y_axis_label="μ",
                     x_range=Range1d(-MARKER_ROOM * V_MAX if marker_room else 0.0, V_MAX),
                     y_range=Range1d(-0.04 * top, top))
    law = source("friction_law", law_data)
    fig.line("v", "mu", source=law, line_color=BLACK, line_width=2)
    m0 = mu0(params)
    fig.scatter([1.0], [m0], size=8, marker="square", color=GREEN, legend_label="μ₀ = μ(1)")
    now = source("friction_now", friction_now(series, frame, params)["friction_now"])
    marker = fig.scatter("v", "mu", source=now, size=12, fill_color=VERMILION, line_color=BLACK,
                         legend_label="current |v_R|")
    fig.legend.location = "bottom_right"
    fig.legend.label_text_font_size = "10px"
    fig.legend.padding = 2
    fig.legend.spacing = 0
    animated(marker)
    legend_stand_ins(fig)
    return fig


def energy_data(fractions: dict) -> dict:
    """Eq. (12) split of the slab work, W = D_x + D_y + U_el + K, as fractions of W."""
    values = [float(fractions.get(k, np.nan)) for k in ENERGY_TERMS]
    return {"energy": {"term": list(ENERGY_TERMS), "fraction": values,
                       "label": [f"{v:.1%}" if np.isfinite(v) else "–" for v in values],
                       "color": list(ENERGY_COLORS), "meaning": list(ENERGY_LABELS)}}


def energy_figure(fractions: dict, width: int = 300, height: int = 230):
    """Where the slab's work goes in one contact (Eq. 12; Fig. 8b shows it against k_r)."""
    fig = new_figure("energy", "Slab work W split (Eq. 12)", width, height,
                     x_range=FactorRange(*ENERGY_TERMS), y_range=Range1d(0, 1.12),
                     y_axis_label="fraction of W",
                     tooltips=[("term", "@meaning"), ("fraction of W", "@label")])
    src = source("energy", energy_data(fractions)["energy"])
    fig.vbar(x="term", top="fraction", width=0.7, source=src, fill_color="color",
             line_color=BLACK)
    fig.text(x="term", y="fraction", text="label", source=src, text_align="center",
             text_baseline="bottom", text_font_size="11px", y_offset=-2)
    fig.xgrid.visible = False
    fig.add_layout(Span(location=1.0, dimension="width", line_color=GREY, line_dash="dotted"))
    return fig

