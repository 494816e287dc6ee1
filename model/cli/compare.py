"""``micropillar pillar ... --compare structured.csv``: the structured surface's friction
predicted at the speeds of a measured curve and compared with it
(``model.lab.friction_compare``): each speed's measured and predicted value, their difference
and the combined error, the RMS, and the speeds where they disagree."""
from __future__ import annotations

import json
import math
import sys

from ..lab.friction_compare import DEFAULT_MU_ERR, N_SIGMA, compare_friction, read_measured
from ..lab.friction_curve import CurveFileError, speed_factor
from . import speeds
from ._common import UsageError, jsonable, real


def add_arguments(group) -> None:
    group.add_argument("--compare", metavar="FILE.csv",
                       help="predict at the speeds of this measured curve of the structured "
                            "sample (columns 'v [unit]', 'mu', optional 'mu_err', as for "
                            "'friction fit') and compare (needs V_s; instead of --speeds)")
    group.add_argument("--v-unit", metavar="UNIT",
                       help="with --compare: unit of v when the file's header has none")
    group.add_argument("--mu-err", type=real, metavar="E",
                       help=f"with --compare: the measurement's standard error of mu when the "
                            f"file has no mu_err column (default {DEFAULT_MU_ERR:g})")


def check(args) -> None:
    """``UsageError`` for --v-unit/--mu-err without --compare, or --compare with --speeds."""
    if args.compare is None:
        for flag, value in (("--v-unit", args.v_unit), ("--mu-err", args.mu_err)):
            if value is not None:
                raise UsageError(flag, "only with --compare")
        return
    if args.speeds is not None or args.n is not None:
        raise UsageError("--compare", "computes at the measured speeds; give --compare or "
                                      "--speeds, not both")
    if args.mu_err is not None and not (math.isfinite(args.mu_err) and args.mu_err >= 0):
        raise UsageError("--mu-err", f"{args.mu_err!r} must be a finite standard error >= 0")


def measured(args):
    """The measured curve of --compare; ``UsageError`` naming the file's line."""
    try:
        if args.v_unit is not None:
            speed_factor(args.v_unit)
        return read_measured(args.compare, v_unit=args.v_unit)
    except CurveFileError as error:
        raise UsageError(None, str(error)) from None


_HEAD = (f"{'V0 [m/s]':>12}  {'measured':>9}  {'predicted':>9}  {'difference':>10}  "
         f"{'+- allowed':>10}")


def _row(c, i) -> str:
    def cell(x, spec):
        width = int("".join(ch for ch in spec.split(".")[0] if ch.isdigit()))
        return f"{'–':>{width}}" if math.isnan(x) else format(x, spec)

    flag = "  disagrees" if c.v[i] in c.disagree else ""
    return (f"{c.v[i]:>12.4g}  {cell(c.measured[i], '>9.5g')}  {cell(c.predicted[i], '>9.5g')}"
            f"  {cell(c.difference[i], '>+10.3g')}  {cell(c.tolerance[i], '>10.2g')}{flag}")


def run(args, design, distribution) -> int:
    """Predict at the measured speeds, compare, print; 0 if every speed was compared."""
    curve = measured(args)
    prediction = speeds.predict(args, design, distribution, curve.v,
                                on_point=speeds.progress(curve.n_points))
    if sys.stderr.isatty():
        print(file=sys.stderr)
    comparison = compare_friction(prediction, curve, mu_err=args.mu_err, n_sigma=N_SIGMA)
    if args.json:
        record = {"comparison": comparison.to_dict(), "prediction": prediction.to_dict()}
        print(json.dumps(jsonable(record)))
    else:
        print(f"Measured ({args.compare}) against predicted F_T,x/F_N of the structured "
              f"surface at the measured speeds")
        print(f"+- allowed: the model's quadrature error + {comparison.n_sigma:g} x the "
              f"measurement's {'mu_err' if comparison.mu_err_given else 'assumed mu_err'}")
        print(_HEAD)
        for i in range(len(comparison.v)):
            print(_row(comparison, i))
        print(f"\nrms difference {comparison.rms:.3g} over {comparison.n_compared} speeds")
        named = ", ".join(f"{s:.4g}" for s in comparison.disagree) or "none"
        print(f"disagree beyond the allowed error at V0 [m/s]: {named}")
        if not comparison.success:
            print(comparison.message)
    return 0 if comparison.success else 1
