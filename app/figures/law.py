"""The Design tab's friction law, Eq. (4) (Fig. 3 in physical units): mu against the
sliding speed v in m/s on a log axis, the law in use, the 95 % band of a fit
(``model.FrictionFit.band``), the measured points it was fitted to (with their ``mu_err``
as error bars) and the design's sliding speed V0.

``law_data`` gives the sources and the axes' extents for new data; ``law_figure`` draws
an empty figure whose named sources a view fills (``common.update``).
"""
from __future__ import annotations

import numpy as np
from bokeh.models import Range1d

from model.contact.params import DEFAULTS

from .common import BLACK, BLUE, GREY, MIN_TEXT_PX, VERMILION, new_figure, source

#: Points of the drawn curves, log-spaced over the axis.
N_SPEEDS = 200
#: The speeds shown around V_s when nothing else is known (a factor either side).
AROUND_V_S = 100.0
EMPTY = {"law": {"v": [], "mu": []}, "law_band": {"v": [], "lo": [], "hi": []},
         "law_measured": {"v": [], "mu": [], "lo": [], "hi": []},
         "law_V0": {"v": [], "mu": []}}


def _speed_axis(law, curve, V0) -> tuple[float, float]:
    """The log axis's ends (m/s): V_s's decades either side, the measured speeds and V0."""
    V_s = law.V_s if law is not None and law.V_s is not None else (
        None if V0 is None else V0 / DEFAULTS["zeta"])
    ends = [] if V_s is None else [V_s / AROUND_V_S, V_s * AROUND_V_S]
    if curve is not None and np.any(curve.v > 0):
        ends += [float(curve.v[curve.v > 0].min()), float(curve.v.max())]
    if V0 is not None:
        ends.append(V0)
    if not ends:
        return 1e-6, 1.0
    return min(ends) / 2, max(ends) * 2


def law_data(law, fit=None, curve=None, V0: float | None = None):
    """``(data, (v_lo, v_hi), (mu_lo, mu_hi))``: the sources of ``law_figure`` and its axes
    for the law in use ``law`` (a ``FrictionLaw``; None: unusable, not drawn), a fit
    ``fit`` of the measured ``curve`` (its band; the points drawn where v > 0) and the
    design's sliding speed ``V0`` (m/s; None: unknown)."""
    data = {k: dict(v) for k, v in EMPTY.items()}
    v_lo, v_hi = _speed_axis(law, curve, V0)
    v = np.geomspace(v_lo, v_hi, N_SPEEDS)
    tops = []
    if law is not None and (law.V_s is not None or V0 is not None):
        mu = law.mu(v, V0)
        data["law"] = {"v": v, "mu": mu}
        tops.append(float(np.max(mu)))
        if V0 is not None:
            data["law_V0"] = {"v": [V0], "mu": [float(law.mu(V0, V0))]}
    if curve is not None:
        shown = curve.v > 0
        err = np.zeros_like(curve.mu) if curve.mu_err is None else curve.mu_err
        data["law_measured"] = {"v": curve.v[shown], "mu": curve.mu[shown],
                                "lo": (curve.mu - err)[shown], "hi": (curve.mu + err)[shown]}
        tops.append(float(np.max(curve.mu + err)))
    top = 1.1 * max(tops) if tops and max(tops) > 0 else 1.5
    bottom = min([0.0] + ([float(np.min(curve.mu - err))] if curve is not None else []))
    bottom -= 0.04 * (top - bottom)
    if fit is not None and fit.success:
        lo, hi = fit.band(v)
        # An undetermined coefficient makes the band unbounded: drawn to the axis' ends.
        data["law_band"] = {"v": v, "lo": np.clip(np.nan_to_num(lo, nan=bottom), bottom, top),
                            "hi": np.clip(np.nan_to_num(hi, nan=top), bottom, top)}
    return data, (v_lo, v_hi), (bottom, top)


def law_figure(width: int = 310, height: int = 300):
    """Fig. 3 in physical units, empty: the law, a fit's band, measured points, V0."""
    fig = new_figure("design_law", "Friction law μ(v) (Eq. 4)", width, height,
                     x_axis_type="log", x_axis_label="sliding speed v [m/s]",
                     y_axis_label="friction coefficient μ", x_range=Range1d(1e-6, 1.0),
                     y_range=Range1d(-0.06, 1.5))
    band = source("law_band", EMPTY["law_band"])
    fig.varea(x="v", y1="lo", y2="hi", source=band, fill_color=BLUE, fill_alpha=0.25,
              legend_label="fit 95 % band")
    measured = source("law_measured", EMPTY["law_measured"])
    fig.segment(x0="v", y0="lo", x1="v", y1="hi", source=measured, line_color=GREY)
    fig.scatter("v", "mu", source=measured, size=5, fill_color="white", line_color=BLUE,
                legend_label="measured")
    fig.line("v", "mu", source=source("law", EMPTY["law"]), line_color=BLACK, line_width=2,
             legend_label="law")
    fig.scatter("v", "mu", source=source("law_V0", EMPTY["law_V0"]), size=10, marker="square",
                fill_color=VERMILION, line_color=BLACK, legend_label="μ at V₀")
    # Below the plot in two columns, where it hides no point of the curve; short labels,
    # so that the projector's larger text still fits the figure's width.
    legend = fig.legend[0]
    legend.update(ncols=2, location="center", label_text_font_size=f"{MIN_TEXT_PX}px",
                  padding=1, spacing=0, margin=2, glyph_width=14, label_standoff=2,
                  click_policy="hide")
    fig.center = [m for m in fig.center if m is not legend]
    fig.add_layout(legend, "below")
    return fig


def set_axes(fig, speeds, mus) -> None:
    """Set ``fig``'s ranges to ``law_data``'s extents."""
    fig.x_range.update(start=speeds[0], end=speeds[1])
    fig.y_range.update(start=mus[0], end=mus[1])
