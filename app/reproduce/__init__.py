"""The paper's figures drawn: ``python -m app.reproduce --out DIR`` (run from the project's
folder, as ``panel serve app``).

``model.reproduce`` computes every figure's data, writes the CSVs and the findings report;
this package adds the pictures, drawn with the dashboard's own figure functions:
``figN.html`` (standalone, BokehJS inlined, opens offline) and, through headless Chromium
and Playwright, ``figN.png`` (a screenshot; by default when both are installed),
``figN.svg`` (vector, drawn by BokehJS) and ``figN.pdf`` (vector, Chromium's print of the
SVG) on request (``formats``; ``python -m app.reproduce --format svg``).
"""
from __future__ import annotations

from functools import partial

from model.reproduce import reproduce as _compute
from model.reproduce.tables import FIGURES

from . import render
from .figures import DRAW

__all__ = ["reproduce", "draw", "FORMATS"]

FORMATS = render.FORMATS


def _formats(png, formats) -> tuple[set, bool]:
    """The picture formats to make and whether they are required (fail without a browser)."""
    if formats is None:
        return ({"png"} if png else set()), png is True
    formats = {formats} if isinstance(formats, str) else set(formats)
    if not formats or not formats <= set(FORMATS):
        raise ValueError(f"formats={sorted(formats)!r} must be some of {list(FORMATS)}")
    return formats, True


def draw(data, out, progress, png="auto", formats=None) -> tuple[dict, str]:
    """Every figure as HTML and pictures: key -> (html, png, svg, pdf; None where not
    made), and why pictures are missing ("" when they are not). ``png``: "auto" (when a
    browser is available), True (fail without one) or False; ``formats`` (some of
    ``FORMATS``) replaces it: exactly those pictures, failing without a browser."""
    wanted, required = _formats(png, formats)
    titles = {f.key: f"Fig. {f.number}: {f.caption}" for f in FIGURES}
    files = {}
    steps = 2 * len(DRAW)
    for i, (key, fn) in enumerate(DRAW.items()):
        files[key] = render.save_html(fn(data), out / f"{key}.html", titles[key])
        progress(i + 1, steps)
    problem = render.browser_problem() if wanted else "not requested"
    if required and problem:
        raise RuntimeError(f"{'/'.join(sorted(f.upper() for f in wanted))} pictures were "
                           f"requested but cannot be made: {problem}")
    made = {key: {} for key in files}
    if not problem:
        jobs = [(html, titles[key], {fmt: out / f"{key}.{fmt}" for fmt in FORMATS
                                     if fmt in wanted}) for key, html in files.items()]
        written = render.pictures(jobs, lambda done, total: progress(len(DRAW) + done, steps))
        made = dict(zip(files, written))
    return {key: (files[key], *(made[key].get(fmt) for fmt in FORMATS)) for key in files}, \
        problem or ""


def reproduce(out, resolution="full", workers: int = 1, png="auto", progress=None,
              formats=None):
    """``model.reproduce.reproduce`` with the figures drawn (see ``draw``)."""
    if png not in ("auto", True, False):
        raise ValueError(f"png={png!r} must be 'auto', True or False")
    _formats(png, formats)  # a bad format fails before the computations
    return _compute(out, resolution, workers, progress,
                    draw=partial(draw, png=png, formats=formats))
