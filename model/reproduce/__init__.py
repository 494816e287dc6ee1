"""Reproduce the paper: every figure's data computed, every finding checked.

``reproduce(out)`` (or ``python -m model reproduce --out DIR``) computes the data behind
Figs. 3, 5a/b, 6, 7a/b, 8a/b, 10a-f and 11a-c and writes into ``out``:

* ``figN.csv`` -- each figure's data, with the parameters and solver settings in a
  ``# key: value`` header (``model.runs.sweeps.read_csv`` reads it back);
* ``report.md`` and ``index.html`` -- the findings of the paper (docs/model.md, "What the
  paper reports", 1-7) against
  the computed numbers with their error estimates, where the model differs, and how
  the headline numbers move with the choices the paper left open.

Drawing is the caller's (this package imports no plotting library): ``draw(data, out,
progress)`` returns, per figure key, the HTML file and the PNG, SVG and PDF files (None
where not made; a shorter tuple leaves the rest None) it wrote, and a note on pictures it
could not make. ``python -m app.reproduce`` passes the
dashboard's figure functions (standalone HTML, and PNG through headless Chromium).
Uniform-array points go through the on-disk cache, so a second run is quick.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from ..runs.sweeps import SweepResult
from . import findings, report, sensitivity
from .datasets import RESOLUTIONS, Data, Resolution, compute, stages
from .tables import FIGURES, FigureSpec

__all__ = ["reproduce", "Reproduction", "FigureFiles", "RESOLUTIONS", "Resolution",
           "FIGURES", "STAGES"]

#: Stages after the computations, for progress reports (the last only when drawing).
STAGES = ("sensitivity", "CSV tables", "figures")


@dataclass(frozen=True)
class FigureFiles:
    spec: FigureSpec
    csv: Path
    html: Path | None = None
    png: Path | None = None
    svg: Path | None = None
    pdf: Path | None = None


@dataclass
class Reproduction:
    """What ``reproduce`` wrote, with the checks and sensitivity variants it computed."""

    out: Path
    resolution: Resolution
    data: Data
    checks: list
    variants: list
    figures: list
    report: Path
    index: Path
    png_note: str
    version: str
    seconds: float
    extra_seconds: dict = field(default_factory=dict)

    @property
    def n_differ(self) -> int:
        return sum(not c.agrees for c in self.checks)


def _resolution(resolution) -> Resolution:
    if isinstance(resolution, Resolution):
        return resolution
    if resolution not in RESOLUTIONS:
        raise ValueError(f"resolution={resolution!r} must be one of {sorted(RESOLUTIONS)}")
    return RESOLUTIONS[resolution]


def _write_tables(data: Data, out: Path, tick) -> list:
    files = []
    for i, spec in enumerate(FIGURES):
        columns, settings = spec.table(data)
        header = {"figure": spec.number, "caption": spec.caption,
                  "resolution": data.resolution.name, **settings}
        csv = out / f"{spec.key}.csv"
        SweepResult(spec.key, {k: list(v) for k, v in columns.items()}, header, 0.0).to_csv(csv)
        files.append(FigureFiles(spec, csv))
        tick(i + 1, len(FIGURES))
    return files


def reproduce(out, resolution="full", workers: int = 1, progress=None,
              draw=None) -> Reproduction:
    """Compute every figure's data into the folder ``out`` and check the paper's findings.

    ``resolution``: ``"full"`` (the figures as published; 1-5 min on 2 cores) or
    ``"coarse"`` (a quick check of the pipeline), or a ``Resolution``. ``workers``:
    processes for the uniform-array sweeps. ``progress(stage, done, total)`` reports
    progress. ``draw``: see the module's docstring; without it, no pictures.
    """
    from .._version import __version__

    start = time.perf_counter()
    res = _resolution(resolution)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    report_ = progress or (lambda stage, done, total: None)
    data = compute(res, workers=workers, progress=report_)
    extra = {}

    def stage(name, fn):
        t0 = time.perf_counter()
        value = fn(lambda done, total: report_(name, done, total))
        extra[name] = time.perf_counter() - t0
        return value

    variants = stage(STAGES[0], lambda t: sensitivity.variants(data.headline, res.tol,
                                                               res.mc_draws, t))
    figures = stage(STAGES[1], lambda t: _write_tables(data, out, t))
    note = "no drawing requested (python -m app.reproduce draws them)"
    if draw is not None:
        drawn, note = stage(STAGES[2], lambda t: draw(data, out, t))
        figures = [FigureFiles(f.spec, f.csv, *drawn[f.spec.key]) for f in figures]
    rep = Reproduction(out, res, data, findings.all_checks(data), variants, figures,
                       out / "report.md", out / "index.html", note, __version__, 0.0, extra)
    rep.seconds = time.perf_counter() - start
    report.write(rep, out)
    return rep


def all_stages(resolution="full", drawing: bool = True) -> list:
    """Names of every stage ``reproduce`` reports progress on, in order."""
    return [name for name, _ in stages(_resolution(resolution))] + list(
        STAGES if drawing else STAGES[:2])
