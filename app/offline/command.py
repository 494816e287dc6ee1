"""``micropillar pack --out explorer.html``: the offline explorer, one self-contained HTML
file that computes in the browser (docs/offline.md).

The command is the app's (the page is drawn with Bokeh): ``model``'s command line finds it
through the ``micropillar.commands`` entry point declared in pyproject.toml, so ``model``
imports no plotting code. Exit codes: 0 written, 2 bad usage
(the folder of ``--out`` does not exist, or the file cannot be written).
"""
from __future__ import annotations

from pathlib import Path

from model.cli._common import UsageError

from .pack import write


def add_command(commands) -> None:
    p = commands.add_parser(
        "pack", help="write the offline explorer: one HTML file, no server, no network",
        description="Write the explorer as one self-contained HTML file (BokehJS inlined, the "
                    "model ported to JavaScript): it opens from a file on any browser, with "
                    "no Python, no server and no network, and recomputes as the sliders move. "
                    "Links carry the state after '#': explorer.html#k_r=3&k_theta=0.01&F_N=1"
                    "&theta0_deg=90.")
    p.add_argument("--out", required=True, metavar="FILE",
                   help="the HTML file to write (its folder must exist)")
    p.set_defaults(run=run)


def run(args) -> int:
    out = Path(args.out)
    if out.is_dir():
        raise UsageError("--out", f"{args.out} is a folder; give a file name such as "
                         f"{out / 'explorer.html'}")
    if not out.parent.is_dir():
        raise UsageError("--out", f"the folder {out.parent} of {args.out} does not exist; create it "
                         f"or choose another")
    try:
        size = write(out)
    except OSError as error:
        raise UsageError("--out", f"cannot write {args.out} ({error.strerror})") from None
    print(f"wrote {out} ({size / 1e6:.1f} MB): open it in a browser, no server needed")
    return 0
