"""Speed of the array computations, each with its error (issue: arrays and sweeps).

    python benchmarks/bench_arrays.py [--quick] [--out DIR]

Reports medians over repeats, each with its min and max, for: one fixed-orientation
array point (beta fixed and self-consistent), a 72-point orientation sweep, and uniform
arrays with self-consistent beta at quadrature error <= 1e-3, with the error estimates
and beta residuals of the same runs; the uniform-array cost against its tolerances;
batch against single-call throughput; peak memory; 24 x 24 regime maps at F_N = 0.1,
1, 3, 10 on 2 processes from an empty disk cache (one 8 x 8 map with --quick). Each run is repeated until about
0.2 s in all, at least 3 times (0.05 s and 1 time for the tolerance table in --quick).
The uniform-array LRU caches are cleared before each repeat so that every run computes
from scratch.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from model import REGIMES, fixed_orientation, orientation_sweep, simulate_support, uniform_array
from model._kernel import warmup
from model.contact.support import _simulate
from model.arrays.uniform import _uniform

from spread import cell, cold_runs


def _clear():
    _simulate.cache_clear()
    _uniform.cache_clear()


MIN_TOTAL = {False: 0.2, True: 0.05}  # seconds to repeat each run for (full, --quick)


def timed(fn, min_total, lo=3, hi=21):
    """Median, min, max seconds and run count of ``fn()`` over cold-cache runs, repeated
    until about ``min_total`` seconds in all and at least ``lo`` times; and its last value."""
    t, value = cold_runs(fn, _clear, min_total, lo, hi)
    return t["median"], t["min"], t["max"], t["n"], value


def run(quick: bool):
    total = MIN_TOTAL[quick]
    theta72 = np.linspace(0, math.pi, 74)[1:-1]
    rows = []
    for name, p in REGIMES.items():
        p1 = p.replace(theta0=1.0)
        for beta in (1.0, "self"):
            med, lo, hi, n, r = timed(lambda: fixed_orientation(p1, beta=beta), total)
            rows.append(dict(what="fixed point", regime=name, beta=str(beta), median_ms=med * 1e3,
                             min_ms=lo * 1e3, max_ms=hi * 1e3, runs=n, error=abs(r.energy_residual),
                             error_kind="energy residual", beta_residual=r.beta_residual))
            med, lo, hi, n, s = timed(lambda: orientation_sweep(p, theta72, beta=beta), total)
            rows.append(dict(what="72-point sweep", regime=name, beta=str(beta), median_ms=med * 1e3,
                             min_ms=lo * 1e3, max_ms=hi * 1e3, runs=n,
                             error=float(np.max(np.abs(s.contacts.energy_residual) / s.contacts.W)),
                             error_kind="max relative energy residual",
                             beta_residual=float(np.max(np.abs(s.beta_residual)))))
        med, lo, hi, n, u = timed(lambda: uniform_array(p, tol=1e-3), total)
        rows.append(dict(what="uniform array tol 1e-3", regime=name, beta="self",
                         median_ms=med * 1e3, min_ms=lo * 1e3, max_ms=hi * 1e3, runs=n,
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
    reps = dict(min_total=MIN_TOTAL[quick], lo=1 if quick else 3)
    for name in ("pendulum", "slider"):
        p = REGIMES[name]
        for tol in tols:
            for beta in (1.0, "self"):
                med, lo, hi, n, u = timed(lambda: uniform_array(p, tol=tol, beta=beta), **reps)
                rows.append(dict(regime=name, tol=tol, rtol=u.stats["rtol"], beta=str(beta),
                                 ms=med * 1e3, min_ms=lo * 1e3, max_ms=hi * 1e3, runs=n,
                                 members=u.n_members,
                                 trajectories=u.stats["trajectories"],
                                 quad_error=u.quadrature_error["FTx_over_mu0FN"],
                                 integration_error=u.integration_error))
        for rtol in ((1e-4, 1e-6) if quick else (1e-4, 1e-5, 1e-6, 1e-7)):
            med, lo, hi, n, u = timed(lambda: uniform_array(p, tol=1e-3, rtol=rtol, beta=1.0), **reps)
            rows.append(dict(regime=name, tol=1e-3, rtol=rtol, beta="1.0", ms=med * 1e3,
                             min_ms=lo * 1e3, max_ms=hi * 1e3, runs=n,
                             members=u.n_members, trajectories=u.stats["trajectories"],
                             quad_error=u.quadrature_error["FTx_over_mu0FN"],
                             integration_error=u.integration_error))
    return rows


def throughput(quick: bool) -> dict:
    """Orientation-sweep trajectories per second against single calls (Python loop):
    median, and min and max (from the slowest and the fastest run)."""
    p = REGIMES["pendulum"]
    theta = np.linspace(0, math.pi, 202)[1:-1]

    def singles():
        for t in theta:
            simulate_support(p.replace(theta0=float(t)), cache=False)

    out = {}
    for key, fn in (("batch", lambda: orientation_sweep(p, theta, beta=1.0)), ("single", singles)):
        med, lo, hi, n, _ = timed(fn, MIN_TOTAL[quick])
        out.update({f"{key}_per_s": theta.size / med, f"{key}_min_per_s": theta.size / hi,
                    f"{key}_max_per_s": theta.size / lo, f"{key}_runs": n})
    return out


def map_timings(quick: bool) -> list:
    """Regime maps (Fig. 5) on 2 processes with an empty disk cache: wall time to the
    coarse 8 x 8 subgrid and to the whole map, and the CPU seconds of all processes
    (``bench_map.one_map``)."""
    from bench_map import one_map

    n, loads = (8, (1.0,)) if quick else (24, (0.1, 1.0, 3.0, 10.0))
    return [one_map(F_N, n) for F_N in loads]


def peak_rss_mb(codes: dict) -> dict:
    """Peak resident memory (MB) of a fresh interpreter running each code string.

    Each gets an empty on-disk result cache (``MICROPILLAR_CACHE_DIR``), so that it
    computes rather than loads. The interpreters run side by side: a process's peak
    memory does not depend on the others, and nothing is timed meanwhile.
    """
    tail = "\nimport resource; print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)"
    out = {}
    with tempfile.TemporaryDirectory() as empty:
        procs = {name: subprocess.Popen(
            [sys.executable, "-c", code + tail], stdout=subprocess.PIPE, text=True,
            env={**os.environ, "MICROPILLAR_CACHE_DIR": str(Path(empty) / str(i))})
            for i, (name, code) in enumerate(codes.items())}
        for name, proc in procs.items():
            stdout, _ = proc.communicate(timeout=900)
            if proc.returncode:
                raise RuntimeError(f"peak memory of {name!r}: exit code {proc.returncode}")
            out[name] = int(stdout.split()[-1]) / 1024
    return out


def memory(quick: bool) -> dict:
    n = 4 if quick else 12
    return peak_rss_mb({
        "uniform array (slider, self-consistent beta)":
            "from model import REGIMES, uniform_array; uniform_array(REGIMES['slider'])",
        f"regime map {n}x{n} (1 process)": f"from model.runs.sweeps import regime_map; regime_map(n={n})",
        "import only (baseline)": "import model",
    })


def ms(v: float) -> str:
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


def report(rows) -> str:
    return (f"# Array benchmarks\n\nmachine: {platform.processor() or platform.machine()}, "
            f"python {platform.python_version()}; medians over repeats, cold caches.\n\n"
            + timings_table(rows))


def timings_table(rows) -> str:
    """The array computations: ms median [min–max] over cold-cache runs, with their errors."""
    head = ("| computation | regime | beta | ms median [min–max] | runs | error | beta residual |\n"
            "|---|---|---|---|---:|---|---:|\n")
    lines = [f"| {r['what']} | {r['regime']} | {r['beta']} | "
             f"{cell(r['median_ms'], r['min_ms'], r['max_ms'], ms)} | {r['runs']} | "
             f"{r['error']:.1e} ({r['error_kind']}) | {abs(r['beta_residual']):.1e} |" for r in rows]
    return head + "\n".join(lines) + "\n"


def map_report(maps) -> str:
    lines = ["", "## Regime maps (2 processes, empty disk cache, one run each)", "",
             "| F_N | grid | first 8x8 s | whole map s | CPU s (all processes) | succeeded | "
             "largest quadrature error |", "|---|---|---|---|---|---|---|"]
    lines += [f"| {m['F_N']:g} | {m['n']}x{m['n']} | "
              f"{'-' if m['coarse_s'] is None else format(m['coarse_s'], '.2f')} | "
              f"{m['wall_s']:.2f} | {m['cpu_s']:.1f} | {m['succeeded']}/{m['points']} | "
              f"{m['max_quadrature_error']:.1e} |" for m in maps]
    return "\n".join(lines) + "\n"


def extra_report(costs, rates, mem) -> str:
    lines = ["", "## Uniform array cost against tolerance", "",
             "| regime | quadrature tol | member rtol | beta | ms median [min–max] | runs | members | "
             "trajectories | quadrature error | integration error |",
             "|---|---|---|---|---|---:|---:|---:|---|---|"]
    lines += [f"| {c['regime']} | {c['tol']:g} | {c['rtol']:g} | {c['beta']} | "
              f"{cell(c['ms'], c['min_ms'], c['max_ms'], ms)} | {c['runs']} | "
              f"{c['members']} | {c['trajectories']} | {c['quad_error']:.1e} | "
              f"{c['integration_error']:.1e} |" for c in costs]
    rate = lambda k: cell(rates[f"{k}_per_s"], rates[f"{k}_min_per_s"], rates[f"{k}_max_per_s"],  # noqa: E731
                          lambda v: f"{v:.0f}")
    lines += ["", f"Orientation sweep throughput (pendulum, 200 orientations), median [min–max] "
              f"over {rates['batch_runs']} and {rates['single_runs']} runs: "
              f"{rate('batch')} trajectories/s in one batch vs {rate('single')}/s through "
              "single calls.", "",
              "## Peak memory (fresh process, empty disk cache)", "", "| computation | peak RSS MB |",
              "|---|---:|"]
    lines += [f"| {k} | {v:.0f} |" for k, v in mem.items()]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats (for CI)")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args()
    print(f"kernel ready in {warmup():.2f} s")
    phases, t = {}, time.perf_counter()
    rows = run(args.quick)
    phases["timings"], t = time.perf_counter() - t, time.perf_counter()
    costs = tolerance_costs(args.quick)
    phases["tolerance_costs"], t = time.perf_counter() - t, time.perf_counter()
    rates = throughput(args.quick)
    phases["throughput"], t = time.perf_counter() - t, time.perf_counter()
    mem = memory(args.quick)
    phases["peak_rss_mb (subprocesses)"], t = time.perf_counter() - t, time.perf_counter()
    maps = map_timings(args.quick)
    phases["regime maps"] = time.perf_counter() - t
    text = report(rows) + extra_report(costs, rates, mem) + map_report(maps)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "arrays.md").write_text(text)
    (out / "arrays.json").write_text(json.dumps(
        {"timings": rows, "tolerance_costs": costs, "throughput": rates, "peak_rss_mb": mem,
         "regime_maps": maps,
         "phases_wall_s": phases},
        indent=1, default=float))
    print(text)


if __name__ == "__main__":
    main()
