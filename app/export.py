"""CSV downloads: the current trajectory (Figs. 7, 10) and the polar sweep (Fig. 11).

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
from model.quantities import TABLES, value_of

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
