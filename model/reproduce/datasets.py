"""The computations behind the paper's figures, at a chosen resolution.

Every uniform-array point goes through the sweeps of ``model.runs.sweeps`` and so through the
on-disk cache: a second reproduction at the same resolution reads its points back.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..arrays.uniform import uniform_array
from ..contact.params import REGIMES, Params
from ..contact.support import simulate_support
from ..runs.shipped_map import RegimeMap, _from_sweep, grid
from ..runs.sweeps import SweepResult, load_sweep, orientation_table, regime_map, stiffness_sweep

#: theta0 of the single supports of Fig. 10a-e (the paper's three orientations).
THETA_FIG10 = {"θ₀ = π/4": math.pi / 4, "θ₀ = π/2": math.pi / 2, "θ₀ = 3π/4": 3 * math.pi / 4}
#: Springs where the paper quotes U_el/W ~ 0.7 (small k_r, k_theta = 0.03; Fig. 8b).
SOFT_SMALL = Params(0.01, 0.03)


@dataclass(frozen=True)
class Resolution:
    """How finely each figure is computed (``RESOLUTIONS`` holds the two presets)."""

    name: str
    map_n: int  # Fig. 5: grid points per stiffness axis
    load_n: int  # Fig. 6: loads on [0.1, 10]
    stiffness_n: int  # Fig. 8: k_r values on [0.01, 3]
    k_theta: tuple  # Fig. 8a: one curve per k_theta (0.03 is Fig. 8b's)
    theta_n: int  # Figs. 10f, 11: orientations on [0, pi]
    samples: int  # Figs. 7, 10: samples of each time history
    tol: float  # quadrature tolerance of every uniform array
    mc_draws: int  # sensitivity: repetitions of the paper's 200 random supports


RESOLUTIONS = {
    "full": Resolution("full", 24, 9, 12, (0.01, 0.03, 0.1, 0.3, 1.0, 3.0), 72, 1500, 1e-3, 20),
    "coarse": Resolution("coarse", 3, 3, 4, (0.03, 3.0), 12, 300, 1e-2, 2),
}


@dataclass
class Data:
    """Model results behind every figure (see ``compute``)."""

    resolution: Resolution
    supports: dict  # (regime, theta0 label) -> SupportResult with a time series
    orientation: dict  # regime -> SweepResult of orientation_table (Figs. 10f, 11)
    regime_map: RegimeMap  # Fig. 5
    load: SweepResult  # Fig. 6
    stiffness: SweepResult  # Fig. 8
    headline: dict  # regime (and "soft, k_r = 0.01") -> UniformArrayResult at F_N = 1
    seconds: dict = field(default_factory=dict)  # stage -> wall time


def _support(regime: str, theta0: float, samples: int):
    return simulate_support(REGIMES[regime].replace(theta0=theta0), rtol=1e-8,
                            samples=samples).check()


def stages(res: Resolution) -> list:
    """(name, number of points) of each computing stage, for progress reports."""
    return [("single supports (Figs. 7, 10a-e)", 8), ("fixed arrays (Figs. 10f, 11)", 2),
            ("regime map (Fig. 5)", res.map_n ** 2), ("load sweep (Fig. 6)", 4 * res.load_n),
            ("stiffness sweep (Fig. 8)", res.stiffness_n * len(res.k_theta)),
            ("headline arrays", 5)]


def compute(res: Resolution, workers: int = 1, progress=None) -> Data:
    """Run every computation; ``progress(stage, done, total)`` after each point."""
    report = progress or (lambda stage, done, total: None)
    names = [name for name, _ in stages(res)]
    seconds = {}

    def timed(i, fn):
        start = time.perf_counter()
        out = fn(lambda done, total: report(names[i], done, total))
        seconds[names[i]] = time.perf_counter() - start
        return out

    def supports(tick):
        pairs = [("pendulum", "θ₀ = π/2"), ("soft", "θ₀ = π/2")]
        pairs += [(r, label) for r in ("slider", "pendulum") for label in THETA_FIG10
                  if (r, label) not in pairs]
        out = {}
        for i, (regime, label) in enumerate(pairs):
            out[(regime, label)] = _support(regime, THETA_FIG10[label], res.samples)
            tick(i + 1, len(pairs))
        return out

    def orientation(tick):
        out = {}
        for i, regime in enumerate(("pendulum", "slider")):
            out[regime] = orientation_table(regime, n=res.theta_n)
            tick(i + 1, 2)
        return out

    k_map = grid(res.map_n)
    k_r8 = grid(res.stiffness_n)
    sweep_args = dict(tol=res.tol, workers=workers)
    data = Data(
        resolution=res, supports=timed(0, supports), orientation=timed(1, orientation),
        regime_map=timed(2, lambda t: _from_sweep(k_map, regime_map(
            k_r=k_map, k_theta=k_map, progress=t, **sweep_args))),
        load=timed(3, lambda t: load_sweep(n=res.load_n, progress=t, **sweep_args)),
        stiffness=timed(4, lambda t: stiffness_sweep(k_r=k_r8, k_theta=res.k_theta,
                                                     progress=t, **sweep_args)),
        headline=timed(5, lambda t: _headline(res.tol, t)), seconds=seconds)
    return data


def _headline(tol: float, tick) -> dict:
    """Uniform arrays of the four regimes (and the small-k_r soft springs) at F_N = 1,
    with every quadrature error estimate."""
    out = {}
    cases = {**{r: REGIMES[r] for r in REGIMES}, "soft, k_r = 0.01": SOFT_SMALL}
    for i, (name, params) in enumerate(cases.items()):
        out[name] = uniform_array(params, tol=tol)
        tick(i + 1, len(cases))
    return out


def rows_of(sweep: SweepResult, **where) -> dict:
    """The columns of ``sweep`` restricted to rows where each ``column == value``."""
    cols = sweep.columns
    keep = np.ones(len(sweep), bool)
    for name, value in where.items():
        column = np.asarray(cols[name])
        keep &= np.isclose(column, value) if column.dtype.kind == "f" else column == value
    return {k: np.asarray(v)[keep] for k, v in cols.items()}
