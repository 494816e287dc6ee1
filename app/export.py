"""CSV downloads: the current trajectory (Figs. 7, 10), the polar sweep (Fig. 11), the
regime map (Fig. 5), the load curves (Fig. 6) and the array under the slab (Figs. 2a, 4).

Both are written by the model's CSV writer (``model.csvfile``): ``# key: value`` lines
(parameters, settings, package version, what each column holds), a header row, the data.
With a pinned state A of a comparison (``app.compare``) the file carries A too: its
settings as ``# pinned <key>: value`` lines (not ``A``: the friction law has parameters
A and B) and its values as the same columns with ``_A`` appended, row by row beside B's
(the trajectories have the same number of samples, the sweeps the same theta0; a
shorter column is padded with NaN).
"""
from __future__ import annotations

import math

import numpy as np

from model import __version__, csvfile
from model.arrays.quantities import TABLES, value_of

TRAJECTORY_COLUMNS = TABLES["trajectory"]


#: The header line (``compare``) that says how a file carries a pinned state A.
PINNED_NOTE = ("beside the current state B, the pinned state A of a comparison: its settings "
               "are the lines 'pinned <key>', its values the columns ending in _A")


def _trajectory(data) -> tuple[dict, dict] | None:
    """(columns, settings) of a ``SupportData``'s contact, or None without a trajectory."""
    result = data.result if data is not None else None
    series = result.series if result is not None else None
    if series is None:
        return None
    settings = {**data.params.as_dict(), "rtol": result.options.rtol,
                "t_out": result.t_out, "success": bool(result.success),
                "message": result.message,
                # The page speaks in degrees: the file gives them beside the radians.
                "theta0_deg": math.degrees(data.params.theta0)}
    columns = {name: value_of(series, name) for name in TRAJECTORY_COLUMNS}
    columns["theta_deg"] = np.degrees(np.asarray(columns["theta"], float))
    return columns, settings


def _with_pinned(columns: dict, header: dict, pinned: tuple[dict, dict] | None,
                 why_not: str) -> tuple[dict, dict]:
    """B's ``columns`` and ``header`` with A's (``pinned``: its columns and settings)
    beside them; without A's, ``why_not`` says why in the header."""
    if pinned is None:
        return columns, ({**header, "compare": why_not} if why_not else header)
    a_columns, a_settings = pinned
    n = max(len(c) for c in (*columns.values(), *a_columns.values()))

    def padded(values):
        values = np.asarray(values)
        if len(values) == n:
            return values
        return np.concatenate((values.astype(float), np.full(n - len(values), np.nan)))
    out = {name: padded(values) for name, values in columns.items()}
    out.update({f"{name}_A": padded(values) for name, values in a_columns.items()})
    return out, {**header, "compare": PINNED_NOTE,
                 **{f"pinned {k}": v for k, v in a_settings.items()}}


def trajectory_csv(data, rtol: float | None = None, pinned=None,
                   comparing: bool = False) -> str:
    """The sampled contact of ``data`` (a ``SupportData``): tau, state, friction / f_N;
    with ``pinned`` (A's ``SupportData``) A's beside it. ``comparing``: A is pinned (its
    trajectory may not be there yet)."""
    mine = _trajectory(data)
    if mine is None:
        return "# no trajectory: " + (data.error if data is not None else "no data") + "\n"
    columns, settings = mine
    header = {"kind": "trajectory", "figure": "7, 10", "version": __version__, **settings,
              "forces": "friction on the support over f_N = beta F_N",
              "column theta_deg": "theta in degrees"}
    a = _trajectory(pinned)
    why_not = "" if not comparing or a is not None else (
        "pinned, but its trajectory is not computed: " + (pinned.error if pinned else
                                                           "not yet"))
    return csvfile.text(*_with_pinned(columns, header, a, why_not))


def _sweep(sweep) -> tuple[dict, dict]:
    columns, header = dict(sweep.columns), {}
    if "theta0" in columns:  # the page speaks in degrees: first column, beside the radians
        columns = {"theta0_deg": np.degrees(np.asarray(columns["theta0"], float)), **columns}
        header["column theta0_deg"] = "theta0 in degrees"
    return columns, header


