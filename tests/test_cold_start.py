"""A first start after installing: the server answers at once while the solver compiles in
the background, and its pages say so until it is ready (``app.jobs.start_warm_up``)."""
from __future__ import annotations

import threading
import time

import pytest

from app import jobs, worker


@pytest.fixture
def cold(monkeypatch):
    """An empty numba cache (as after installing) and a compile that waits for ``release``."""
    release, started = threading.Event(), threading.Event()

    def slow_warm():
        started.set()
        assert release.wait(10)

    monkeypatch.setattr("model._kernel.cache_is_cold", lambda: True)
    monkeypatch.setattr(jobs, "compile_in_a_process", lambda: True)
    monkeypatch.setattr(worker, "warm", slow_warm)
    monkeypatch.setattr(jobs, "_SOLVER_READY", threading.Event())
    monkeypatch.setattr(jobs, "work_pool", lambda: type("Pool", (), {"warm_up": lambda s: None})())
    yield release, started
    release.set()


def test_a_cold_start_compiles_in_the_background(cold):
    release, started = cold
    t0 = time.perf_counter()
    assert jobs.start_warm_up() is True
    assert time.perf_counter() - t0 < 1.0 and started.wait(5)
    assert not jobs.solver_ready()
    release.set()
    for _ in range(100):
        if jobs.solver_ready():
            break
        time.sleep(0.05)
    assert jobs.solver_ready()


def test_the_cold_compile_runs_in_a_process_of_its_own_then_loads_here(monkeypatch):
    order, ran, compile_in_a_process = [], [], jobs.compile_in_a_process
    monkeypatch.setattr("model._kernel.cache_is_cold", lambda: True)
    monkeypatch.setattr(jobs, "compile_in_a_process", lambda: order.append("compile") or True)
    monkeypatch.setattr(worker, "warm", lambda: order.append("load"))
    monkeypatch.setattr(jobs, "_SOLVER_READY", threading.Event())
    monkeypatch.setattr(jobs, "work_pool", lambda: type("Pool", (), {"warm_up": lambda s: None})())
    assert jobs.start_warm_up() is True
    for _ in range(100):
        if jobs.solver_ready():
            break
        time.sleep(0.05)
    assert jobs.solver_ready() and order == ["compile", "load"]
    # the process: the package's own warm-up command; a failure is reported, not raised
    monkeypatch.setattr("subprocess.run", lambda argv, **kw: ran.append(argv) or
                        type("Done", (), {"returncode": 3, "stderr": "boom"})())
    assert compile_in_a_process() is False
    assert ran[0][1:] == ["-m", "model", "warmup"]


def test_a_warm_cache_loads_the_solver_before_serving(monkeypatch):
    calls = []
    monkeypatch.setattr("model._kernel.cache_is_cold", lambda: False)
    monkeypatch.setattr(worker, "warm", lambda: calls.append("warm"))
    monkeypatch.setattr(jobs, "_SOLVER_READY", threading.Event())
    monkeypatch.setattr(jobs, "work_pool", lambda: type("Pool", (), {"warm_up": lambda s: None})())
    assert jobs.start_warm_up() is False
    assert calls == ["warm"] and jobs.solver_ready()


def test_the_page_says_the_solver_is_being_prepared(monkeypatch):
    from app.views.page import Dashboard

    monkeypatch.setattr(jobs, "_SOLVER_READY", threading.Event())
    page = Dashboard()
    assert page.preparing.visible and "Preparing the solver" in page.preparing.object
    jobs._SOLVER_READY.set()
    page._check_solver()
    assert not page.preparing.visible
    assert not Dashboard().preparing.visible


@pytest.mark.slow
def test_a_served_first_start_answers_within_seconds():
    """``panel serve app`` with nothing in numba's cache (as after installing) answers its
    first page within seconds of its launch, while the solver compiles in the background
    (it compiled first and answered after ~16 s before; ~3 s now on this machine).
    Measured by ``benchmarks/cold_start.py``."""
    import re
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    done = subprocess.run([sys.executable, str(root / "benchmarks" / "cold_start.py"),
                           "--runs", "1", "--port", str(_free_port())], cwd=root,
                          capture_output=True, text=True, timeout=120)
    match = re.search(r"empty numba cache: ([0-9.]+|nan) ", done.stdout)
    assert match, done.stdout + done.stderr
    assert float(match.group(1)) < 10.0, done.stdout
    # The health check's liveness probe builds no page: it does not wait for the compile
    # (it took ~15 s on a first start when it built the dashboard).
    probe = re.search(r"right after it: ([0-9]+) ", done.stdout)
    assert probe and int(probe.group(1)) < 5_000, done.stdout


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
