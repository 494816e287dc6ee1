"""``micropillar pillar ... --speeds 0.1mm/s..1m/s --n 30``: the structured surface's
friction against sliding speed beside the flat material's mu(V0) (``model.lab.speed_curve``),
each row printed as its speed finishes."""
from __future__ import annotations

import json
import math
import sys

from ..lab.speed_curve import check_own_V_s, friction_velocity, parse_speeds, speed_range
from ._common import UsageError, fmt, jsonable, whole

#: Default number of speeds of --speeds.
N_SPEEDS = 30
#: Default local processes of --speeds and --compare: the speeds are independent, and
#: two cores halve a long curve's time (one process: --workers 1).
N_WORKERS = 2


def add_arguments(group) -> None:
    group.add_argument("--speeds", metavar="LO..HI",
                       help="friction against sliding speed V0 over this range, e.g. "
                            "'0.1mm/s..1m/s' (the design's V0 is replaced; needs V_s)")
    group.add_argument("--n", type=whole, default=None, metavar="N",
                       help=f"with --speeds: speeds, evenly spaced in log (default {N_SPEEDS})")
    group.add_argument("--workers", type=whole, default=None, metavar="N",
                       help=f"with --speeds or --compare: local processes computing the speeds "
                            f"(default {N_WORKERS})")


def speeds(args):
    """The speeds (m/s) of --speeds and --n, or None without --speeds."""
    if args.speeds is None:
        if args.n is not None:
            raise UsageError("--n", "only with --speeds")
        if args.workers is not None and getattr(args, "compare", None) is None:
            raise UsageError("--workers", "only with --speeds or --compare")
        return None
    if args.workers is not None and args.workers < 1:
        raise UsageError("--workers", f"{args.workers} must be at least 1")
    try:
        lo, hi = parse_speeds(args.speeds)
        return speed_range(lo, hi, N_SPEEDS if args.n is None else args.n)
    except ValueError as error:
        raise UsageError("--n" if str(error).startswith("n=") else "--speeds", str(error)) from None


_HEAD = f"{'V0 [m/s]':>12}  {'mu flat':>10}  {'F_T,x/F_N':>10}  {'+-':>8}  {'energy':>8}  status"


def _row(p) -> str:
    value = "–" if math.isnan(p.mu_apparent) else f"{p.mu_apparent:.6g}"
    error = "–" if math.isnan(p.quadrature_error) else f"{p.quadrature_error:.2g}"
    energy = "–" if math.isnan(p.integration_error) else f"{p.integration_error:.2g}"
    text = f"{p.V0:>12.4g}  {p.mu_flat:>10.6g}  {value:>10}  {error:>8}  {energy:>8}  {p.status}"
    return text if p.success else f"{text}: {p.message}"


def predict(args, design, distribution, values, on_point=None):
    """The design's friction-velocity curve at ``values`` (m/s); ``UsageError`` naming the
    flag of a bad input."""
    check_own_V_s_flag(design)
    try:
        return friction_velocity(design, values, distribution, beta=args.beta,
                                 tol=1e-3 if args.tol is None else args.tol,
                                 budget=args.budget, on_point=on_point,
                                 workers=N_WORKERS if args.workers is None else args.workers)
    except ValueError as error:
        flag = {"V_s": "--V-s", "tol": "--tol", "beta": "--beta", "budget": "--budget",
                "workers": "--workers"}
        name = str(error).split("=", 1)[0]
        raise UsageError(flag.get(name), str(error)) from None


def progress(total: int):
    """``on_point`` that counts finished speeds on a terminal's stderr."""
    done = [0]

    def show(i, point):
        done[0] += 1
        if sys.stderr.isatty():
            print(f"\r{done[0]}/{total} speeds", end="", file=sys.stderr, flush=True)
    return show


def in_order(emit):
    """``on_point`` that calls ``emit(point)`` in increasing speed, each as soon as every
    slower speed has finished (the speeds finish in any order on several processes)."""
    waiting, following = {}, [0]

    def show(i, point):
        waiting[i] = point
        while following[0] in waiting:
            emit(waiting.pop(following[0]))
            following[0] += 1
    return show


def run(args, design, distribution, values) -> int:
    """The curve, printed row by row (or as one JSON object); 0 if every speed succeeded."""
    if not args.json:
        check_own_V_s_flag(design)
        law = design.friction_law
        print(f"Friction against sliding speed (F_T,x/F_N of the structured surface, mu of "
              f"the flat material; Eq. 4 with mu_s {fmt(law.mu_s)}, A {fmt(law.A)}, "
              f"B {fmt(law.B)}, V_s {fmt(law.V_s)} m/s)")
        print("+- quadrature error of F_T,x/F_N; energy: relative energy-balance residual")
        print(_HEAD, flush=True)
    show = progress(len(values)) if args.json else in_order(
        lambda point: print(_row(point), flush=True))
    curve = predict(args, design, distribution, values, on_point=show)
    if args.json:
        if sys.stderr.isatty():
            print(file=sys.stderr)
        print(json.dumps(jsonable(curve.to_dict())))
    return 0 if curve.success else 1


def check_own_V_s_flag(design) -> None:
    """``UsageError`` naming --V-s unless the design's law has its own V_s."""
    try:
        check_own_V_s(design)
    except ValueError as error:
        raise UsageError("--V-s", f"{error} (--V-s or --friction)") from None
