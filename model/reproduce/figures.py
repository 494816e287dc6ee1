"""Every figure of the paper as (Bokeh figure, CSV columns, CSV header), drawn with the
same functions as the dashboard (``model.figures``)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from bokeh.layouts import row
from bokeh.models import GlyphRenderer

from .. import figures as F
from ..figures.arrays import AVERAGE_COLUMNS
from ..figures.histories import friction_law_data
from ..figures.polar import QUANTITIES as POLAR
from ..params import REGIMES
from .datasets import THETA_FIG10, Data, rows_of


@dataclass(frozen=True)
class FigureSpec:
    """One figure: ``key`` (e.g. ``"fig5a"``), the paper's number, a caption, and how to
    draw it and tabulate its data from the ``Data`` of a reproduction."""

    key: str
    number: str
    caption: str
    draw: Callable
    table: Callable  # Data -> (columns: dict, settings: dict)


def _titled(fig, title: str):
    fig.title.text = title
    return fig


def _drop_empty_legend_items(fig):
    """Remove legend entries whose glyphs have no data (e.g. the dashboard's 'current'
    markers, which a static figure does not have)."""
    for legend in fig.legend:
        legend.items = [item for item in legend.items
                        if any(isinstance(r, GlyphRenderer) and len(next(iter(
                            r.data_source.data.values()), [])) for r in item.renderers)]
    return fig


def _static(fig):
    """A figure without the dashboard's animation markers (current instant, current
    theta0): a static picture has no "now"."""
    for name, src in F.sources(fig).items():
        if name.endswith(("_now", "_spoke")):
            src.data = {k: [] for k in src.data}
    for name in ("forces_time",):
        if (span := F.annotation(fig, name)) is not None:
            span.visible = False
    return _drop_empty_legend_items(fig)


UNIFORM = {"beta": "self-consistent", "average": "paper (Eq. 10)", "F_N": 1.0}


def _series_table(data: Data, keys, names=("tau", "x", "y", "v_x", "v_y", "r", "F_x",
                                            "F_y", "F_abs")):
    cols = {"regime": [], "theta0": []}
    cols.update({n: [] for n in names})
    for regime, label in keys:
        s = data.supports[(regime, label)]
        n = len(s.series.tau)
        cols["regime"] += [regime] * n
        cols["theta0"] += [s.params.theta0] * n
        for name in names:
            cols[name] += list(getattr(s.series, name))
    settings = {"beta": 1.0, "F_N": 1.0, "rtol": 1e-8, "samples": data.resolution.samples,
                "note": "forces over f_N; positions and lengths in r0; time tau = t V0/r0"}
    return cols, settings


def _law_table(data):
    law = friction_law_data()["friction_law"]
    return {"v_over_V0": law["v"], "mu": law["mu"]}, {"mu_s": 1.3, "A": 1.44, "B": -20.0,
                                                      "zeta": 10.0}


def _map_table(data):
    m = data.regime_map
    i, j = np.meshgrid(np.arange(m.k_r.size), np.arange(m.k_theta.size), indexing="ij")
    cols = {"k_r": m.k_r[i.ravel()], "k_theta": m.k_theta[j.ravel()]}
    for name in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0",
                 "beta", "quadrature_error", "success", "n_failed", "n_pivot"):
        cols[name] = np.asarray(getattr(m, name))[i.ravel(), j.ravel()]
    return cols, {**UNIFORM, "tol": data.resolution.tol, "grid": f"{m.k_r.size} x log"}


def _load_curves(data, average="paper"):
    cols = data.load.columns
    return {r: {float(f): {c: float(rows_of(data.load, regime=r, F_N=f)[c][0])
                           for c in (AVERAGE_COLUMNS[average], "quadrature_error_FTx")}
                for f in np.unique(cols["F_N"])} for r in REGIMES}


def _polar(key: str):
    column, title, _ = POLAR[key]
    key_ = title.split("Fig. ")[1].rstrip(")")

    def draw(data):
        figs = []
        for regime in ("pendulum", "slider"):
            t = data.orientation[regime].columns
            p = REGIMES[regime]
            fig = _static(F.polar_figure(key, t["theta0"], t[column], width=380, height=400))
            figs.append(_titled(fig, f"{title.split(' (')[0]}: {regime} "
                                     f"(k_r = {p.k_r:g}, k_θ = {p.k_theta:g}), Fig. {key_}"))
        return row(*figs)

    def table(data):
        cols = {"regime": [], "theta0": [], column: [], "beta": [], "relative_residual": [],
                "success": []}
        for regime in ("pendulum", "slider"):
            t = data.orientation[regime].columns
            for name in cols:
                cols[name] += [regime] * len(t["theta0"]) if name == "regime" else list(t[name])
        return cols, {"beta": "self-consistent", "F_N": 1.0,
                      "rtol": data.orientation["pendulum"].settings["rtol"],
                      "note": "theta0 in (0, pi); the other half follows by mirror symmetry"}
    return draw, table


def _components(key: str, regime: str, pair):
    keys = [(regime, label) for label in THETA_FIG10]

    def draw(data):
        curves = {label: data.supports[(regime, label)].series for _, label in keys}
        p = REGIMES[regime]
        what = "Positions" if pair[0] == "x" else "Velocities"
        return F.components_figure(curves, pair, f"{what}, {regime} (k_r = {p.k_r:g}, "
                                   f"k_θ = {p.k_theta:g}), F_N = 1 (Fig. {key[3:]})")
    return draw, lambda data: _series_table(data, keys, ("tau", *pair))


def _radius(data):
    keys = [(r, label) for r in ("slider", "pendulum") for label in THETA_FIG10]
    return F.radius_figure({k: data.supports[k].series for k in keys})


def _rms_table(data):
    cols = {"regime": [], "theta0": [], "dtheta_rms": [], "dr_rms": []}
    for regime in ("pendulum", "slider"):
        t = data.orientation[regime].columns
        for name in cols:
            cols[name] += [regime] * len(t["theta0"]) if name == "regime" else list(t[name])
    return cols, {"beta": "self-consistent", "F_N": 1.0}


def _specs() -> list:
    p7 = [("pendulum", "θ₀ = π/2")], [("soft", "θ₀ = π/2")]
    specs = [
        FigureSpec("fig3", "3", "Friction law μ(v), μ_s = 1.3, A = 1.44, B = −20",
                   lambda d: _drop_empty_legend_items(F.friction_law_figure(width=560,
                                                                            height=380)),
                   _law_table),
        FigureSpec("fig5a", "5a", "Uniform arrays: F_T,x/(μ₀F_N) over (k_r, k_θ), F_N = 1",
                   lambda d: F.regime_map_figure(d.regime_map, "5a"), _map_table),
        FigureSpec("fig5b", "5b", "Uniform arrays: D_y/D_x over (k_r, k_θ), F_N = 1",
                   lambda d: F.regime_map_figure(d.regime_map, "5b"), _map_table),
        FigureSpec("fig6", "6", "Uniform arrays: F_T,x/(μ₀F_N) against F_N, four regimes",
                   lambda d: _drop_empty_legend_items(F.load_figure(_load_curves(d))),
                   lambda d: (d.load.columns, {**UNIFORM, **d.load.settings})),
    ]
    for key, regime, pairs in (("fig7a", "pendulum", p7[0]), ("fig7b", "soft", p7[1])):
        p = REGIMES[regime]
        specs.append(FigureSpec(
            key, key[3:], f"Friction on one support, {regime}, θ₀ = π/2, F_N = 1",
            lambda d, r=regime, p=p, key=key: _titled(_static(F.forces_figure(
                d.supports[(r, "θ₀ = π/2")].series, p, width=560, height=400)),
                f"Friction during contact, {r} (k_r = {p.k_r:g}, k_θ = {p.k_theta:g}), "
                f"θ₀ = π/2, F_N = 1 (Fig. {key[3:]})"),
            lambda d, keys=pairs: _series_table(d, keys, ("tau", "F_x", "F_y", "F_abs"))))
    specs += [
        FigureSpec("fig8a", "8a", "Uniform arrays: N_c/N_c0 against k_r, several k_θ",
                   lambda d: F.contact_count_figure(d.stiffness.columns),
                   lambda d: (d.stiffness.columns, {**UNIFORM, **d.stiffness.settings})),
        FigureSpec("fig8b", "8b", "Uniform arrays: split of the slab work against k_r, "
                   "k_θ = 0.03", lambda d: F.work_split_figure(d.stiffness.columns, 0.03),
                   lambda d: (rows_of(d.stiffness, k_theta=0.03),
                              {**UNIFORM, **d.stiffness.settings})),
    ]
    for key, regime, pair in (("fig10a", "slider", ("x", "y")),
                              ("fig10b", "slider", ("v_x", "v_y")),
                              ("fig10c", "pendulum", ("x", "y")),
                              ("fig10d", "pendulum", ("v_x", "v_y"))):
        draw, table = _components(key, regime, pair)
        specs.append(FigureSpec(key, key[3:], f"{regime}: {pair[0]}, {pair[1]} against τ for "
                                "θ₀ = π/4, π/2, 3π/4", draw, table))
    specs += [
        FigureSpec("fig10e", "10e", "Support length r̃ against τ, slider and pendulum", _radius,
                   lambda d: _series_table(d, [(r, lb) for r in ("slider", "pendulum")
                                               for lb in THETA_FIG10], ("tau", "r"))),
        FigureSpec("fig10f", "10f", "Δθ_rms and Δr̃_rms against θ₀, slider and pendulum",
                   lambda d: F.rms_figure({r: d.orientation[r].columns
                                           for r in ("slider", "pendulum")}), _rms_table),
    ]
    for key, q in (("fig11a", "FTx"), ("fig11b", "DyDx"), ("fig11c", "FTy")):
        draw, table = _polar(q)
        specs.append(FigureSpec(key, key[3:], f"Fixed arrays: {POLAR[q][1].split(' (')[0]}, "
                                "pendulum and slider (polar)", draw, table))
    return specs


FIGURES = _specs()
