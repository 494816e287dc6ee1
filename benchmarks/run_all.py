"""Run the three benchmarks one after the other and report the total time.

    python benchmarks/run_all.py [--quick] [--out DIR] [--no-browser] [--only SCRIPT ...]

Runs bench_support.py, bench_arrays.py and bench_dashboard.py in turn (never side by
side: they time things), each in its own interpreter with the repository on the path,
writing to DIR (default bench-out). Prints, and writes to DIR/run_all.json, each
script's wall time and CPU time (user + sys of the script and its child processes) and
the machine's load average before and after: on a shared machine the wall time grows
with the other load, the CPU time much less. Exits non-zero if any script failed.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ("bench_support.py", "bench_arrays.py", "bench_dashboard.py")


def children_cpu() -> float:
    """CPU seconds (user + sys) of the finished child processes so far."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="each script's --quick mode (as in the tests)")
    ap.add_argument("--out", type=Path, default=Path("bench-out"), help="output folder (default bench-out)")
    ap.add_argument("--no-browser", action="store_true", help="dashboard: server-side part only")
    ap.add_argument("--only", nargs="+", choices=SCRIPTS, default=SCRIPTS, metavar="SCRIPT",
                    help=f"run only these of {', '.join(SCRIPTS)}")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])}
    runs, load_before = {}, os.getloadavg()
    t0, c0 = time.perf_counter(), children_cpu()
    for script in (s for s in SCRIPTS if s in args.only):
        cmd = [sys.executable, str(ROOT / "benchmarks" / script), "--out", str(args.out)]
        if args.quick:
            cmd.append("--quick")
        if args.no_browser and script == "bench_dashboard.py":
            cmd.append("--no-browser")
        print(f"\n=== {' '.join(cmd[1:])}", flush=True)
        start, cpu = time.perf_counter(), children_cpu()
        code = subprocess.run(cmd, cwd=ROOT, env=env).returncode
        runs[script] = {"wall_s": time.perf_counter() - start, "cpu_s": children_cpu() - cpu,
                        "returncode": code}
    total = {"wall_s": time.perf_counter() - t0, "cpu_s": children_cpu() - c0}
    load_after = os.getloadavg()
    summary = {"mode": "quick" if args.quick else "full", "cores": os.cpu_count(), "scripts": runs,
               "total": total, "loadavg_1_5_15_before": load_before, "loadavg_1_5_15_after": load_after}
    (args.out / "run_all.json").write_text(json.dumps(summary, indent=1))
    print(f"\n{'script':<20} {'wall s':>8} {'CPU s':>8}  exit")
    for script, r in runs.items():
        print(f"{script:<20} {r['wall_s']:8.1f} {r['cpu_s']:8.1f}  {r['returncode']}")
    print(f"{'total':<20} {total['wall_s']:8.1f} {total['cpu_s']:8.1f}")
    print(f"load average (1 min) {load_before[0]:.1f} before, {load_after[0]:.1f} after, "
          f"on {os.cpu_count()} cores; wrote {args.out}/run_all.json")
    return 1 if any(r["returncode"] for r in runs.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
