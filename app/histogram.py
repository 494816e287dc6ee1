"""An orientation histogram uploaded to the Design tab: the file read, its form in the
state, and its text in a shared link.

``read_upload`` reads the bytes of a CSV file in the form the command line and
``model.designs.distributions.Histogram.from_csv`` accept (``model.designs.histogram_csv``: a header
``theta0_deg,weight`` or ``lower_deg,upper_deg,weight``, one row per bin), refusing an
empty, oversized, undecodable, non-numeric or negative-weight file with a ``ValueError``
that names the problem. It returns the state's form ``{"edges_deg": [...], "weights": [...]}``
(``ExplorerState.dist_hist``; ``from_dict`` reads it with ``family="histogram"``).

A link carries a histogram of at most ``LINK_MAX_BINS`` equally wide bins as one URL value
(``link_text`` / ``from_link``), ``hist=<first edge>:<bin width>:<weights>``, angles in
degrees, each weight two characters of the URL-safe base-64 alphabet: an integer level
0 ... 4095 of the largest bin. Such a histogram is held in the state with its weights as
these levels (rounded to 1 part in 4095 of the largest, 1.2e-4 of it at most), so the
page computes exactly what the link restores. Any other histogram is used as read and is
not in the link (``link_note`` says so).
"""
from __future__ import annotations

import math

import numpy as np

from model.designs.distributions import Histogram

from .upload import upload_text

__all__ = ["MAX_UPLOAD_BYTES", "MAX_BINS", "LINK_MAX_BINS", "LINK_MAX_CHARS", "LEVELS", "read_upload",
           "link_text", "from_link", "link_note", "describe"]

#: Largest file read (a 360-bin histogram is ~5 kB).
MAX_UPLOAD_BYTES = 64 * 1024
#: Most bins used on the page: every bin edge is a break of the orientation quadrature.
MAX_BINS = 360
#: Most bins a link carries (2 characters each in a URL value of at most 100).
LINK_MAX_BINS = 40
#: Longest ``hist=`` value (``app.urlstate.MAX_VALUE_CHARS``: a longer one is not read).
LINK_MAX_CHARS = 100
#: Weight levels in a link: two base-64 characters.
LEVELS = 64 * 64 - 1
_ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_"
_INDEX = {c: i for i, c in enumerate(_ALPHABET)}


def _fmt(value: float) -> str:
    return format(float(value), ".6g")


def _levels(weights) -> list[int]:
    w = np.asarray(weights, dtype=float)
    return [int(q) for q in np.rint(w / w.max() * LEVELS)]


def _linkable(edges_deg: np.ndarray) -> tuple[float, float] | None:
    """(first edge, width) written as the link writes them, when the bins are equally wide,
    at most ``LINK_MAX_BINS``, and the written numbers give the same edges (1e-6 deg)."""
    n = edges_deg.size - 1
    widths = np.diff(edges_deg)
    if n > LINK_MAX_BINS or not np.allclose(widths, widths[0], rtol=1e-9, atol=1e-9):
        return None
    lo, width = float(_fmt(edges_deg[0])), float(_fmt(widths.mean()))
    if abs(lo - edges_deg[0]) > 1e-6 or abs(width - widths.mean()) > 1e-6:
        return None
    return lo, width


def _regular(lo: float, width: float, levels: list[int]) -> dict:
    """The state's form of a link's histogram (the same floats whichever way it came)."""
    edges = [lo + width * i for i in range(len(levels) + 1)]
    Histogram(tuple(np.radians(edges)), tuple(levels))  # raises if unusable
    return {"edges_deg": edges, "weights": list(levels)}


def read_upload(data: bytes, filename: str = "") -> dict:
    """The state's form of an uploaded histogram file; ``ValueError`` naming what is wrong
    with the file (empty, too large, not text, not the CSV form, bad values)."""
    name = f"the file {filename!r}" if filename else "the uploaded file"
    text = upload_text(data, name, MAX_UPLOAD_BYTES,
                       "upload a CSV file with a header row (theta0_deg,weight or "
                       "lower_deg,upper_deg,weight) and one row per bin",
                       "a histogram needs one short row per bin")
    hist = Histogram.from_text(text, name)
    n = len(hist.weights)
    if n > MAX_BINS:
        raise ValueError(f"{name} has {n} bins, at most {MAX_BINS} are used here: merge bins "
                         f"(e.g. 72 bins of 5 degrees), or use the command line "
                         f"(python -m model array --orientation csv --histogram FILE)")
    edges = np.degrees(hist.edges)
    linkable = _linkable(edges)
    if linkable is not None:
        try:
            return _regular(*linkable, _levels(hist.weights))
        except ValueError:
            pass  # rounding made the span exceed 360 degrees: keep the file's numbers
    return {"edges_deg": [float(e) for e in edges], "weights": list(hist.weights)}


def link_text(hist: dict | None) -> str | None:
    """The ``hist=`` value of the state's histogram, or None when a link cannot carry it."""
    if not hist:
        return None
    edges = np.asarray(hist["edges_deg"], dtype=float)
    linkable = _linkable(edges)
    if linkable is None:
        return None
    levels = _levels(hist["weights"])
    try:
        if _regular(*linkable, levels) != hist:  # not held as link levels: would change
            return None
    except ValueError:
        return None
    code = "".join(_ALPHABET[q // 64] + _ALPHABET[q % 64] for q in levels)
    text = f"{_fmt(linkable[0])}:{_fmt(linkable[1])}:{code}"
    return text if len(text) <= LINK_MAX_CHARS else None


def from_link(text: str) -> dict | None:
    """The state's histogram from a ``hist=`` value, or None when it is unusable."""
    parts = text.split(":")
    if len(parts) != 3:
        return None
    try:
        lo, width = float(parts[0]), float(parts[1])
    except ValueError:
        return None
    code = parts[2]
    if not (math.isfinite(lo) and math.isfinite(width) and -360.0 <= lo <= 360.0
            and width > 0) or len(code) % 2 or not 2 <= len(code) <= 2 * LINK_MAX_BINS:
        return None
    if any(c not in _INDEX for c in code):
        return None
    levels = [_INDEX[code[i]] * 64 + _INDEX[code[i + 1]] for i in range(0, len(code), 2)]
    if not any(levels):
        return None
    try:
        return _regular(lo, width, levels)
    except ValueError:
        return None


def describe(hist: dict) -> str:
    """'36 bins from -5° to 355°'."""
    e = hist["edges_deg"]
    return f"{len(e) - 1} bin{'s' if len(e) > 2 else ''} from {e[0]:.4g}° to {e[-1]:.4g}°"


def link_note(hist: dict | None) -> str:
    """Whether a shared link carries ``hist``, in a sentence for the page."""
    if not hist:
        return ""
    if link_text(hist) is not None:
        return "In the link (weights to 1 part in 4095 of the largest bin)."
    return (f"**Not in the link:** a link carries at most {LINK_MAX_BINS} equally wide bins; "
            "a shared link opens with the uniform distribution until the file is uploaded "
            "there.")
