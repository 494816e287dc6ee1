"""The plots of the Array, Orientation (polar), Regime map and Load tabs in words, for
screen readers (``app.views.access.LiveDescription``), written from the computed results.

One function per tab, each a short paragraph: what is drawn, the values that matter now
(the extremes of the curves and where they lie, the value at the current controls) and
what they mean. No number is fixed per preset; every one is read from the result passed
in. (The One support tab's words: ``app.motion_words.plots_description``.)

* ``array_description``: the array under the slab (Figs. 2a, 4), its settled friction
  F_T,x/(mu0 F_N) (Eq. 10) and N_c/N_c0;
* ``polar_description``: the fixed arrays against theta0 (Fig. 11a-c), their extremes and
  the values at the current theta0;
* ``map_description``: the uniform arrays over (k_r, k_theta) (Fig. 5a/5b), the extremes
  and the cell of the current springs;
* ``load_description``: the uniform arrays against F_N (Fig. 6) for the current springs
  and the paper's regimes.

The Design tab's figures: ``app.design_words``.
"""
from __future__ import annotations

import math
import re

import numpy as np

from .figures.arrays import AVERAGE_COLUMNS, map_column
from .motion_words import change_words
from .state import classify

#: Each map panel's quantity in words (Fig. 5a, 5b).
MAP_WORDS = {"5a": "friction F_T,x/(μ₀F_N)", "5b": "D_y/D_x, the sideways over the forward "
             "dissipation"}
#: The averages of a uniform array in words (the Advanced options' choice).
AVERAGE_WORDS = {"paper": "Eq. 10 average", "duration": "duration-weighted average"}


def minus(text: str) -> str:
    """Negative numbers with a minus sign (a screen reader says "minus", not "dash")."""
    return re.sub(r"-(?=[0-9.])", "−", text)


def small(x: float) -> str:
    """A number as said aloud: 3 digits, "nearly 0" below 0.001 (never "2.69e−05")."""
    return "nearly 0" if abs(x) < 1e-3 else f"{x:.3g}"


def _deg(radians) -> float:
    return math.degrees(float(radians))


def array_description(motion, orientation: str) -> str:
    """The Array tab's top view and live counts for ``motion`` (a
    ``model.arrays.array_motion.ArrayMotion``): the grid, the orientations and where the force
    on the slab settles (the array model's duration-weighted F_T,x/(mu0 F_N), Eq. 10)."""
    if motion is None:
        return "The array's plots are being computed."
    m = motion.model
    if orientation == "uniform":
        how = "θ₀ uniform (all directions)"
    else:
        how = f"every support at θ₀ = {_deg(motion.params.theta0):.0f}°"
    settled = float(m["FTx_over_mu0FN_duration"])
    return minus(
        f"Top view of {motion.n_supports} supports on a {motion.n_rows} × {motion.n_cols} "
        f"grid, {how}, k_r = {motion.params.k_r:.3g}, k_θ = {motion.params.k_theta:.3g}, "
        f"F_N = {motion.params.F_N:.3g}, under a slab sliding along +x; below it the live "
        f"count of supports in contact and the friction on the slab. Once settled, "
        f"F_T,x/(μ₀F_N) = {settled:.3g}, friction {change_words(settled)}, with "
        f"N_c/N_c0 = {float(m['Nc_over_Nc0']):.3g} supports in contact per rigid one "
        f"(β = {float(m['beta']):.3g}).")


def extreme(theta0_deg: np.ndarray, values: np.ndarray, pick) -> tuple[float, float]:
    """(value, theta0 in degrees) of the smallest or largest (``pick``) finite value."""
    finite = np.isfinite(values)
    i = int(np.flatnonzero(finite)[pick(values[finite])])
    return float(values[i]), float(theta0_deg[i])


def polar_description(sweep, support=None) -> str:
    """The Orientation tab's three polar diagrams for ``sweep`` (the fixed arrays of the
    current springs against theta0, Fig. 11a-c; theta0 in (0, 180°), mirrored), and the
    values at the current theta0 from ``support`` (a ``SupportData``) when it is there."""
    if sweep is None:
        return "The polar diagrams are being computed."
    cols, s = sweep.columns, sweep.settings
    theta = np.degrees(np.asarray(cols["theta0"], float))
    ftx = np.asarray(cols["FTx_over_mu0FN"], float)
    dydx = np.asarray(cols["Dy_over_Dx"], float)
    fty = np.asarray(cols["FTy_over_mu0FN"], float)
    if not (np.isfinite(ftx).any() and np.isfinite(dydx).any() and np.isfinite(fty).any()):
        return "The polar diagrams have no finished orientation to show."
    low, at_low = extreme(theta, ftx, np.argmin)
    high, at_high = extreme(theta, ftx, np.argmax)
    d_low, d_high = (small(float(np.nanmin(dydx))), small(float(np.nanmax(dydx))))
    side, at_side = extreme(theta, np.abs(fty), np.argmax)
    side = float(fty[np.flatnonzero(theta == at_side)[0]])
    towards = "+y" if side > 0 else "−y"
    text = (f"Polar diagrams (Fig. 11) of arrays whose supports all share one orientation "
            f"θ₀, for k_r = {s['k_r']:.3g}, k_θ = {s['k_theta']:.3g}, F_N = {s['F_N']:.3g}; "
            f"θ₀ and −θ₀ give the same friction and D_y/D_x. Friction F_T,x/(μ₀F_N) is "
            f"lowest, {low:.3g}, at θ₀ = {at_low:.0f}° and highest, {high:.3g}, at "
            f"θ₀ = {at_high:.0f}°. D_y/D_x goes from {d_low} to {d_high}. The "
            f"sideways force F_T,y/(μ₀F_N) is strongest at θ₀ = {at_side:.0f}°, "
            f"{side:.3g}, pushing the slab towards {towards} (the opposite at −θ₀).")
    fixed = getattr(support, "fixed", None)
    if fixed is not None:
        text += (f" At the current θ₀ = {_deg(support.params.theta0):.0f}°: "
                 f"F_T,x/(μ₀F_N) = {float(fixed.FTx_over_mu0FN):.3g}, "
                 f"D_y/D_x = {float(fixed.Dy_over_Dx):.3g}, "
                 f"F_T,y/(μ₀F_N) = {float(fixed.FTy_over_mu0FN):.3g}.")
    return minus(text)


