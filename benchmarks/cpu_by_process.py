"""Where a command's CPU goes: its processes' CPU time summed by kind (Linux).

    python benchmarks/cpu_by_process.py -- python -m pytest
    python benchmarks/cpu_by_process.py --out cpu.json -- python benchmarks/load_test.py --quick

Runs the command after ``--`` and reads ``/proc`` every ``--interval`` seconds (default
1): each descendant process's user + system CPU time, last seen, summed by kind
(Chromium, the dashboard's ``panel serve``, its work-pool processes, pytest-xdist
workers, Playwright's driver, other Python commands by their first arguments). Prints a
table with the wall time and the share of the machine's cores the command used, and
exits with the command's exit code. Also the whole machine's busy CPU over the run
(``/proc/stat`` read before and after: everything but idle and I/O wait), which counts
every process, short-lived or not, and other work on the machine too.

What it misses: a process that starts and ends between two readings, and the last
``--interval`` of each process's life (so short-lived processes are undercounted; the
table says how many processes of each kind were seen). For the test suite it shows
what a faster suite has to cut: on the 2-core machine, 2026-11-27, Chromium took ~40 % of
the CPU (~3 s per page opened).
"""
from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import time

HZ = os.sysconf("SC_CLK_TCK")


def kind(cmdline: str) -> str:
    """The kind of process a command line belongs to."""
    words = cmdline.split()
    if not words:
        return "kernel or unknown"
    head = os.path.basename(words[0])
    if "chrom" in head:
        return "Chromium"
    if "panel serve" in cmdline:
        return "panel serve"
    if "node" in head:
        return "node (Playwright's driver)"
    if "spawn_main" in cmdline or "multiprocessing" in cmdline or "loky" in cmdline:
        return "pool workers (multiprocessing)"
    if "execnet" in cmdline or "exec(eval(sys.stdin.readline()))" in cmdline:
        return "pytest-xdist workers"
    if "pytest" in cmdline:
        return "pytest"
    if "python" in head:
        return "python " + " ".join(words[1:3])[:50]
    return head[:40]


def _children(root: int) -> dict[int, str]:
    """pid -> /proc/<pid>/stat fields after the command name, for ``root``'s descendants."""
    parent, stats = {}, {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        parent[int(name)], stats[int(name)] = int(fields[1]), fields
    out = {}
    for pid, fields in stats.items():
        p = pid
        while p in parent and p not in (0, 1):
            if parent[p] == root:
                out[pid] = fields
                break
            p = parent[p]
    return out


def sample(root: int, seen: dict, kinds: dict) -> None:
    """Read every descendant's CPU time; key by (pid, start time) so reused pids differ."""
    for pid, fields in _children(root).items():
        key = (pid, fields[19])
        seen[key] = (int(fields[11]) + int(fields[12])) / HZ
        if key not in kinds:
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as fh:
                    kinds[key] = kind(fh.read().replace(b"\0", b" ").decode(errors="replace"))
            except OSError:
                kinds[key] = "kernel or unknown"


def machine_busy_s() -> float:
    """Seconds of CPU the whole machine has spent busy (all cores; not idle, not I/O wait)."""
    with open("/proc/stat") as fh:
        ticks = [int(x) for x in fh.readline().split()[1:]]
    return (sum(ticks) - ticks[3] - ticks[4]) / HZ


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--interval", type=float, default=1.0, help="seconds between readings")
    parser.add_argument("--out", help="also write the table as JSON here")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- the command to run")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("give the command to run after --")
    if not os.path.isdir("/proc/self"):
        parser.error("this needs Linux's /proc")
    seen, kinds = {}, {}
    start, busy0 = time.monotonic(), machine_busy_s()
    child = subprocess.Popen(command)
    me = os.getpid()
    while child.poll() is None:
        sample(me, seen, kinds)
        time.sleep(args.interval)
    wall, busy = time.monotonic() - start, machine_busy_s() - busy0
    totals, counts = collections.Counter(), collections.Counter()
    for key, cpu in seen.items():
        totals[kinds[key]] += cpu
        counts[kinds[key]] += 1
    total = sum(totals.values())
    rows = [{"kind": k, "cpu_s": round(v, 1), "share": round(v / total, 3) if total else 0.0,
             "processes": counts[k]} for k, v in totals.most_common()]
    print("| process kind | CPU s | share | processes |\n|---|---:|---:|---:|")
    for r in rows:
        print(f"| {r['kind']} | {r['cpu_s']:.1f} | {r['share']:.0%} | {r['processes']} |")
    cores = os.cpu_count() or 1
    print(f"\nwall {wall:.1f} s; CPU seen {total:.1f} s = {total / wall / cores:.0%} of "
          f"{cores} cores (processes shorter than --interval are missed); the machine "
          f"busy {busy:.1f} s, {busy / wall:.2f} of its {cores} cores on average",
          file=sys.stderr)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as fh:
            json.dump({"wall_s": round(wall, 1), "cores": cores, "rows": rows,
                       "machine_busy_s": round(busy, 1)}, fh, indent=1)
    return child.returncode


if __name__ == "__main__":
    sys.exit(main())
