"""Where the suite's CPU goes, test by test: ``python -m pytest --cpu-report cpu.json``.

For each test, the CPU time (user + system) of the process that runs it and of all its
descendants while it runs (its setup, call and teardown): the served dashboards, their
work-pool processes, Chromium and every command a test starts. So a test that opens a
page is charged the page's Chromium and server CPU, and the first test of a module also
the start of the module's fixtures. ``benchmarks/cpu_by_process.py`` answers the other
question (CPU by kind of process, for the whole run).

With pytest-xdist each worker writes its tests to ``<report>.parts/<worker>.jsonl``; the
controller merges them into the report (JSON: every test, every module summed, the
total) and prints the modules that cost the most. Linux only (``/proc``, via psutil).

What it misses: CPU used between tests (collection, a worker's start), and a descendant
that outlives its parent and is adopted by another process (it leaves the tree).
"""
from __future__ import annotations

import json
import os
import resource
import time
from pathlib import Path

import pytest

#: Modules listed at the end of the run, costliest first.
SHOWN = 12
_FOUND = pytest.StashKey[dict]()


def pytest_addoption(parser):
    parser.addoption("--cpu-report", metavar="PATH", default=None,
                     help="write each test's CPU time, its descendants' included, to PATH "
                          "(JSON; tests/cpu_report.py)")


def tree_cpu_s(process=None) -> float:
    """CPU seconds of this process, its reaped children and its live descendants (and
    the children those reaped)."""
    import psutil

    process = process or psutil.Process()
    total = 0.0
    for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN):
        usage = resource.getrusage(who)
        total += usage.ru_utime + usage.ru_stime
    try:
        descendants = process.children(recursive=True)
    except psutil.Error:
        descendants = []
    for child in descendants:
        try:
            t = child.cpu_times()
            total += t.user + t.system + t.children_user + t.children_system
        except psutil.Error:  # ended meanwhile: its parent now counts it
            pass
    return total


def _parts(path: Path) -> Path:
    return path.with_name(path.name + ".parts")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    report = item.config.getoption("cpu_report")
    if not report:
        yield
        return
    start_cpu, start = tree_cpu_s(), time.monotonic()
    yield
    row = {"test": item.nodeid.split("@", 1)[0], "cpu_s": round(tree_cpu_s() - start_cpu, 3),
           "wall_s": round(time.monotonic() - start, 3)}
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    parts = _parts(Path(report))
    parts.mkdir(parents=True, exist_ok=True)
    with open(parts / f"{worker}.jsonl", "a", encoding="utf-8") as out:
        out.write(json.dumps(row) + "\n")


def merge(path: Path) -> dict:
    """The report from the workers' parts (which are removed)."""
    rows = []
    parts = _parts(path)
    for part in sorted(parts.glob("*.jsonl")):
        rows += [json.loads(line) for line in part.read_text(encoding="utf-8").splitlines()]
        part.unlink()
    if parts.exists():
        parts.rmdir()
    modules: dict[str, dict] = {}
    for row in rows:
        m = modules.setdefault(row["test"].split("::", 1)[0], {"tests": 0, "cpu_s": 0.0})
        m["tests"] += 1
        m["cpu_s"] = round(m["cpu_s"] + row["cpu_s"], 3)
    return {"total_cpu_s": round(sum(r["cpu_s"] for r in rows), 1), "tests": len(rows),
            "modules": dict(sorted(modules.items(), key=lambda kv: -kv[1]["cpu_s"])),
            "by_test": sorted(rows, key=lambda r: -r["cpu_s"])}


def pytest_sessionfinish(session):
    report = session.config.getoption("cpu_report")
    if report and not hasattr(session.config, "workerinput"):  # the controller only
        path = Path(report)
        found = merge(path)
        path.write_text(json.dumps(found, indent=1), encoding="utf-8")
        session.config.stash[_FOUND] = found  # for the summary below


def pytest_terminal_summary(terminalreporter, config):
    found = config.stash.get(_FOUND, None)
    if found is None:
        return
    write = terminalreporter.write_line
    write(f"CPU of the tests and their processes: {found['total_cpu_s']:.0f} s over "
          f"{found['tests']} tests ({config.getoption('cpu_report')}); costliest modules:")
    for module, m in list(found["modules"].items())[:SHOWN]:
        write(f"  {m['cpu_s']:8.1f} s  {m['tests']:4d} tests  {module}")
