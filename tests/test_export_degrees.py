"""The page speaks in degrees, and so do its CSV downloads: the trajectory carries
theta in degrees beside radians and theta0 in degrees in its header; the polar sweep's
first column is theta0 in degrees."""
import csv
import io
import math

import pytest

from app.export import sweep_csv, trajectory_csv
from app.worker import compute_polar, compute_support
from model import REGIMES


def _rows(text):
    return [r for r in csv.reader(io.StringIO(text)) if r and not r[0].startswith("#")]


def test_trajectory_has_degrees():
    p = REGIMES["pendulum"].replace(theta0=math.radians(120.0))
    text = trajectory_csv(compute_support(p))
    header = dict(line[2:].split(": ", 1) for line in text.splitlines()
                  if line.startswith("# ") and ": " in line)
    assert float(header["theta0_deg"]) == pytest.approx(120.0, rel=1e-12)
    rows = _rows(text)
    i, j = rows[0].index("theta"), rows[0].index("theta_deg")
    for row in rows[1:]:
        assert float(row[j]) == pytest.approx(math.degrees(float(row[i])), rel=1e-12)


def test_polar_sweep_starts_with_degrees():
    rows = _rows(sweep_csv(compute_polar(REGIMES["stiff"])))
    assert rows[0][:2] == ["theta0_deg", "theta0"]
    assert all(float(r[0]) == pytest.approx(math.degrees(float(r[1])), rel=1e-12)
               for r in rows[1:])
    assert 0 < float(rows[1][0]) < float(rows[-1][0]) < 180
