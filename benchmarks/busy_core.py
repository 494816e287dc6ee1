"""Run a benchmark with one core kept busy by another process, as on a shared lab server.

    python benchmarks/busy_core.py [--cores 1] -- python benchmarks/load_test.py --sessions 30

Starts ``--cores`` processes that each spin on the CPU (pure Python arithmetic, no I/O,
at normal priority like any other user's job), runs the command after ``--`` while they
spin, then stops them. The spinners stop by themselves after ``--max-seconds`` (default
3600) even if this script is killed. Prints the load average before and after and exits
with the command's exit code, so any benchmark of the project can be measured both
quiet and with a busy core by the same command line.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import subprocess
import sys

SPIN = ("import time\n"
        "deadline = time.monotonic() + {seconds}\n"
        "x = 0\n"
        "while time.monotonic() < deadline:\n"
        "    for _ in range(100_000):\n"
        "        x = (x * 1103515245 + 12345) & 0x7fffffff\n")


@contextlib.contextmanager
def busy_cores(cores: int = 1, max_seconds: float = 3600.0):
    """Keep ``cores`` cores busy with spinning processes for the duration of the block."""
    spinners = [subprocess.Popen([sys.executable, "-c", SPIN.format(seconds=max_seconds)])
                for _ in range(cores)]
    try:
        yield spinners
    finally:
        for p in spinners:
            p.terminate()
        for p in spinners:
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                p.kill()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cores", type=int, default=1, help="cores kept busy (1)")
    ap.add_argument("--max-seconds", type=float, default=3600.0,
                    help="the spinners stop by themselves after this long (3600)")
    ap.add_argument("command", nargs=argparse.REMAINDER, help="-- the command to run")
    args = ap.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        ap.error("give the command to run after --, e.g. -- python benchmarks/bench_dashboard.py")
    if not 1 <= args.cores <= (os.cpu_count() or 1):
        ap.error(f"--cores {args.cores}: must be between 1 and the {os.cpu_count()} cores here")
    before = os.getloadavg()
    with busy_cores(args.cores, args.max_seconds):
        code = subprocess.run(command).returncode
    after = os.getloadavg()
    print(f"busy_core: {args.cores} core(s) kept busy; load average (1, 5, 15 min) "
          f"before {before[0]:.2f} {before[1]:.2f} {before[2]:.2f}, "
          f"after {after[0]:.2f} {after[1]:.2f} {after[2]:.2f}", file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
