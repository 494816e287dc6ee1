"""Batched throughput against the exit-state error it buys (one core, kernel only).

    python benchmarks/bench_throughput.py [--rtols 1e-4 1e-5 1e-6] [--repeats N]

200 pendulum orientations in one ``_kernel.integrate_batch`` call, method auto, atol =
rtol/100. For each rtol: trajectories per second, median [min–max] over repeated
calls, and the exit-state error (x, y, v_x, v_y, theta) against the same kernel at
rtol 1e-12 (median and max over the orientations), so that pairs of different order
can be compared at equal error. Prints the load average.
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


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rtols", type=float, nargs="+", default=[1e-4, 3e-5, 1e-5, 1e-6])
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    p = REGIMES["pendulum"]
    theta = np.linspace(0, math.pi, 202)[1:-1]
    Y0 = np.array([_kernel.initial_state(p.replace(theta0=float(t))) for t in theta])
    P = np.array([_kernel.pack(p.replace(theta0=float(t))) for t in theta])

    def run(rtol):
        return _kernel.integrate_batch(Y0, P, rtol, rtol / 100, 0, 1_000_000, 1e5, False)

    ref = run(1e-12)[2][:, :_kernel.N_MOTION]
    print(f"load average before: {Path('/proc/loadavg').read_text().split()[:3]}")
    for rtol in args.rtols:
        status, _, Y, _, stats, *_ = run(rtol)
        err = np.max(np.abs(Y[:, :_kernel.N_MOTION] - ref), axis=1)
        times = []
        for _ in range(args.repeats):
            start = time.perf_counter()
            run(rtol)
            times.append(time.perf_counter() - start)
        s = spread(times)
        rate = [theta.size / s[k] for k in ("median", "max", "min")]
        print(f"rtol {rtol:.0e}: {cell(*rate, lambda v: f'{v:,.0f}')} trajectories/s; exit-state "
              f"error median {np.median(err):.2g}, max {err.max():.2g}; mean n_rhs "
              f"{stats[:, _kernel.slots.ST_RHS].mean():.0f}; failed {int(np.sum(status != 0))}")
    print(f"load average after: {Path('/proc/loadavg').read_text().split()[:3]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
