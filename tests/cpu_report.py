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

What it misses: CPU used between tests (collection, a worker's start), the last tenth of
a second of a process that was not this process's child, and a descendant that outlives
its parent and is adopted by another process (it leaves the tree).
"""
from __future__ import annotations

import json
import os
import resource
import threading
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


def pytest_configure(config):
    """The controller starts a report afresh (parts left by a run that was stopped)."""
    report = config.getoption("cpu_report")
    if report and not hasattr(config, "workerinput"):
        for stale in _parts(Path(report)).glob("*.jsonl"):
            stale.unlink()


class Descendants:
    """The CPU of this process's descendants, read every ``interval`` seconds by a thread
    (``/proc``, via psutil): each process's own user + system time, last seen.

    Read this way, not from the processes' ``children_*`` times: a process that ignores
    ``SIGCHLD`` (Chromium's zygote does) reaps its children without adding their CPU to its
    own, so a page's renderer closed with its test would leave no trace. What a process
    did in its last ``interval`` before it ended is missed, and a process that lived less
    than that is never seen: ``charge`` adds the CPU of this process's reaped children
    (``RUSAGE_CHILDREN``) beyond what was seen of them."""

    def __init__(self, interval: float = 0.1):
        import psutil

        self.me, self.interval = psutil.Process(), interval
        self.seen: dict[tuple, list] = {}  # (pid, start) -> [parent pid, CPU s, alive]
        self.lock = threading.Lock()
        threading.Thread(target=self._run, name="cpu-report", daemon=True).start()

    def _run(self) -> None:
        while True:
            time.sleep(self.interval)
            self.read()

    def read(self) -> None:
        import psutil

        found = {}
        try:
            children = self.me.children(recursive=True)
        except psutil.Error:
            children = []
        for child in children:
            try:
                with child.oneshot():
                    t = child.cpu_times()
                    found[child.pid, child.create_time()] = [child.ppid(), t.user + t.system]
            except psutil.Error:
                pass
        with self.lock:
            for entry in self.seen.values():
                entry[2] = False
            for key, (ppid, cpu) in found.items():
                self.seen[key] = [ppid, cpu, True]

    def snapshot(self) -> tuple[dict, float, float]:
        """(CPU of each descendant seen, this process's CPU, its reaped children's CPU)."""
        self.read()
        with self.lock:
            cpu = {key: entry[1] for key, entry in self.seen.items()}
        return cpu, _rusage(resource.RUSAGE_SELF), _rusage(resource.RUSAGE_CHILDREN)

    def charge(self, start: tuple[dict, float, float]) -> float:
        """CPU seconds used since ``start`` (a ``snapshot``) by this process and its
        descendants; the processes seen ended are forgotten."""
        before, self_0, reaped_0 = start
        after, self_1, reaped_1 = self.snapshot()
        with self.lock:
            ended = {key: entry for key, entry in self.seen.items() if not entry[2]}
            for key in ended:
                del self.seen[key]
        used = self_1 - self_0 + sum(cpu - before.get(key, 0.0) for key, cpu in after.items())
        # This process's children reaped meanwhile (with what they reaped) beyond their
        # CPU seen: the end of their lives and the processes too short to be seen.
        mine = self.me.pid
        parents = {key[0]: entry[0] for key, entry in ended.items()}

        def under_a_child(pid: int) -> bool:
            for _ in range(64):
                if parents.get(pid) == mine:
                    return True
                if pid not in parents:
                    return False
                pid = parents[pid]
            return False

        seen_of_reaped = sum(entry[1] for key, entry in ended.items() if under_a_child(key[0]))
        return used + max(0.0, reaped_1 - reaped_0 - seen_of_reaped)


def _rusage(who) -> float:
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


_DESCENDANTS: list = []  # one reader per process, started with the first test


def _parts(path: Path) -> Path:
    return path.with_name(path.name + ".parts")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    report = item.config.getoption("cpu_report")
    if not report:
        yield
        return
    if not _DESCENDANTS:
        _DESCENDANTS.append(Descendants())
    descendants = _DESCENDANTS[0]
    start_cpu, start = descendants.snapshot(), time.monotonic()
    yield
    row = {"test": item.nodeid.split("@", 1)[0],
           "cpu_s": round(descendants.charge(start_cpu), 3),
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
