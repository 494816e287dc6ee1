"""Cost of the compiled kernel at a fixed exit-state error, and batched throughput.

    python benchmarks/bench_kernel.py [--out DIR] [--repeats N]

For each case the kernel (``_kernel.integrate_batch`` on one row, method auto, atol =
rtol/100) runs over a fine rtol sweep (four per decade); its exit state (x, y, v_x, v_y,
theta) is compared with a DOP853 reference at rtol 1e-13 (cached in
DIR/kernel_reference.json). The time, the RHS evaluations and the step counts at the
target error are log-log interpolated between the two sweep points around the first
crossing of the target. Times are medians [min–max] over repeated loops. Also: batched
throughput of 200 pendulum orientations (rtol 1e-6) through the kernel alone and
through ``orientation_sweep`` (beta = 1), trajectories per second on one core, and
the per-call time of the Python wrapper of one support. Prints the load average.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np


from model import REGIMES, Params, simulate_support
from model import _kernel
from model.arrays.fixed import orientation_sweep

from spread import cell, spread

CASES = {"pendulum pi/2": (REGIMES["pendulum"], 1e-6),
         "hard F_N=10": (Params(k_r=0.01, k_theta=0.01, F_N=10, theta0=math.pi / 2), 1e-5)}
RTOLS = [10.0 ** (-k / 4) for k in range(14, 39)]  # 3.2e-4 ... 1e-9.5
S = _kernel.slots


def high(rtol) -> bool:
    """True when the kernel's explicit pair at ``rtol`` is DOP853."""
    return rtol <= getattr(_kernel, "DOP853_RTOL", 0.0)


def load() -> str:
    return Path("/proc/loadavg").read_text().split(" ", 3)[:3].__str__()


def reference(name, params, cache_file: Path) -> dict:
    cache = json.loads(cache_file.read_text()) if cache_file.exists() else {}
    key = f"{name} | {json.dumps(params.as_dict(), sort_keys=True)}"
    if key not in cache:
        res = simulate_support(params, rtol=1e-13, atol=1e-15, method="reference",
                               max_steps=2_000_000)
        cache[key] = {"t_out": res.t_out, "state_out": [float(v) for v in res.state_out]}
        cache_file.write_text(json.dumps(cache, indent=1))
    return cache[key]


def timed(fn, repeats: int, min_loop=0.02) -> dict:
    start = time.perf_counter()
    fn()
    one = time.perf_counter() - start
    n = max(1, math.ceil(min_loop / max(one, 1e-9)))
    out = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(n):
            fn()
        out.append((time.perf_counter() - start) / n)
    return spread(out)


def sweep(params, ref, repeats) -> list:
    Y0, P = _kernel.initial_state(params)[None], _kernel.pack(params)[None]
    rows = []
    for rtol in RTOLS:
        def call(rtol=rtol):
            return _kernel.integrate_batch(Y0, P, rtol, rtol / 100, 0, 1_000_000, 1e5, False)
        status, t, Y, D, st, *_ = call()
        err = float(np.max(np.abs(Y[0, :S.N_MOTION] - ref["state_out"])))
        t_s = timed(call, repeats)
        rows.append(dict(rtol=rtol, ok=int(status[0]) == 0, error=err, us=t_s["median"] * 1e6,
                         min_us=t_s["min"] * 1e6, max_us=t_s["max"] * 1e6,
                         n_rhs=int(st[0, S.ST_RHS]), n_acc=int(st[0, S.ST_ACC]),
                         n_rej=int(st[0, S.ST_REJ]), n_impl=int(st[0, S.ST_ACC_IMPL]),
                         rel_energy=abs(float(D[0, 4])) / max(abs(float(Y[0, S.W])), 1e-300)))
    return rows


def at_error(rows, target, key):
    """``key`` at the target error: log-log interpolated between the sweep points around its
    first crossing, or the first point below it when the explicit pair changes between the
    two (``_kernel.DOP853_RTOL``: no interpolation across the switch)."""
    for i, r in enumerate(rows):
        if r["ok"] and r["error"] <= target:
            if i == 0 or high(rows[i - 1]["rtol"]) != high(r["rtol"]):
                return r[key]
            p = rows[i - 1]
            f = math.log(p["error"] / target) / math.log(p["error"] / r["error"])
            return math.exp(math.log(p[key]) + f * math.log(max(r[key], 1e-300) / max(p[key], 1e-300)))
    return None


def throughput(repeats) -> dict:
    p = REGIMES["pendulum"]
    theta = np.linspace(0, math.pi, 202)[1:-1]
    Y0 = np.array([_kernel.initial_state(p.replace(theta0=float(t))) for t in theta])
    P = np.array([_kernel.pack(p.replace(theta0=float(t))) for t in theta])
    kern = timed(lambda: _kernel.integrate_batch(Y0, P, 1e-6, 1e-8, 0, 1_000_000, 1e5, False),
                 repeats, min_loop=0.05)
    sweep_ = timed(lambda: orientation_sweep(p, theta, beta=1.0), repeats, min_loop=0.05)
    single = timed(lambda: simulate_support(p, cache=False), repeats)
    return {"kernel_per_s": [theta.size / kern[k] for k in ("median", "max", "min")],
            "orientation_sweep_per_s": [theta.size / sweep_[k] for k in ("median", "max", "min")],
            "single_call_us": [single[k] * 1e6 for k in ("median", "min", "max")]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("bench-out"))
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--table", action="store_true", help="print every sweep row")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    _kernel.warmup()
    print(f"load average before: {load()}")
    results = {}
    for name, (params, target) in CASES.items():
        ref = reference(name, params, args.out / "kernel_reference.json")
        rows = sweep(params, ref, args.repeats)
        at = {k: at_error(rows, target, k) for k in ("us", "min_us", "max_us", "n_rhs", "n_acc",
                                                     "n_rej", "rtol")}
        results[name] = {"target": target, "at_target": at, "rows": rows}
        print(f"{name}: at error {target:g}: {cell(at['us'], at['min_us'], at['max_us'])} us, "
              f"rtol {at['rtol']:.2g}, n_rhs {at['n_rhs']:.0f}, steps {at['n_acc']:.0f} "
              f"+ {at['n_rej']:.0f} rejected")
        if args.table:
            for r in rows:
                print(f"  rtol {r['rtol']:.2e} err {r['error']:.2e} err/rtol {r['error'] / r['rtol']:6.2f} "
                      f"{cell(r['us'], r['min_us'], r['max_us'])} us n_rhs {r['n_rhs']} acc {r['n_acc']} "
                      f"rej {r['n_rej']} impl {r['n_impl']} rel_energy {r['rel_energy']:.1e}")
    tp = throughput(args.repeats)
    results["throughput"] = tp
    fmt = lambda v: f"{v:,.0f}"  # noqa: E731
    print(f"throughput, 200 pendulum orientations, rtol 1e-6: kernel {cell(*tp['kernel_per_s'], fmt)}"
          f" /s; orientation_sweep(beta=1) {cell(*tp['orientation_sweep_per_s'], fmt)} /s; "
          f"one simulate_support call (uncached) {cell(*tp['single_call_us'])} us")
    print(f"load average after: {load()}")
    (args.out / "kernel.json").write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
