"""Speed of the regime map (Fig. 5) on 2 processes from empty caches, with its error.

    python benchmarks/bench_map.py [--quick] [--runs N] [--out DIR]

Times the 24 x 24 map (tol 1e-3, self-consistent beta) at F_N = 0.1, 1, 3 and 10, ``--runs``
times at F_N = 3 (median [min–max]) and once at the other loads; each run gets an empty
disk cache (``MICROPILLAR_CACHE_DIR`` pointed at a new temporary folder) and a new process
pool, and the uniform-array LRU cache of the calling process is cleared. Each map reports
the time to its first complete 8 x 8 picture (the coarse phase, ``coarse=``), to the whole
map, the CPU seconds of all processes, the points that succeeded, the largest quadrature
error estimate of F_T,x/(mu0 F_N) and the largest |beta residual|. A separate 8 x 8 map at
F_N = 3 is the dashboard's first picture at a load without a shipped map. ``--quick``: one
12 x 12 map at F_N = 3 and the 8 x 8 (for CI).
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from model._kernel import warmup
from model.runs.sweeps import regime_map
from model.arrays.uniform import _uniform


def _cpu() -> float:
    return sum(resource.getrusage(w).ru_utime + resource.getrusage(w).ru_stime
               for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


def one_map(F_N: float, n: int, workers: int = 2) -> dict:
    """One regime map from empty caches: wall and CPU seconds, coarse phase, errors."""
    _uniform.cache_clear()
    old = os.environ.get("MICROPILLAR_CACHE_DIR")
    coarse = {}
    with tempfile.TemporaryDirectory() as empty:
        os.environ["MICROPILLAR_CACHE_DIR"] = empty
        cpu0, start = _cpu(), time.perf_counter()
        try:
            r = regime_map(n=n, F_N=F_N, tol=1e-3, workers=workers,
                           coarse=lambda s: coarse.setdefault("s", time.perf_counter() - start))
        finally:
            if old is None:
                os.environ.pop("MICROPILLAR_CACHE_DIR")
            else:
                os.environ["MICROPILLAR_CACHE_DIR"] = old
        wall, cpu = time.perf_counter() - start, _cpu() - cpu0
    beta, nc = r.columns["beta"], r.columns["Nc_over_Nc0"]
    free = beta < 1.0  # beta capped at 1 keeps its negative residual by definition
    residual = np.abs(beta - 1.0 / nc)[free]  # G = beta - L0/<tau_out> = beta - N_c0/N_c
    return dict(F_N=F_N, n=n, workers=workers, wall_s=wall, coarse_s=coarse.get("s"), cpu_s=cpu,
                succeeded=int(np.sum(r.columns["success"])), points=len(r),
                max_quadrature_error=float(np.max(r.columns["quadrature_error_FTx"])),
                max_beta_residual=float(residual.max()) if residual.size else 0.0)


def summary(runs: list) -> dict:
    """Median, min and max of the wall and coarse-phase seconds over ``runs``."""
    out = dict(runs[0], runs=len(runs))
    for key in ("wall_s", "coarse_s", "cpu_s"):
        values = [r[key] for r in runs if r[key] is not None]
        if values:
            out.update({key: statistics.median(values), f"{key}_min": min(values),
                        f"{key}_max": max(values)})
    for key in ("max_quadrature_error", "max_beta_residual"):
        out[key] = max(r[key] for r in runs)
    out["succeeded"] = min(r["succeeded"] for r in runs)
    return out


def _cell(row, key) -> str:
    if row.get(key) is None:
        return "-"
    if row["runs"] == 1:
        return f"{row[key]:.2f}"
    return f"{row[key]:.2f} [{row[key + '_min']:.2f}–{row[key + '_max']:.2f}]"


def report(rows) -> str:
    lines = ["# Regime map benchmark", "",
             f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
             f"python {platform.python_version()}; 2 processes, empty caches; "
             "median [min–max] where there are several runs.", "",
             "| F_N | grid | runs | first 8x8 s | whole map s | CPU s | succeeded | "
             "largest quadrature error | largest abs beta residual |",
             "|---|---|---:|---|---|---|---|---|---|"]
    lines += [f"| {r['F_N']:g} | {r['n']}x{r['n']} | {r['runs']} | "
              f"{_cell(r, 'coarse_s') if r['n'] > 8 else _cell(r, 'wall_s')} | "
              f"{_cell(r, 'wall_s')} | {_cell(r, 'cpu_s')} | {r['succeeded']}/{r['points']} | "
              f"{r['max_quadrature_error']:.1e} | {r['max_beta_residual']:.1e} |" for r in rows]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one 12x12 and one 8x8 map (for CI)")
    ap.add_argument("--runs", type=int, default=3, help="runs of the 24x24 map at F_N = 3")
    ap.add_argument("--out", default="bench-out", help="output folder (default bench-out)")
    args = ap.parse_args()
    print(f"kernel ready in {warmup():.2f} s")
    plan = [(3.0, 12, 1)] if args.quick else [
        (0.1, 24, 1), (1.0, 24, 1), (3.0, 24, max(1, args.runs)), (10.0, 24, 1)]
    plan.append((3.0, 8, 1 if args.quick else max(1, args.runs)))
    rows = [summary([one_map(F_N, n) for _ in range(runs)]) for F_N, n, runs in plan]
    text = report(rows)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "map.md").write_text(text)
    (out / "map.json").write_text(json.dumps({"maps": rows}, indent=1, default=float))
    print(text)


if __name__ == "__main__":
    main()
