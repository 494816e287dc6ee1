"""Command line: the animation of one support or of the array as GIF or MP4, for slides.

    python -m app.animate --what support|array --format gif|mp4 --frames N --size WxH
        --out FILE [--regime NAME] [--k-r K] [--k-theta K] [--F-N F] [--theta0-deg DEG]
        [--fps FPS] [--orientation uniform|fixed] [--supports N]

Springs and load start from ``--regime`` (default pendulum); theta0 is in degrees. Bad
input ends with a message naming the value and exit status 2; a computation that fails
ends with status 1.
"""
from __future__ import annotations

import argparse
import re
import sys

from model import REGIMES

from .animation_export import (FORMATS, FPS_RANGE, FRAMES_RANGE, WHAT, check_request,
                               export_animation, main_params)


def _size(text: str):
    match = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", text)
    if not match:
        raise argparse.ArgumentTypeError(f"{text!r} is not WIDTHxHEIGHT in pixels (e.g. 960x540)")
    return int(match.group(1)), int(match.group(2))


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def _whole(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m app.animate", description=__doc__.split("\n")[0])
    p.add_argument("--what", choices=WHAT, required=True, help="one support or the array")
    p.add_argument("--format", choices=FORMATS, default=None,
                   help="gif or mp4 (default: from the extension of --out)")
    p.add_argument("--frames", type=_whole, default=120,
                   help=f"number of frames, {FRAMES_RANGE[0]}..{FRAMES_RANGE[1]} (default 120)")
    p.add_argument("--size", type=_size, default=(960, 540), help="WIDTHxHEIGHT px (default 960x540)")
    p.add_argument("--out", required=True, help="output file (.gif or .mp4)")
    p.add_argument("--fps", type=_number, default=20.0,
                   help=f"frames per second, {FPS_RANGE[0]}..{FPS_RANGE[1]} (default 20)")
    p.add_argument("--regime", choices=sorted(REGIMES), default="pendulum")
    p.add_argument("--k-r", type=_number, default=None, help="radial stiffness k_r")
    p.add_argument("--k-theta", type=_number, default=None, help="torsional stiffness k_theta")
    p.add_argument("--F-N", dest="F_N", type=_number, default=None, help="normal load F_N")
    p.add_argument("--theta0-deg", type=_number, default=None,
                   help="rest orientation theta0 in degrees (the support; a fixed array)")
    p.add_argument("--orientation", choices=("uniform", "fixed"), default="uniform",
                   help="the array's orientations (default uniform)")
    p.add_argument("--supports", type=_whole, default=100, help="the array's size (default 100)")
    return p


def main(argv=None) -> int:
    p = parser()
    args = p.parse_args(argv)  # exits 2 with a message on malformed input
    fmt = args.format
    suffix = args.out.rsplit(".", 1)[-1].lower() if "." in args.out else ""
    if fmt is None:
        if suffix not in FORMATS:
            p.error(f"--out {args.out!r}: give --format gif|mp4 or end the name in .gif or .mp4")
        fmt = suffix
    elif suffix in FORMATS and suffix != fmt:
        p.error(f"--out {args.out!r} ends in .{suffix} but --format is {fmt}")
    try:
        check_request(args.what, fmt, args.frames, args.size, args.fps)
        params = main_params(args.k_r, args.k_theta, args.F_N, args.theta0_deg, args.regime)
        if not 1 <= args.supports <= 2000:
            raise ValueError(f"--supports {args.supports} must be in 1..2000")
        result = export_animation(args.what, fmt, args.out, params, frames=args.frames,
                                  size=args.size, fps=args.fps, orientation=args.orientation,
                                  n_supports=args.supports)
    except ValueError as error:
        p.error(str(error))
    if not result.success:
        print(f"error: {result.message}", file=sys.stderr)
        return 1
    print(f"{result.path}: {result.message} ({result.seconds:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
