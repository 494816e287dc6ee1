"""The project's CSV format, written and read in one place.

A file starts with ``# key: value`` lines (what was computed, the package version, the
settings; strings as they are, everything else as JSON), then one line per registered
column saying what it holds (``# column k_r: k_r: radial stiffness (Eq. (5))``, from
``model.arrays.quantities``), then a header row and the data. Floats are written in their
shortest round-trip form, so reading a file back gives the same numbers.
``numpy.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8",
skip_header=<number of # lines>)`` reads the table too.
"""
from __future__ import annotations

import csv
import io
import json

import numpy as np

from .arrays.quantities import QUANTITIES, column_notes

__all__ = ["write", "text", "read", "read_text", "cell"]

_COLUMN = "column "


def cell(value) -> str:
    """Text of one CSV cell; floats in their shortest round-trip form."""
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return str(value)


def write(out, columns: dict, header: dict) -> None:
    """Write ``header`` and the equally long ``columns`` (name -> values) to the text
    stream ``out``."""
    notes = column_notes([name for name in columns if name in QUANTITIES])
    for key, value in {**header, **notes}.items():
        out.write(f"# {key}: {value if isinstance(value, str) else json.dumps(value)}\n")
    writer = csv.writer(out)
    writer.writerow(list(columns))
    for row in zip(*columns.values()):
        writer.writerow([cell(v) for v in row])


def text(columns: dict, header: dict) -> str:
    """``write`` into a string."""
    out = io.StringIO()
    write(out, columns, header)
    return out.getvalue()


def read(path) -> tuple[dict, dict]:
    """(header, columns) of a file written by ``write``; columns are numpy arrays
    (bool, int, float or str, whichever reads every cell)."""
    with open(path, encoding="utf-8") as src:
        return _read_lines(src)


def read_text(text: str) -> tuple[dict, dict]:
    """``read`` of the text ``write`` wrote (``text``'s result)."""
    return _read_lines(io.StringIO(text))


def _read_lines(src) -> tuple[dict, dict]:
    header, lines = {}, []
    for line in src:
        if line.startswith("# "):
            key, _, value = line[2:].rstrip("\n").partition(": ")
            if key.startswith(_COLUMN):
                continue  # described by the registry, not a setting
            try:
                header[key] = json.loads(value)
            except ValueError:
                header[key] = value
        else:
            lines.append(line)
    if not lines:
        return header, {}
    names, *rows = list(csv.reader(lines))
    return header, {name: _parse([r[j] for r in rows]) for j, name in enumerate(names)}


def _parse(texts):
    if texts and set(texts) <= {"True", "False"}:
        return np.array([t == "True" for t in texts])
    for kind in (int, float):
        try:
            return np.array([kind(t) for t in texts], dtype=kind)
        except ValueError:
            pass
    return np.array(texts)
