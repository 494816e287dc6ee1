"""The CSV form of an orientation histogram (``model.designs.distributions.Histogram``).

A header row, then one row per bin, in either form:

* ``theta0_deg,weight``: equally spaced bin centres in degrees (each bin as wide as the
  spacing; a single row is a bin of 360 degrees around its centre);
* ``lower_deg,upper_deg,weight``: contiguous bins given by their edges in degrees.

Lines starting with ``#`` are comments. Weights are shares of the supports: finite,
non-negative, not all 0 (normalised by ``Histogram``). ``parse_histogram`` reads the text
of such a file (from disk: ``Histogram.from_csv``; from a page upload:
``Histogram.from_text``) and raises ``ValueError`` naming the source, the row and the fix.
"""
from __future__ import annotations

import csv
import math

import numpy as np

__all__ = ["HEADERS", "parse_histogram", "data_rows", "number_cell"]

#: The accepted header rows.
HEADERS = (("theta0_deg", "weight"), ("lower_deg", "upper_deg", "weight"))
_EXPECTED = "theta0_deg,weight or lower_deg,upper_deg,weight"


def data_rows(text: str) -> list[tuple[int, list[str]]]:
    """(line number, cells) of the non-empty, non-comment lines of a CSV text (also read
    by ``model.lab.friction_curve``)."""
    out = []
    for number, row in enumerate(csv.reader(text.splitlines()), start=1):
        if row and any(c.strip() for c in row) and not row[0].lstrip().startswith("#"):
            out.append((number, row))
    return out


def number_cell(source: str, line: int, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{source} has a non-numeric value {text.strip()[:20]!r} on line "
                         f"{line}; every row after the header must hold numbers") from None
    if not math.isfinite(value):
        raise ValueError(f"{source} has a value that is not finite ({text.strip()!r}) on line "
                         f"{line}; give finite numbers")
    return value


def parse_histogram(text: str, source: str = "the histogram") -> tuple[np.ndarray, np.ndarray]:
    """Bin edges (radians, increasing) and weights (as given) of a histogram's CSV ``text``.

    ``source`` names the file in the errors (e.g. ``"histogram file 'h.csv'"``).
    """
    rows = data_rows(text)
    if len(rows) < 2:
        raise ValueError(f"{source} is empty: it needs a header row ({_EXPECTED}) and one "
                         f"row per bin")
    header = tuple(h.strip() for h in rows[0][1])
    if header not in HEADERS:
        raise ValueError(f"{source} has header {list(header)}; expected {_EXPECTED}")
    table = []
    for line, row in rows[1:]:
        if len(row) != len(header):
            raise ValueError(f"{source}: line {line} has {len(row)} columns; every row must "
                             f"have {len(header)} like its header {','.join(header)}")
        table.append([number_cell(source, line, x) for x in row])
    table = np.array(table, dtype=float)
    w = table[:, -1]
    negative = np.flatnonzero(w < 0)
    if negative.size:
        line = rows[1 + negative[0]][0]
        raise ValueError(f"{source} has a negative weight {w[negative[0]]:g} on line {line}; "
                         f"weights are shares of the supports and must be >= 0")
    if not w.sum() > 0:
        raise ValueError(f"{source}: every weight is 0; give at least one bin a positive "
                         f"weight (weights must be non-negative and not all 0)")
    if header == HEADERS[1]:
        lo, hi = table[:, 0], table[:, 1]
        if not np.allclose(lo[1:], hi[:-1]):
            raise ValueError(f"{source}: bins must be contiguous (each lower_deg equal to the "
                             f"previous upper_deg)")
        edges = np.append(lo, hi[-1])
    else:
        centres = table[:, 0]
        if centres.size == 1:
            edges = np.array([centres[0] - 180.0, centres[0] + 180.0])
        else:
            step = np.diff(centres)
            if not np.allclose(step, step[0], rtol=1e-6, atol=1e-9) or step[0] <= 0:
                raise ValueError(f"{source}: theta0_deg must be equally spaced and increasing")
            edges = np.append(centres - step[0] / 2, centres[-1] + step[0] / 2)
    if not (np.all(np.diff(edges) > 0) and edges[-1] - edges[0] <= 360.0 + 1e-7):
        raise ValueError(f"{source}: the bins must be increasing and span at most 360 degrees "
                         f"(they span {edges[0]:g} to {edges[-1]:g} degrees)")
    return np.radians(edges), w
