"""A measured friction curve read from a CSV file: friction coefficient against sliding
speed, the data a tribometer gives (fitted with Eq. (4) by ``model.lab.friction_fit``).

The file has a header row naming the columns ``v`` (sliding speed, its unit in brackets:
``v [mm/s]``, or given separately) and ``mu`` (friction coefficient), and optionally
``mu_err`` (the standard error of each ``mu``, used as the fit's weights); other columns
are ignored. Lines starting with ``#`` and blank lines are skipped. Every refusal is a
``CurveFileError`` naming the file, the line and the fix.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..designs.histogram_csv import data_rows, number_cell
from ..designs.si import ureg
from ..files import read_user_text

__all__ = ["FrictionCurve", "CurveFileError", "read_curve", "curve_from_text", "speed_factor",
           "N_COEFFICIENTS"]

#: Coefficients of Eq. (4) that a fit determines: mu_s, A, B and V_s.
N_COEFFICIENTS = 4

_UNIT = re.compile(r"^\s*(\w+)\s*(?:\[(.*)\])?\s*$")


class CurveFileError(ValueError):
    """A friction-curve file that cannot be used, with the line that says why."""


@dataclass(frozen=True)
class FrictionCurve:
    """Measured friction coefficient ``mu`` against sliding speed ``v`` (m/s), with the
    standard error ``mu_err`` of each point (None when the file has none)."""

    v: np.ndarray
    mu: np.ndarray
    mu_err: np.ndarray | None = None
    source: str = ""

    def __post_init__(self):
        v, mu = np.asarray(self.v, dtype=float), np.asarray(self.mu, dtype=float)
        err = None if self.mu_err is None else np.asarray(self.mu_err, dtype=float)
        object.__setattr__(self, "v", v)
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "mu_err", err)
        if v.ndim != 1 or mu.shape != v.shape or (err is not None and err.shape != v.shape):
            raise ValueError(f"v, mu and mu_err must be 1-d and equally long, not of shapes "
                             f"{v.shape}, {mu.shape}{'' if err is None else ', ' + str(err.shape)}")
        problem = first_problem(v, mu, err)
        if problem is not None:
            i, text = problem
            raise ValueError(f"point {i}: {text}")

    @property
    def n_points(self) -> int:
        return len(self.v)


def first_problem(v, mu, mu_err=None):
    """(index, reason) of the first point a fit of Eq. (4) cannot use, or None: a value
    that is not finite, a negative speed, a ``mu_err`` that is not positive, too few
    points (index: the last point), or no positive speed."""
    columns = {"v": v, "mu": mu, **({} if mu_err is None else {"mu_err": mu_err})}
    for i in range(len(v)):
        for key, values in columns.items():
            if not math.isfinite(values[i]):
                return i, f"{key} = {values[i]!r} is not a finite number"
        if v[i] < 0:
            return i, f"negative speed v = {v[i]!r}; give the sliding speed's magnitude"
        if mu_err is not None and not mu_err[i] > 0:
            return i, f"mu_err = {mu_err[i]!r} must be positive (the standard error of mu)"
    if len(v) < N_COEFFICIENTS:
        return max(len(v) - 1, 0), (f"{len(v)} data points, fewer than the {N_COEFFICIENTS} "
                                    f"coefficients of Eq. (4) (mu_s, A, B, V_s); measure "
                                    f"more speeds")
    if not np.any(np.asarray(v) > 0):
        return len(v) - 1, "every speed is zero; measure at sliding speeds above zero"
    return None


def speed_factor(unit: str, where: str = "--v-unit") -> float:
    """Metres per second in one ``unit`` of speed (``"mm/s"``, ``"um/s"``, ``"m/s"``);
    ``CurveFileError`` naming ``where`` when it is not a speed."""
    try:
        q = ureg.Quantity(1.0, unit.strip())
        ok = q.check("[length] / [time]")
    except Exception:  # pint raises many kinds for text that is not a unit
        ok = False
    if not ok:
        raise CurveFileError(f"{where}: {unit!r} is not a unit of speed; write it like 'mm/s' "
                             f"or 'm/s'")
    return float(q.to("m/s").magnitude)


def _header(cells, name: str, line: int, v_unit: str | None):
    """Column indices of v, mu, mu_err and the speed factor from the header row."""
    columns, unit = {}, None
    for j, text in enumerate(cells):
        match = _UNIT.match(text)
        if not match:
            continue
        key = match.group(1).lower()
        if key in ("v", "mu", "mu_err") and key not in columns:
            columns[key] = j
            if key == "v":
                unit = match.group(2)
    missing = [c for c in ("v", "mu") if c not in columns]
    if missing:
        raise CurveFileError(
            f"{name} line {line}: the header {','.join(cells)!r} has no column "
            f"{' or '.join(repr(c) for c in missing)}; the first row must name the columns, "
            f"such as 'v [mm/s],mu' (optionally ',mu_err')")
    if unit is not None and v_unit is not None and \
            speed_factor(unit, f"{name} line {line}") != speed_factor(v_unit):
        raise CurveFileError(f"{name} line {line}: the header gives v in {unit!r} but "
                             f"--v-unit says {v_unit!r}; give one of them")
    unit = unit if unit is not None else v_unit
    if unit is None:
        raise CurveFileError(f"{name} line {line}: no unit for v; write the header as "
                             f"'v [mm/s],mu' or give --v-unit mm/s")
    factor = speed_factor(unit, f"{name} line {line}" if v_unit is None else "--v-unit")
    return columns, factor


def read_curve(path, v_unit: str | None = None) -> FrictionCurve:
    r"""The friction curve in ``path`` (speeds converted to m/s); ``CurveFileError`` naming
    the line for a file without a header, a cell that is not a finite number, a negative
    speed, a ``mu_err`` that is not positive, or fewer points than the coefficients of
    Eq. (4).

    Parameters
    ----------
    path : str or Path
        A CSV file with columns ``v`` and ``mu`` (optional ``mu_err``); the speed unit in
        the header (``v [mm/s]``) or in ``v_unit``.
    v_unit : str, optional
        The unit of ``v`` when the header gives none, e.g. ``"mm/s"``.

    Returns
    -------
    FrictionCurve
        The points, speeds in m/s.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from model import read_curve
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "flat.csv"
    >>> _ = path.write_text("v [mm/s],mu\n0.1,0.5\n1,1.0\n10,1.2\n100,1.25\n1000,1.27\n")
    >>> curve = read_curve(path)
    >>> float(curve.v[1]), len(curve.mu)
    (0.001, 5)
    """
    try:
        text = read_user_text(path, "CSV")
    except ValueError as error:
        raise CurveFileError(str(error)) from None
    return curve_from_text(text, Path(path).name, v_unit, source=str(path))


def curve_from_text(text: str, name: str, v_unit: str | None = None,
                    source: str = "") -> FrictionCurve:
    """The friction curve in the CSV ``text`` of the file ``name`` (as ``read_curve``
    reads a file, e.g. an upload's content); ``CurveFileError`` naming the line."""
    rows = data_rows(text)
    if not rows:
        raise CurveFileError(f"{name}: no header and no data; the first row must name the "
                             f"columns, such as 'v [mm/s],mu'")
    line, cells = rows[0]
    if all(_is_number(c) for c in cells):
        raise CurveFileError(f"{name} line {line}: no header (the first row holds numbers); "
                             f"add a first row naming the columns, such as 'v [mm/s],mu'")
    columns, factor = _header(cells, name, line, v_unit)
    width = max(columns.values()) + 1
    data, numbers = {key: [] for key in columns}, []
    for line, cells in rows[1:]:
        if len(cells) < width:
            raise CurveFileError(f"{name} line {line}: {len(cells)} cells, the header names "
                                 f"{width}")
        try:
            for key, j in columns.items():
                data[key].append(number_cell(name, line, cells[j]))
        except ValueError as error:
            raise CurveFileError(str(error)) from None
        numbers.append(line)
    v = np.array(data["v"], dtype=float)
    mu = np.array(data["mu"], dtype=float)
    err = np.array(data["mu_err"], dtype=float) if "mu_err" in data else None
    problem = first_problem(v, mu, err)
    if problem is not None:
        i, text = problem
        line = numbers[i] if numbers else rows[-1][0]
        raise CurveFileError(f"{name} line {line}: {text}")
    return FrictionCurve(v=v * factor, mu=mu, mu_err=err, source=source)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
