"""A first start after installing: the server answers at once while the solver compiles in
the background, and its pages say so until it is ready (``app.jobs.start_warm_up``)."""
from __future__ import annotations

import threading
import time
import urllib.request

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
def test_a_served_first_start_answers_within_seconds(tmp_path, monkeypatch):
    """``panel serve app`` with nothing in numba's cache: the page is served within a few
    seconds of the server's start, while the compile goes on (the log says so)."""
    from browser.serving import serve_app

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba-cache"))
    log = tmp_path / "server.log"
    t0 = time.perf_counter()
    with serve_app(log, warmup=False, timeout_s=90.0) as base:
        up = time.perf_counter() - t0
        with urllib.request.urlopen(f"{base}/app", timeout=30) as response:
            assert response.status == 200
        first_page = time.perf_counter() - t0
        text = log.read_text()
    assert "preparing the solver" in text, text[-2000:]
    # The server's own start (imports, Panel) is most of it; no compile before answering.
    assert first_page - up < 5.0 and first_page < 30.0, (up, first_page)
