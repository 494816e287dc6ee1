"""What opening the dashboard costs: one page at a time, in headless Chromium.

    python benchmarks/bench_page_open.py [--opens 5] [--repo PATH ...] [--out DIR]

For each checkout given with ``--repo`` (default: this one), ``panel serve app`` is started
from it (its ``app/`` and, through ``PYTHONPATH``, its packages) and a page is opened
``--opens`` times, each in a fresh browser context, waiting until the document is rendered
and its sources at rest (the first open, which warms the server, is not counted). Per open:
the server process's CPU (user + system, its worker processes not included) and the wall
time from navigation to the page at rest. With several ``--repo`` the servers run side by
side and the opens alternate between them (same machine, same moment: e.g. ``main``
against a branch's worktree).

Writes DIR/page_open.json and prints median [min-max] per checkout. Numbers measured
while other jobs run are not trustworthy: note the load average printed with them.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import time
from pathlib import Path

import psutil

from checkout import ROOT, helper
from machine import loadavg
from spread import cell, spread


def _cpu_s(process: psutil.Process) -> float:
    times = process.cpu_times()
    return times.user + times.system


def _server_process(base: str) -> psutil.Process:
    port = base.rsplit(":", 1)[1]
    for proc in psutil.process_iter(["cmdline"]):
        line = " ".join(proc.info["cmdline"] or [])
        if "serve" in line and f"--port {port}" in line:
            return proc
    raise RuntimeError(f"no server process found for {base}")


def run(repos: list[Path], opens: int, out: Path) -> dict:
    serving, tools = helper("browser/serving"), helper("browser/page_tools")
    from playwright.sync_api import sync_playwright

    out.mkdir(parents=True, exist_ok=True)
    rows = {str(r): [] for r in repos}
    load0 = loadavg()
    with contextlib.ExitStack() as stack:
        servers = {}
        for i, repo in enumerate(repos):
            base = stack.enter_context(serving.serve_app(
                out / f"page-open-server-{i}.log", app_dir=str(repo / "app"),
                env={"PYTHONPATH": str(repo)}))
            servers[str(repo)] = (base, _server_process(base))
        playwright = stack.enter_context(sync_playwright())
        browser = serving.launch_chromium(playwright)
        stack.callback(browser.close)
        for i in range(opens + 1):
            for repo, (base, process) in servers.items():
                context = browser.new_context(viewport=serving.VIEWPORT)
                page = context.new_page()
                cpu0, t0 = _cpu_s(process), time.perf_counter()
                tools.wait_for_app(page, f"{base}/app?theta0_deg={20 + 7 * i}")
                tools.settle(page)
                wall, cpu = time.perf_counter() - t0, _cpu_s(process) - cpu0
                context.close()
                if i:  # the first open warms the server
                    rows[repo].append({"server_cpu_s": cpu, "open_s": wall})
                time.sleep(1.0)  # the closed page's messages drained
    report = {"opens": opens, "load_average": {"start": load0, "end": loadavg()},
              "repos": {repo: {key: spread(r[key] for r in got)
                               for key in ("server_cpu_s", "open_s")} | {"runs": got}
                        for repo, got in rows.items()}}
    (out / "page_open.json").write_text(json.dumps(report, indent=1))
    return report


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--opens", type=int, default=5)
    ap.add_argument("--repo", action="append", type=Path,
                    help="a checkout to serve (repeat to alternate; default this one)")
    ap.add_argument("--out", type=Path, default=Path("bench-out"))
    args = ap.parse_args()
    repos = [r.resolve() for r in (args.repo or [ROOT])]
    for repo in repos:
        if not (repo / "app" / "main.py").is_file():
            ap.error(f"--repo {repo}: no app/main.py there; give a checkout of this project")
    if args.opens < 1:
        ap.error(f"--opens {args.opens}: give at least 1")
    report = run(repos, args.opens, args.out)
    load = report["load_average"]
    print(f"{args.opens} opens each, load average {load['start'][0]:.1f} -> {load['end'][0]:.1f}")
    for repo, got in report["repos"].items():
        c, w = got["server_cpu_s"], got["open_s"]
        print(f"{repo}: server CPU per open {cell(c['median'], c['min'], c['max'], lambda v: f'{v:.2f}')} s; "
              f"open -> at rest {cell(w['median'], w['min'], w['max'], lambda v: f'{v:.2f}')} s")
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    raise SystemExit(main())
