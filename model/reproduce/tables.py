"""Every figure of the paper as a table: its key, number, caption and data (columns and the
settings for the CSV header). Drawing is left to the caller (``app/reproduce`` draws them
with the dashboard's figure functions), so this package needs no plotting library."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..arrays.quantities import MAP_FIGURES, POLAR_FIGURES, label
from ..contact.friction import mu
from ..contact.params import DEFAULTS
from .datasets import THETA_FIG10, Data, rows_of

UNIFORM = {"beta": "self-consistent", "average": "paper (Eq. 10)", "F_N": 1.0}
SERIES = ("tau", "x", "y", "v_x", "v_y", "r", "F_x", "F_y", "F_abs")
#: Fig. 11 panel -> the orientation-table column it shows.
POLAR_COLUMNS = POLAR_FIGURES
#: Columns of the regime map (Fig. 5) in its table.
MAP_COLUMNS = ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0", "beta",
               "quadrature_error", "success", "n_failed", "n_pivot")


@dataclass(frozen=True)
class FigureSpec:
    """One figure: ``key`` (e.g. ``"fig5a"``), the paper's number, a caption, and how to
    tabulate its data from the ``Data`` of a reproduction."""

    key: str
    number: str
    caption: str
    table: Callable  # Data -> (columns: dict, settings: dict)


def series_table(data: Data, keys, names=SERIES):
    """Time histories of the single supports ``keys`` ((regime, theta0 label) pairs)."""
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
    v = np.linspace(0.0, 2.0, 301)
    return {"v_over_V0": v, "mu": mu(v)}, {k: DEFAULTS[k] for k in ("mu_s", "A", "B", "zeta")}


def _map_table(data):
    m = data.regime_map
    i, j = np.meshgrid(np.arange(m.k_r.size), np.arange(m.k_theta.size), indexing="ij")
    cols = {"k_r": m.k_r[i.ravel()], "k_theta": m.k_theta[j.ravel()]}
    for name in MAP_COLUMNS:
        cols[name] = np.asarray(getattr(m, name))[i.ravel(), j.ravel()]
    return cols, {**UNIFORM, "tol": data.resolution.tol, "grid": f"{m.k_r.size} x log"}


def _orientation_table(data, names):
    cols = {"regime": [], "theta0": [], **{n: [] for n in names}}
    for regime in ("pendulum", "slider"):
        t = data.orientation[regime].columns
        for name in cols:
            cols[name] += [regime] * len(t["theta0"]) if name == "regime" else list(t[name])
    return cols, {"beta": "self-consistent", "F_N": 1.0,
                  "rtol": data.orientation["pendulum"].settings["rtol"],
                  "note": "theta0 in (0, pi); the other half follows by mirror symmetry"}


def _specs() -> list:
    fig7 = {"fig7a": "pendulum", "fig7b": "soft"}
    fig10 = {"fig10a": ("slider", ("x", "y")), "fig10b": ("slider", ("v_x", "v_y")),
             "fig10c": ("pendulum", ("x", "y")), "fig10d": ("pendulum", ("v_x", "v_y"))}
    specs = [
        FigureSpec("fig3", "3", "Friction law μ(v), μ_s = 1.3, A = 1.44, B = −20", _law_table),
    ]
    specs += [FigureSpec(f"fig{n}", n, f"Uniform arrays: {label(q)} over (k_r, k_θ), F_N = 1",
                         _map_table) for n, q in MAP_FIGURES.items()]
    specs += [
        FigureSpec("fig6", "6", f"Uniform arrays: {label('FTx_over_mu0FN')} against F_N, "
                   "four regimes",
                   lambda d: (d.load.columns, {**UNIFORM, **d.load.settings})),
    ]
    specs += [FigureSpec(key, key[3:], f"Friction on one support, {r}, θ₀ = π/2, F_N = 1",
                         lambda d, r=r: series_table(d, [(r, "θ₀ = π/2")],
                                                     ("tau", "F_x", "F_y", "F_abs")))
              for key, r in fig7.items()]
    specs += [
        FigureSpec("fig8a", "8a",
                   f"Uniform arrays: {label('Nc_over_Nc0')} against k_r, several k_θ",
                   lambda d: (d.stiffness.columns, {**UNIFORM, **d.stiffness.settings})),
        FigureSpec("fig8b", "8b", "Uniform arrays: split of the slab work against k_r, "
                   "k_θ = 0.03", lambda d: (rows_of(d.stiffness, k_theta=0.03),
                                            {**UNIFORM, **d.stiffness.settings})),
    ]
    specs += [FigureSpec(key, key[3:], f"{r}: {p[0]}, {p[1]} against τ for θ₀ = π/4, π/2, "
                         "3π/4", lambda d, r=r, p=p: series_table(
                             d, [(r, lb) for lb in THETA_FIG10], ("tau", *p)))
              for key, (r, p) in fig10.items()]
    specs += [
        FigureSpec("fig10e", "10e", f"Support length {label('r')} against τ, slider and pendulum",
                   lambda d: series_table(d, [(r, lb) for r in ("slider", "pendulum")
                                              for lb in THETA_FIG10], ("tau", "r"))),
        FigureSpec("fig10f", "10f",
                   f"{label('dtheta_rms')} and {label('dr_rms')} against θ₀, slider and pendulum",
                   lambda d: _orientation_table(d, ("dtheta_rms", "dr_rms"))),
    ]
    specs += [FigureSpec(f"fig{n}", n, f"Fixed arrays: {label(c)} vs θ₀, pendulum and slider "
                         "(polar)", lambda d, c=c: _orientation_table(
                             d, (c, "beta", "relative_residual", "success")))
              for n, c in POLAR_COLUMNS.items()]
    return specs


FIGURES = _specs()
