"""CSV downloads: the current trajectory (Figs. 7, 10) and the polar sweep (Fig. 11).

Both are written by the model's CSV writer (``model.csvfile``): ``# key: value`` lines
(parameters, settings, package version, what each column holds), a header row, the data.
"""
from __future__ import annotations

import math

import numpy as np

from model import __version__, csvfile
from model.quantities import TABLES, value_of

TRAJECTORY_COLUMNS = TABLES["trajectory"]


def trajectory_csv(data, rtol: float | None = None) -> str:
    """The sampled contact of ``data`` (a ``SupportData``): tau, state, friction / f_N."""
    result = data.result if data is not None else None
    series = result.series if result is not None else None
    if series is None:
        return "# no trajectory: " + (data.error if data is not None else "no data") + "\n"
    settings = {"kind": "trajectory", "figure": "7, 10", "version": __version__,
                **data.params.as_dict(), "rtol": result.options.rtol,
                "t_out": result.t_out, "success": bool(result.success),
                "message": result.message,
                "forces": "friction on the support over f_N = beta F_N",
                # The page speaks in degrees: the file gives them beside the radians.
                "theta0_deg": math.degrees(data.params.theta0),
                "column theta_deg": "theta in degrees"}
    columns = {name: value_of(series, name) for name in TRAJECTORY_COLUMNS}
    columns["theta_deg"] = np.degrees(np.asarray(columns["theta"], float))
    return csvfile.text(columns, settings)


def sweep_csv(sweep) -> str:
    """A ``model.SweepResult`` (e.g. the polar sweep of Fig. 11) as CSV text."""
    if sweep is None:
        return "# no sweep computed yet: open the Polar tab first\n"
    columns, header = dict(sweep.columns), {}
    if "theta0" in columns:  # the page speaks in degrees: first column, beside the radians
        columns = {"theta0_deg": np.degrees(np.asarray(columns["theta0"], float)), **columns}
        header["column theta0_deg"] = "theta0 in degrees"
    return csvfile.text(columns, {"kind": sweep.kind, "version": __version__,
                                  "points": len(sweep), "seconds": round(float(sweep.seconds), 3),
                                  **sweep.settings, **header})
