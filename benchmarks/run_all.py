"""Run the benchmarks one after the other and write the performance report.

    python benchmarks/run_all.py [--quick] [--out DIR] [--no-browser] [--only SCRIPT ...]
                                 [--report PAGE]

Runs bench_support.py, bench_arrays.py, bench_dashboard.py and bench_friction_fit.py in
turn (never side by side: they time things), each in its own interpreter, importing the
installed package (``pip install -e .``) and writing to DIR (default bench-out). Prints,
and writes to DIR/run_all.json, the machine (CPU, cores, versions), the date, each script's wall time
and CPU time (user + sys of the script and its child processes) and the machine's load
average before and after each script: on a shared machine the wall time grows with the
other load, the CPU time much less. ``--report PAGE`` then writes the Markdown report
of this run (``report.py``; e.g. ``--report docs/performance-latest.md``, the page the
documentation's Performance page includes). Exits non-zero if any script failed.
"""
from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

import report
from machine import loadavg, machine

HERE = Path(__file__).resolve().parent
SCRIPTS = ("bench_support.py", "bench_arrays.py", "bench_dashboard.py", "bench_friction_fit.py")


def children_cpu() -> float:
    """CPU seconds (user + sys) of the finished child processes so far."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_script(script: str, out: Path, quick: bool, no_browser: bool) -> dict:
    """Run one benchmark; its wall and CPU seconds, exit code, start and the load around it."""
    cmd = [sys.executable, str(HERE / script), "--out", str(out)]
    if quick:
        cmd.append("--quick")
    if no_browser and script == "bench_dashboard.py":
        cmd.append("--no-browser")
    print(f"\n=== {' '.join(cmd[1:])}", flush=True)
    before, started = loadavg(), time.time()
    start, cpu = time.perf_counter(), children_cpu()
    code = subprocess.run(cmd).returncode
    return {"wall_s": time.perf_counter() - start, "cpu_s": children_cpu() - cpu,
            "returncode": code, "started": started, "loadavg_before": before,
            "loadavg_after": loadavg()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="each script's --quick mode (as in the tests)")
    ap.add_argument("--out", type=Path, default=Path("bench-out"), help="output folder (default bench-out)")
    ap.add_argument("--no-browser", action="store_true", help="dashboard: server-side part only")
    ap.add_argument("--only", nargs="+", choices=SCRIPTS, default=SCRIPTS, metavar="SCRIPT",
                    help=f"run only these of {', '.join(SCRIPTS)}")
    ap.add_argument("--report", type=Path, metavar="PAGE",
                    help="write the Markdown report of this run to PAGE")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    command = " ".join(["python benchmarks/run_all.py", *(sys.argv[1:] if argv is None else argv)])
    info, load_before = machine(), loadavg()
    t0, c0 = time.perf_counter(), children_cpu()
    runs = {script: run_script(script, out, args.quick, args.no_browser)
            for script in SCRIPTS if script in args.only}
    total = {"wall_s": time.perf_counter() - t0, "cpu_s": children_cpu() - c0}
    summary = {"command": command, "mode": "quick" if args.quick else "full", "machine": info,
               "cores": info["cores"], "scripts": runs, "total": total,
               "loadavg_1_5_15_before": load_before, "loadavg_1_5_15_after": loadavg()}
    (out / "run_all.json").write_text(json.dumps(summary, indent=1))
    print(f"\n{'script':<20} {'wall s':>8} {'CPU s':>8}  load before/after  exit")
    for script, r in runs.items():
        print(f"{script:<20} {r['wall_s']:8.1f} {r['cpu_s']:8.1f}  "
              f"{r['loadavg_before'][0]:5.2f} / {r['loadavg_after'][0]:5.2f}  {r['returncode']}")
    print(f"{'total':<20} {total['wall_s']:8.1f} {total['cpu_s']:8.1f}")
    print(f"load average (1 min) {load_before[0]:.1f} before, {summary['loadavg_1_5_15_after'][0]:.1f} "
          f"after, on {info['cores']} cores; wrote {out}/run_all.json")
    if args.report:
        report.write(out, args.report)
        print(f"wrote the report {args.report}")
    return 1 if any(r["returncode"] for r in runs.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
