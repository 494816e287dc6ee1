"""Speed of the array computations, each with its error (issue: arrays and sweeps).

    python benchmarks/bench_arrays.py [--quick] [--out DIR]

Reports medians over repeats (with min/max) for: one fixed-orientation array point
(beta fixed and self-consistent), a 72-point orientation sweep, and uniform arrays
with self-consistent beta at quadrature error <= 1e-3, with the error estimates and
beta residuals of the same runs. The uniform-array LRU caches are cleared before each
repeat so that every run computes from scratch.
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from model import REGIMES, SolverOptions, fixed_orientation, orientation_sweep, uniform_array
from model._kernel import warmup
from model.support import _simulate
from model.uniform import _uniform


def _clear():
    _simulate.cache_clear()
    _uniform.cache_clear()


def timed(fn, repeats):
    """Median, min and max seconds of ``fn()`` over ``repeats`` cold-cache runs, and its last value."""
    times, value = [], None
    for _ in range(repeats):
        _clear()
        start = time.perf_counter()
        value = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), max(times), value


def run(quick: bool):
    repeats = 3 if quick else 7
    theta72 = np.linspace(0, math.pi, 74)[1:-1]
    rows = []
    for name, p in REGIMES.items():
        p1 = p.replace(theta0=1.0)
        for beta in (1.0, "self"):
            med, lo, hi, r = timed(lambda: fixed_orientation(p1, beta=beta), repeats * 3)
            rows.append(dict(what="fixed point", regime=name, beta=str(beta), median_ms=med * 1e3,
                             min_ms=lo * 1e3, max_ms=hi * 1e3, error=abs(r.energy_residual),
                             error_kind="energy residual", beta_residual=r.beta_residual))
            med, lo, hi, s = timed(lambda: orientation_sweep(p, theta72, beta=beta), repeats)
            rows.append(dict(what="72-point sweep", regime=name, beta=str(beta), median_ms=med * 1e3,
                             min_ms=lo * 1e3, max_ms=hi * 1e3,
                             error=float(np.max(np.abs(s.contacts.energy_residual) / s.contacts.W)),
                             error_kind="max relative energy residual",
                             beta_residual=float(np.max(np.abs(s.beta_residual)))))
        med, lo, hi, u = timed(lambda: uniform_array(p, tol=1e-3), repeats)
        rows.append(dict(what="uniform array tol 1e-3", regime=name, beta="self",
                         median_ms=med * 1e3, min_ms=lo * 1e3, max_ms=hi * 1e3,
                         error=u.quadrature_error["FTx_over_mu0FN"],
                         error_kind="quadrature error estimate of F_T,x/(mu0 F_N)",
                         beta_residual=u.beta_residual, trajectories=u.stats["trajectories"],
                         members=u.n_members))
    return rows


def tolerance_costs(quick: bool) -> list:
    """Uniform-array cost against the quadrature tolerance (members, time, error estimate)
    and against the members' integration tolerance; the self-consistent beta's extra cost."""
    rows = []
    tols = (1e-2, 1e-3) if quick else (1e-2, 3e-3, 1e-3, 3e-4, 1e-4)
    for name in ("pendulum", "slider"):
        p = REGIMES[name]
        for tol in tols:
            for beta in (1.0, "self"):
                med, _, _, u = timed(lambda: uniform_array(p, tol=tol, beta=beta), 1 if quick else 3)
                rows.append(dict(regime=name, tol=tol, rtol=u.stats["rtol"], beta=str(beta),
                                 ms=med * 1e3, members=u.n_members,
                                 trajectories=u.stats["trajectories"],
                                 quad_error=u.quadrature_error["FTx_over_mu0FN"],
                                 integration_error=u.integration_error))
        for rtol in ((1e-4, 1e-6) if quick else (1e-4, 1e-5, 1e-6, 1e-7)):
            med, _, _, u = timed(lambda: uniform_array(p, tol=1e-3, rtol=rtol, beta=1.0),
                                 1 if quick else 3)
            rows.append(dict(regime=name, tol=1e-3, rtol=rtol, beta="1.0", ms=med * 1e3,
                             members=u.n_members, trajectories=u.stats["trajectories"],
                             quad_error=u.quadrature_error["FTx_over_mu0FN"],
                             integration_error=u.integration_error))
    return rows


def throughput() -> dict:
    """Orientation-sweep trajectories per second against single calls (Python loop)."""
    p = REGIMES["pendulum"]
    theta = np.linspace(0, math.pi, 202)[1:-1]
    med, _, _, _ = timed(lambda: orientation_sweep(p, theta, beta=1.0), 3)
    _clear()
    start = time.perf_counter()
    for t in theta:
        _simulate.__wrapped__(p.replace(theta0=float(t)), SolverOptions(), 0)
    single = time.perf_counter() - start
    return {"batch_per_s": theta.size / med, "single_per_s": theta.size / single}


def peak_rss_mb(code: str) -> float:
    """Peak resident memory (MB) of a fresh interpreter running ``code``."""
    script = code + "\nimport resource; print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)"
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True, timeout=900)
    return int(out.stdout.split()[-1]) / 1024


def memory(quick: bool) -> dict:
    n = 4 if quick else 12
    return {
        "uniform array (slider, self-consistent beta)": peak_rss_mb(
            "from model import REGIMES, uniform_array; uniform_array(REGIMES['slider'])"),
        f"regime map {n}x{n} (1 process)": peak_rss_mb(
            f"from model.sweeps import regime_map; regime_map(n={n})"),
        "import only (baseline)": peak_rss_mb("import model"),
    }


def report(rows) -> str:
    head = (f"# Array benchmarks\n\nmachine: {platform.processor() or platform.machine()}, "
            f"python {platform.python_version()}; medians over repeats, cold caches.\n\n"
            "| computation | regime | beta | median ms | min-max ms | error | beta residual |\n"
            "|---|---|---|---:|---|---|---:|\n")
    lines = [f"| {r['what']} | {r['regime']} | {r['beta']} | {r['median_ms']:.2f} | "
             f"{r['min_ms']:.2f}-{r['max_ms']:.2f} | {r['error']:.1e} ({r['error_kind']}) | "
             f"{abs(r['beta_residual']):.1e} |" for r in rows]
    return head + "\n".join(lines) + "\n"


def extra_report(costs, rates, mem) -> str:
    lines = ["", "## Uniform array cost against tolerance", "",
             "| regime | quadrature tol | member rtol | beta | ms | members | trajectories | "
             "quadrature error | integration error |", "|---|---|---|---|---:|---:|---:|---|---|"]
    lines += [f"| {c['regime']} | {c['tol']:g} | {c['rtol']:g} | {c['beta']} | {c['ms']:.1f} | "
              f"{c['members']} | {c['trajectories']} | {c['quad_error']:.1e} | "
              f"{c['integration_error']:.1e} |" for c in costs]
    lines += ["", f"Orientation sweep throughput (pendulum, 200 orientations): "
              f"{rates['batch_per_s']:.0f} trajectories/s in one batch vs "
              f"{rates['single_per_s']:.0f}/s through single calls.", "",
              "## Peak memory (fresh process)", "", "| computation | peak RSS MB |", "|---|---:|"]
    lines += [f"| {k} | {v:.0f} |" for k, v in mem.items()]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args()
    print(f"kernel ready in {warmup():.2f} s")
    rows = run(args.quick)
    costs = tolerance_costs(args.quick)
    rates = throughput()
    mem = memory(args.quick)
    text = report(rows) + extra_report(costs, rates, mem)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "arrays.md").write_text(text)
    (out / "arrays.json").write_text(json.dumps(
        {"timings": rows, "tolerance_costs": costs, "throughput": rates, "peak_rss_mb": mem},
        indent=1, default=float))
    print(text)


if __name__ == "__main__":
    main()