def _nearest(axis: np.ndarray, k: float) -> int | None:
    """Index of the grid value nearest ``k`` on a log axis; None outside the grid's cells."""
    logs = np.log(np.asarray(axis, float))
    half = (logs[1] - logs[0]) / 2 if logs.size > 1 else 0.0
    x = math.log(k) if k > 0 else -math.inf
    if not logs[0] - half <= x <= logs[-1] + half:
        return None
    return int(np.argmin(np.abs(logs - x)))


def map_description(regime_map, quantity: str, average: str, k_r: float,
                    k_theta: float) -> str:
    """The Regime map tab's Fig. 5a (``quantity`` "5a": F_T,x/(mu0 F_N) with the chosen
    ``average``) or 5b (D_y/D_x) of uniform arrays over (k_r, k_theta): the map's range,
    its extremes and where they lie, and the value in the cell of the current springs."""
    if regime_map is None:
        return "The regime map is being computed."
    values = np.asarray(getattr(regime_map, map_column(quantity, average)), float)
    k_rs, k_thetas = np.asarray(regime_map.k_r, float), np.asarray(regime_map.k_theta, float)
    if not np.isfinite(values).any():
        return "The regime map has no finished cell to show."
    lo = np.unravel_index(np.nanargmin(values), values.shape)
    hi = np.unravel_index(np.nanargmax(values), values.shape)
    F_N = regime_map.metadata.get("F_N", 1.0)
    what = MAP_WORDS[quantity] + (f", {AVERAGE_WORDS[average]}" if quantity == "5a" else "")
    text = (f"Regime map (Fig. {quantity}) of arrays with uniformly spread orientations at "
            f"F_N = {F_N:g}: {what}, coloured over k_r from {k_rs[0]:.3g} to "
            f"{k_rs[-1]:.3g} and k_θ from {k_thetas[0]:.3g} to {k_thetas[-1]:.3g} (log "
            f"axes, {values.shape[0]} × {values.shape[1]} cells). Lowest "
            f"{values[lo]:.3g} at k_r = {k_rs[lo[0]]:.3g}, k_θ = {k_thetas[lo[1]]:.3g}; "
            f"highest {values[hi]:.3g} at k_r = {k_rs[hi[0]]:.3g}, "
            f"k_θ = {k_thetas[hi[1]]:.3g}.")
    i, j = _nearest(k_rs, k_r), _nearest(k_thetas, k_theta)
    here = f"The current springs, k_r = {k_r:.3g}, k_θ = {k_theta:.3g} ({classify(k_r, k_theta)} regime)"
    if i is None or j is None:
        text += f" {here}, lie outside the map."
    else:
        text += f" {here}, lie in a cell where it is {values[i, j]:.3g}."
    return minus(text)


def _curve_values(curve: dict, column: str) -> tuple[list, list]:
    points = sorted((float(F_N), float(row.get(column, math.nan)))
                    for F_N, row in curve.items())
    return [p[0] for p in points], [p[1] for p in points]


def load_description(curves: dict | None, F_N: float, average: str,
                     now: dict | None = None) -> str:
    """The Load tab's Fig. 6: uniform arrays' F_T,x/(mu0 F_N) (the chosen ``average``)
    against the normal load, for the current springs (``curves["current"]``) and the
    paper's regimes (the other curves); ``now``: the uniform array at the current F_N."""
    column = AVERAGE_COLUMNS[average]
    current = (curves or {}).get("current") or {}
    if not current:
        return "The load curves are being computed."
    loads, values = _curve_values(current, column)
    row = next(iter(current.values()))
    k_r, k_theta = float(row["k_r"]), float(row["k_theta"])
    finite = [(v, f) for f, v in zip(loads, values) if math.isfinite(v)]
    lowest, at = min(finite) if finite else (math.nan, math.nan)
    text = (f"Load curves (Fig. 6): friction F_T,x/(μ₀F_N) ({AVERAGE_WORDS[average]}) of "
            f"arrays with uniformly spread orientations against the normal load F_N, from "
            f"{loads[0]:.3g} to {loads[-1]:.3g} (log axis). For the current springs "
            f"(k_r = {k_r:.3g}, k_θ = {k_theta:.3g}, {classify(k_r, k_theta)} regime) it goes "
            f"from {values[0]:.3g} at F_N = {loads[0]:.3g} to {values[-1]:.3g} at "
            f"F_N = {loads[-1]:.3g}, lowest {lowest:.3g} at F_N = {at:.3g}.")
    if now and math.isfinite(now.get(column, math.nan)):
        text += f" At the current F_N = {F_N:.3g}: {now[column]:.3g}."
    regimes = {name: _curve_values(c, column) for name, c in (curves or {}).items()
               if name != "current" and c}
    if regimes:
        top = max(max(l) for l, _ in regimes.values())
        at_top = [f"{name} {v[l.index(top)]:.3g}" for name, (l, v) in regimes.items()
                  if top in l]
        text += f" The paper's regimes at F_N = {top:.3g}: {', '.join(at_top)}."
    return minus(text)
