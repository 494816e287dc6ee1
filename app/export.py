"""CSV downloads: the current trajectory (Figs. 7, 10) and the polar sweep (Fig. 11).

Both start with ``# key: value`` lines (parameters, settings, package version), like the
model's sweep CSVs, then a header row and the data.
"""
from __future__ import annotations

import csv
import io
import json

import numpy as np

from model import __version__

TRAJECTORY_COLUMNS = ("tau", "x", "y", "v_x", "v_y", "theta", "r", "F_x", "F_y", "F_abs")


def _header(out, items: dict) -> None:
    for key, value in items.items():
        out.write(f"# {key}: {value if isinstance(value, str) else json.dumps(value)}\n")


def _cell(value) -> str:
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def trajectory_csv(data, rtol: float | None = None) -> str:
    """The sampled contact of ``data`` (a ``SupportData``): tau, state, friction / f_N."""
    out = io.StringIO()
    result = data.result if data is not None else None
    series = result.series if result is not None else None
    if series is None:
        out.write("# no trajectory: " + (data.error if data is not None else "no data") + "\n")
        return out.getvalue()
    settings = {"kind": "trajectory", "figure": "7, 10", "version": __version__,
                **data.params.as_dict(), "rtol": result.options.rtol,
                "t_out": result.t_out, "success": bool(result.success),
                "message": result.message,
                "forces": "friction on the support over f_N = beta F_N",
                "v_R_abs": "|v - (1, 0)|, the relative speed of Eq. 4"}
    _header(out, settings)
    writer = csv.writer(out)
    writer.writerow([*TRAJECTORY_COLUMNS, "v_R_abs"])
    cols = [np.asarray(getattr(series, c)) for c in TRAJECTORY_COLUMNS]
    v_r = np.hypot(np.asarray(series.v_x) - 1.0, np.asarray(series.v_y))
    for row in zip(*cols, v_r):
        writer.writerow([_cell(v) for v in row])
    return out.getvalue()


def sweep_csv(sweep) -> str:
    """A ``model.SweepResult`` (e.g. the polar sweep of Fig. 11) as CSV text."""
    out = io.StringIO()
    if sweep is None:
        out.write("# no sweep computed yet: open the Polar tab first\n")
        return out.getvalue()
    _header(out, {"kind": sweep.kind, "version": __version__, "points": len(sweep),
                  "seconds": round(float(sweep.seconds), 3), **sweep.settings})
    writer = csv.writer(out)
    writer.writerow(list(sweep.columns))
    for row in zip(*sweep.columns.values()):
        writer.writerow([_cell(v) for v in row])
    return out.getvalue()
