"""``python -m app.reproduce --out DIR [--png | --no-png | --format png|svg|pdf ...]``:
``python -m model reproduce`` with the figures drawn as HTML and PNG, or the formats
asked for (see ``app.reproduce``). Exit codes as there."""
import sys
from functools import partial

from model.cli import UsageError
from model.cli._common import CommandParser
from model.cli.reproduce import add_arguments, run

from . import FORMATS, draw
from .render import browser_problem

PROG = "python -m app.reproduce"


def main(argv=None) -> int:
    parser = CommandParser(prog=PROG, description="Regenerate every figure of the paper "
                           "(HTML, PNG, CSV) and check its findings (report.md, index.html).")
    add_arguments(parser)
    png = parser.add_mutually_exclusive_group()
    png.add_argument("--png", dest="png", action="store_const", const=True, default="auto",
                     help="require PNG pictures (fail without Chromium and Playwright)")
    png.add_argument("--no-png", dest="png", action="store_const", const=False,
                     help="skip the PNG pictures")
    png.add_argument("--format", dest="formats", action="append", choices=FORMATS,
                     help="make exactly these pictures (repeat for several, e.g. --format svg "
                          "--format pdf): svg and pdf are vector graphics for papers; fails "
                          "without Chromium and Playwright")
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:
        return stop.code if isinstance(stop.code, int) else 2
    if args.formats and browser_problem():  # before minutes of computing
        print(f"{PROG}: error: --format: {'/'.join(args.formats)} pictures cannot be made: "
              f"{browser_problem()}", file=sys.stderr)
        return 2
    try:
        return run(args, draw=partial(draw, png=args.png, formats=args.formats))
    except UsageError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
