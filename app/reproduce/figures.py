"""Every figure of the paper drawn from the ``Data`` of a reproduction, with the same
functions as the dashboard (``app.figures``): ``DRAW`` maps a figure's key (those of
``model.reproduce.tables.FIGURES``) to a function ``Data -> Bokeh model``."""
from __future__ import annotations

import numpy as np
from bokeh.layouts import row
from bokeh.models import GlyphRenderer

from model.contact.params import REGIMES
from model.reproduce.datasets import THETA_FIG10, rows_of
from model.reproduce.tables import POLAR_COLUMNS

from .. import figures as F
from ..figures.arrays import AVERAGE_COLUMNS
from ..figures.polar import QUANTITIES as POLAR


def _titled(fig, title: str):
    fig.title.text = title
    return fig


def _drop_empty_legend_items(fig):
    """Remove legend entries whose glyphs have no data (e.g. the dashboard's 'current'
    markers, which a static figure does not have: their legend names a stand-in with
    NaN data, ``app.figures.common.stand_in``)."""
    def drawn(r):
        if not isinstance(r, GlyphRenderer):
            return False
        for column in r.data_source.data.values():
            try:
                if np.isfinite(np.asarray(column, dtype=float)).any():
                    return True
            except (TypeError, ValueError):  # text
                continue
        return False
    for legend in fig.legend:
        legend.items = [item for item in legend.items if any(drawn(r) for r in item.renderers)]
    return fig


def _static(fig):
    """A figure without the dashboard's animation markers (current instant, current
    theta0): a static picture has no "now"."""
    for name, src in F.sources(fig).items():
        if name.endswith(("_now", "_spoke")):
            src.data = {k: [] for k in src.data}
    if (span := F.annotation(fig, "forces_time")) is not None:
        span.visible = False
    return _drop_empty_legend_items(fig)


def _springs(regime: str) -> str:
    p = REGIMES[regime]
    return f"{regime} (k_r = {p.k_r:g}, k_θ = {p.k_theta:g})"


def _load_curves(data, average="paper"):
    return {r: {float(f): {c: float(rows_of(data.load, regime=r, F_N=f)[c][0])
                           for c in (AVERAGE_COLUMNS[average], "quadrature_error_FTx")}
                for f in np.unique(data.load.columns["F_N"])} for r in REGIMES}


def _forces(key: str, regime: str):
    return lambda d: _titled(_static(F.forces_figure(
        d.supports[(regime, "θ₀ = π/2")].series, REGIMES[regime], width=560, height=400)),
        f"Friction during contact, {_springs(regime)}, θ₀ = π/2, F_N = 1 (Fig. {key[3:]})")


def _components(key: str, regime: str, pair):
    what = "Positions" if pair[0] == "x" else "Velocities"

    def draw(d):
        curves = {label: d.supports[(regime, label)].series for label in THETA_FIG10}
        return F.components_figure(curves, pair, f"{what}, {_springs(regime)}, F_N = 1 "
                                   f"(Fig. {key[3:]})")
    return draw


def _polar(number: str):
    key = next(k for k, v in POLAR.items() if v[0] == POLAR_COLUMNS[number])

    def draw(d):
        figs = []
        for regime in ("pendulum", "slider"):
            t = d.orientation[regime].columns
            fig = _static(F.polar_figure(key, t["theta0"], t[POLAR_COLUMNS[number]],
                                         width=380, height=400))
            figs.append(_titled(fig, f"{POLAR[key][1].split(' (')[0]}: {_springs(regime)}, "
                                     f"Fig. {number}"))
        return row(*figs)
    return draw


DRAW = {
    "fig3": lambda d: _drop_empty_legend_items(
        F.friction_law_figure(width=560, height=380, marker_room=False)),
    "fig5a": lambda d: F.regime_map_figure(d.regime_map, "5a"),
    "fig5b": lambda d: F.regime_map_figure(d.regime_map, "5b"),
    "fig6": lambda d: _drop_empty_legend_items(F.load_figure(_load_curves(d))),
    "fig7a": _forces("fig7a", "pendulum"),
    "fig7b": _forces("fig7b", "soft"),
    "fig8a": lambda d: F.contact_count_figure(d.stiffness.columns),
    "fig8b": lambda d: F.work_split_figure(d.stiffness.columns, 0.03),
    "fig10a": _components("fig10a", "slider", ("x", "y")),
    "fig10b": _components("fig10b", "slider", ("v_x", "v_y")),
    "fig10c": _components("fig10c", "pendulum", ("x", "y")),
    "fig10d": _components("fig10d", "pendulum", ("v_x", "v_y")),
    "fig10e": lambda d: F.radius_figure({(r, lb): d.supports[(r, lb)].series
                                         for r in ("slider", "pendulum") for lb in THETA_FIG10}),
    "fig10f": lambda d: F.rms_figure({r: d.orientation[r].columns for r in ("slider", "pendulum")}),
    "fig11a": _polar("11a"),
    "fig11b": _polar("11b"),
    "fig11c": _polar("11c"),
}
