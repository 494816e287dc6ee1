"""``python -m model reproduce --out DIR``: every figure's data computed, every finding
checked (see ``model.reproduce``); ``python -m app.reproduce`` adds the pictures.

Progress is drawn on stderr, one bar per stage; the summary (checks that agree and differ,
the files written) goes to stdout. Exit codes: 0 done (differences from the paper are
results, not failures), 2 bad usage, 130 interrupted.
"""
from __future__ import annotations

import sys

from ._common import PROG, UsageError, output_folder, whole
from .sweep import ProgressBar


def add_command(commands) -> None:
    p = commands.add_parser(
        "reproduce", help="compute every figure of the paper as CSV and check its findings",
        description="Compute the data of Figs. 3, 5a/b, 6, 7a/b, 8a/b, 10a-f and 11a-c of "
                    "the paper as CSV files, and write report.md and index.html checking the "
                    "paper's findings against the computed numbers. Uniform-array points are "
                    "kept in the on-disk cache, so a second run is quick. The pictures (HTML, "
                    "PNG): python -m app.reproduce with the same flags.")
    add_arguments(p)
    p.set_defaults(run=run)


def add_arguments(p) -> None:
    """``--out``, ``--resolution`` and ``--workers``."""
    p.add_argument("--out", required=True, metavar="DIR",
                   help="folder to write into (created if missing)")
    p.add_argument("--resolution", choices=("full", "coarse"), default="full",
                   help="full: the figures as published (default; 1-5 min on 2 cores, less "
                        "with a warm cache); coarse: a quick check of the pipeline")
    p.add_argument("--workers", type=whole, default=2, metavar="N",
                   help="processes for the uniform-array sweeps (default 2)")


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


def run(args, draw=None) -> int:
    """Run it; ``draw`` as in ``model.reproduce.reproduce`` (None: tables and report only)."""
    from ..reproduce import reproduce

    if args.workers < 1:
        raise UsageError("--workers", f"{args.workers} must be at least 1")
    out = output_folder("--out", args.out)
    progress = StageProgress(sys.stderr)
    try:
        rep = reproduce(out, resolution=args.resolution, workers=args.workers,
                        progress=progress, draw=draw)
    except KeyboardInterrupt:
        progress.close()
        print(f"{PROG} reproduce: interrupted; {out} is incomplete", file=sys.stderr)
        return 130
    except OSError as error:
        progress.close()
        raise UsageError("--out", f"cannot write into {str(out)!r}: {error}") from None
    except RuntimeError as error:  # pictures required but impossible
        progress.close()
        raise UsageError("--png", str(error)) from None
    progress.close()
    agree = len(rep.checks) - rep.n_differ
    pictures = sum(f.png is not None for f in rep.figures)
    print(f"{len(rep.figures)} figures ({pictures} with PNG) in {rep.seconds:.0f} s; "
          f"{agree} of {len(rep.checks)} checks agree with the paper, {rep.n_differ} differ "
          "(see the report)")
    print(f"report: {rep.report}\nindex:  {rep.index}")
    if rep.png_note:
        print(f"pictures missing: {rep.png_note}")
    return 0
