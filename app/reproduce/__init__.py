"""The paper's figures drawn: ``python -m app.reproduce --out DIR`` (run from the project's
folder, as ``panel serve app``).

``model.reproduce`` computes every figure's data, writes the CSVs and the findings report;
this package adds the pictures, drawn with the dashboard's own figure functions:
``figN.html`` (standalone, BokehJS inlined, opens offline) and ``figN.png`` (a screenshot
in headless Chromium through Playwright, when both are installed).
"""
from __future__ import annotations

from functools import partial

from model.reproduce import reproduce as _compute
from model.reproduce.tables import FIGURES

from . import render
from .figures import DRAW

__all__ = ["reproduce", "draw"]


def draw(data, out, progress, png="auto") -> tuple[dict, str]:
    """Every figure as HTML (and PNG): key -> (html, png or None), and why PNGs are missing
    ("" when they are not). ``png``: "auto" (when a browser is available), True (fail
    without one) or False."""
    titles = {f.key: f"Fig. {f.number}: {f.caption}" for f in FIGURES}
    files = {}
    for i, (key, fn) in enumerate(DRAW.items()):
        files[key] = render.save_html(fn(data), out / f"{key}.html", titles[key])
        progress(i + 1, 2 * len(DRAW))
    problem = render.browser_problem() if png else "not requested"
    if png is True and problem:
        raise RuntimeError(f"PNG pictures were requested but cannot be made: {problem}")
    pngs = {key: None for key in files}
    if not problem:
        pages = [(html, out / f"{key}.png") for key, html in files.items()]
        render.html_to_png(pages, lambda done, total: progress(len(DRAW) + done, 2 * len(DRAW)))
        pngs = {key: png_ for key, (_, png_) in zip(files, pages)}
    return {key: (files[key], pngs[key]) for key in files}, problem or ""


def reproduce(out, resolution="full", workers: int = 1, png="auto", progress=None):
    """``model.reproduce.reproduce`` with the figures drawn (see ``draw``)."""
    if png not in ("auto", True, False):
        raise ValueError(f"png={png!r} must be 'auto', True or False")
    return _compute(out, resolution, workers, progress, draw=partial(draw, png=png))
