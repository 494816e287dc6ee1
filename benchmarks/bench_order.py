"""The explicit pairs side by side: cost against exit-state error, to place DOP853_RTOL.

    python benchmarks/bench_order.py [--rtols 1e-4 1e-5 1e-6 1e-7] [--n 48] [--no-time]

For each regime (``REGIMES``; n orientations theta0 in (0, 2 pi), method auto, atol =
rtol/100) and each explicit pair (Dormand-Prince 5(4) and DOP853, forced through
``driver.integrate``'s ``high`` flag whatever the rtol): the exit-state error (x, y, v_x,
v_y, theta) against the kernel at rtol 1e-12 (median and max over the orientations), the
mean right-hand-side evaluations and the time per trajectory (median [min-max] over
repeats; one Python call per trajectory, the same for both pairs). The pair to use at a
requested rtol is the one with the lower cost at the error the other reaches there.
Prints the load average.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np


from model import REGIMES
from model import _kernel

from spread import cell, spread

S = _kernel.slots


def run(Y0, P, rtol, high):
    out = [_kernel.integrate(Y0[i], P[i], rtol, rtol / 100, 0, 1_000_000, 1e5, False, high)
           for i in range(Y0.shape[0])]
    status = np.array([o[0] for o in out])
    Y = np.array([o[2] for o in out])
    n_rhs = np.array([o[3][S.ST_RHS] for o in out])
    return status, Y, n_rhs


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtols", type=float, nargs="+", default=[1e-4, 3e-5, 1e-5, 3e-6, 1e-6,
                                                                3e-7, 1e-7])
    ap.add_argument("--n", type=int, default=48)
    ap.add_argument("--regimes", nargs="+", default=list(REGIMES))
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--no-time", action="store_true", help="errors and RHS counts only")
    args = ap.parse_args(argv)
    print(f"load average before: {Path('/proc/loadavg').read_text().split()[:3]}")
    for name in args.regimes:
        p = REGIMES[name]
        theta = np.linspace(0, 2 * math.pi, args.n, endpoint=False) + math.pi / args.n
        Y0 = np.array([_kernel.initial_state(p.replace(theta0=float(t))) for t in theta])
        P = np.array([_kernel.pack(p.replace(theta0=float(t))) for t in theta])
        ref = run(Y0, P, 1e-12, True)[1][:, :S.N_MOTION]
        print(f"{name} ({args.n} orientations)")
        for rtol in args.rtols:
            line = f"  rtol {rtol:.0e}"
            for high, label in ((False, "DP5"), (True, "DOP853")):
                status, Y, n_rhs = run(Y0, P, rtol, high)
                err = np.max(np.abs(Y[:, :S.N_MOTION] - ref), axis=1)
                line += (f" | {label}: err median {np.median(err):.1e} max {err.max():.1e}, "
                         f"n_rhs {n_rhs.mean():.0f}")
                if not args.no_time:
                    times = []
                    for _ in range(args.repeats):
                        start = time.perf_counter()
                        run(Y0, P, rtol, high)
                        times.append((time.perf_counter() - start) / args.n * 1e6)
                    s = spread(times)
                    line += f", {cell(s['median'], s['min'], s['max'])} us"
                if np.any(status != 0):
                    line += f", failed {int(np.sum(status != 0))}"
            print(line, flush=True)
    print(f"load average after: {Path('/proc/loadavg').read_text().split()[:3]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
