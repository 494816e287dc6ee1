"""``python -m model reproduce --out DIR``: every figure of the paper regenerated, every
finding checked (see ``model.reproduce``).

Progress is drawn on stderr, one bar per stage; the summary (checks that agree and differ,
the files written) goes to stdout. Exit codes: 0 done (differences from the paper are
results, not failures), 2 bad usage, 130 interrupted.
"""
from __future__ import annotations

import sys
from pathlib import Path

from ._common import PROG, UsageError, whole
from .sweep import ProgressBar


def add_command(commands) -> None:
    p = commands.add_parser(
        "reproduce", help="regenerate every figure of the paper and check its findings",
        description="Regenerate Figs. 3, 5a/b, 6, 7a/b, 8a/b, 10a-f and 11a-c of the paper "
                    "as HTML, PNG (when Chromium and Playwright are available) and CSV, and "
                    "write report.md and index.html checking the paper's findings against the "
                    "computed numbers. Uniform-array points are kept in the on-disk cache, so "
                    "a second run is quick.")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="folder to write into (created if missing)")
    p.add_argument("--resolution", choices=("full", "coarse"), default="full",
                   help="full: the figures as published (default; 1-5 min on 2 cores, less with a warm cache); "
                        "coarse: a quick check of the pipeline")
    p.add_argument("--workers", type=whole, default=2, metavar="N",
                   help="processes for the uniform-array sweeps (default 2)")
    png = p.add_mutually_exclusive_group()
    png.add_argument("--png", dest="png", action="store_const", const=True, default="auto",
                     help="require PNG pictures (fail without a browser)")
    png.add_argument("--no-png", dest="png", action="store_const", const=False,
                     help="skip the PNG pictures")
    p.set_defaults(run=run)


class StageProgress:
    """``progress(stage, done, total)``: a stage's name, then its ``ProgressBar``."""

    def __init__(self, stream):
        self.stream, self.stage, self.bar = stream, None, None

    def __call__(self, stage: str, done: int, total: int) -> None:
        if stage != self.stage:
            self.close()
            self.stage, self.bar = stage, ProgressBar(self.stream)
            self.stream.write(f"{stage}\n")
        self.bar(done, total)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def run(args) -> int:
    from ..reproduce import reproduce

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError("--out", f"{str(out)!r} exists and is not a folder")
    if args.workers < 1:
        raise UsageError("--workers", f"{args.workers} must be at least 1")
    progress = StageProgress(sys.stderr)
    try:
        rep = reproduce(out, resolution=args.resolution, workers=args.workers, png=args.png,
                        progress=progress)
    except KeyboardInterrupt:
        progress.close()
        print(f"{PROG} reproduce: interrupted; {out} is incomplete", file=sys.stderr)
        return 130
    except OSError as error:
        progress.close()
        raise UsageError("--out", f"cannot write into {str(out)!r}: {error}") from None
    except RuntimeError as error:  # PNGs required but no browser
        progress.close()
        raise UsageError("--png", str(error)) from None
    progress.close()
    agree = len(rep.checks) - rep.n_differ
    print(f"{len(rep.figures)} figures ({'with' if not rep.png_note else 'without'} PNG) in "
          f"{rep.seconds:.0f} s; {agree} of {len(rep.checks)} checks agree with the paper, "
          f"{rep.n_differ} differ (see the report)")
    print(f"report: {rep.report}\nindex:  {rep.index}")
    if rep.png_note:
        print(f"no PNG pictures: {rep.png_note}")
    return 0