def sweep_csv(sweep, pinned=None, comparing: bool = False) -> str:
    """A ``model.SweepResult`` (e.g. the polar sweep of Fig. 11) as CSV text; with
    ``pinned`` (A's sweep over the same points) A's beside it. ``comparing``: A is pinned
    (its sweep may not be there yet)."""
    if sweep is None:
        return "# no sweep computed yet: open the Polar tab first\n"
    columns, header = _sweep(sweep)
    header = {"kind": sweep.kind, "version": __version__, "points": len(sweep),
              "seconds": round(float(sweep.seconds), 3), **sweep.settings, **header}
    a = None if pinned is None else (_sweep(pinned)[0], dict(pinned.settings))
    why_not = "pinned, but its sweep is not computed yet" if comparing and a is None else ""
    return csvfile.text(*_with_pinned(columns, header, a, why_not))


def _not_yet(what: str) -> str:
    return f"# no {what} computed yet: it is being computed, download again in a moment\n"


def map_csv(regime_map) -> str:
    """The regime map on show (Fig. 5, a ``model.runs.shipped_map.RegimeMap``): one row per
    (k_r, k_theta) cell, k_r outer; its metadata (load, beta, tolerance, grid) in the header."""
    if regime_map is None:
        return _not_yet("regime map")
    arrays = regime_map.arrays()
    n, m = regime_map.shape
    k_r, k_theta = np.meshgrid(arrays.pop("k_r"), arrays.pop("k_theta"), indexing="ij")
    columns = {"k_r": k_r.ravel(), "k_theta": k_theta.ravel(),
               **{name: np.asarray(v).ravel() for name, v in arrays.items()}}
    columns["quadrature_error_FTx"] = columns.pop("quadrature_error")
    header = {"kind": "regime_map", "figure": "5", "version": __version__,
              "cells": f"{n} x {m} (k_r outer)", **regime_map.metadata}
    return csvfile.text(columns, header)


def load_csv(curves: dict | None) -> str:
    """The Load tab's curves (Fig. 6): {curve: {F_N: uniform-array row}} as one row per
    curve and load; ``curve`` is "current" (the springs of the controls) or a regime."""
    rows = [(name, F_N, row) for name, curve in (curves or {}).items()
            for F_N, row in sorted(curve.items())]
    if not rows:
        return _not_yet("load curve")
    names = [k for k in rows[0][2] if k not in ("k_r", "k_theta", "F_N")]
    columns = {"curve": [r[0] for r in rows], "k_r": [r[2].get("k_r") for r in rows],
               "k_theta": [r[2].get("k_theta") for r in rows], "F_N": [r[1] for r in rows],
               **{k: [r[2].get(k) for r in rows] for k in names}}
    header = {"kind": "load", "figure": "6", "version": __version__,
              "column curve": "current: the springs of the controls; else a regime of the paper"}
    return csvfile.text(columns, header)


#: The Array tab's per-frame columns (``model.arrays.array_motion.ArrayMotion``).
ARRAY_FRAME_COLUMNS = ("t", "slab_lead", "N_c", "N_c0", "FTx", "FTx_running")


def array_csv(motion) -> str:
    """The Array tab's live curves, frame by frame (time, the slab's leading edge, supports
    in contact N_c against N_c0, F_T,x/(mu0 F_N) now and its running mean); the array
    model's readouts and the grid in the header."""
    if motion is None:
        return _not_yet("array")
    columns = {name: np.asarray(getattr(motion, name), float) for name in ARRAY_FRAME_COLUMNS}
    model = {f"model {k}": (v if isinstance(v, str) else float(v))
             for k, v in motion.model.items()}
    header = {"kind": "array", "figure": "2a, 4", "version": __version__,
              **motion.params.as_dict(), "orientation": motion.orientation,
              "supports": int(motion.n_supports),
              "grid": f"{motion.n_rows} x {motion.n_cols}", "steady window": [float(x) for x in motion.steady],
              **model,
              "column FTx": "F_T,x/(mu0 F_N) of the supports in contact now (NaN: no rigid "
                            "support would be under the slab)",
              "column FTx_running": "its mean since the steady window opened"}
    return csvfile.text(columns, header)
