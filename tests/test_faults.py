"""Faults: failing model runs, dying workers, sessions that go away mid-computation, and a
disk cache that cannot be written.

(a) A run that fails or exhausts its budget shows a message and the session stays usable.
    (A future that raises is covered by tests/test_app_state.py.)
(b) Sessions that end mid-computation: tests/test_session_end.py.
(c) A read-only, full or impossible disk-cache folder degrades to no disk cache with one
    logged warning for a whole sweep, and the results are still computed. (Single
    ``DiskCache`` objects are covered by tests/test_cache.py.)
"""
from __future__ import annotations

import errno
import functools
import logging
import math
import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from app import jobs, worker
from app import slot as slots
from app.state import ExplorerState
from fakes import InProcessPool
from model.runs import cache as cache_mod
from model.runs.sweeps import regime_map


# ---------------------------------------------------------------------- (a) failing runs

@pytest.fixture(scope="module")
def dashboard():
    """One dashboard without a server: jobs run synchronously (in the worker processes)."""
    from app.views import Dashboard

    return Dashboard(ExplorerState())


def _orbit(page):
    return np.asarray(page.support._sources["orbit"].data["x1"], dtype=float).copy()


def _error(page, name="support"):
    return page.results.errors.get(name, "")


@pytest.mark.parametrize("budget, expected", [
    (dict(MAX_STEPS=20), "step budget"),
    (dict(simulate_support=functools.partial(worker.simulate_support, tau_max=1.0)),
     "time budget tau_max"),
])
def test_a_run_over_its_budget_shows_why_and_the_next_change_computes(dashboard, monkeypatch,
                                                                      budget, expected):
    state = dashboard.state
    state.reset()
    assert _error(dashboard) == "" and not dashboard.alert.visible
    for name, value in budget.items():
        monkeypatch.setattr(worker, name, value)
    monkeypatch.setattr(slots, "work_pool", InProcessPool)
    state.F_N = 2.0
    data = dashboard.results.support
    assert data.params.F_N == 2.0 and data.result is not None and not data.result.success
    assert "did not reach its end" in _error(dashboard)
    assert expected in _error(dashboard)
    assert dashboard.alert.visible and "did not reach its end" in dashboard.alert.object
    assert np.all(np.isfinite(_orbit(dashboard)))  # the partial contact is drawn, sanely

    monkeypatch.undo()  # the real workers again
    state.F_N = 3.0
    data = dashboard.results.support
    assert data.params.F_N == 3.0 and data.result.success
    assert _error(dashboard) == "" and not dashboard.alert.visible
    state.reset()


def test_a_model_that_raises_keeps_the_last_good_plots_and_recovers(dashboard, monkeypatch):
    state = dashboard.state
    state.reset()
    before = _orbit(dashboard)

    def broken(*args, **kwargs):
        raise FloatingPointError("overflow in the friction law (simulated)")

    monkeypatch.setattr(worker, "fixed_orientation", broken)
    monkeypatch.setattr(slots, "work_pool", InProcessPool)
    state.theta0 = 120.0
    assert "The model raised FloatingPointError" in _error(dashboard)
    assert dashboard.alert.visible and "simulated" in dashboard.alert.object
    np.testing.assert_array_equal(_orbit(dashboard), before)  # the last good plots stay

    monkeypatch.undo()
    state.theta0 = 121.0
    assert _error(dashboard) == "" and not dashboard.alert.visible
    assert dashboard.results.support.params.theta0 == pytest.approx(math.radians(121.0))
    assert not np.array_equal(_orbit(dashboard), before)
    state.reset()


def test_a_worker_that_dies_mid_run_shows_a_message_and_a_new_worker_takes_over(
        dashboard, monkeypatch, caplog):
    state = dashboard.state
    state.reset()
    before = _orbit(dashboard)
    pool = jobs.work_pool().executor("interactive")
    pid = pool.submit(os.getpid).result(timeout=120)

    class Dying:
        def submit(self, lane, key, fn, *args, **options):
            if lane != "interactive":
                return jobs.work_pool().submit(lane, key, fn, *args, **options)
            threading.Timer(0.5, os.kill, (pid, signal.SIGKILL)).start()  # killed (OOM) ...
            return jobs.work_pool().submit("interactive", None, time.sleep, 60)  # ... mid-run

    monkeypatch.setattr(slots, "work_pool", Dying)
    state.F_N = 2.0
    assert "BrokenProcessPool" in _error(dashboard) and dashboard.alert.visible
    np.testing.assert_array_equal(_orbit(dashboard), before)

    monkeypatch.undo()
    with caplog.at_level(logging.WARNING, logger=jobs.__name__):
        state.F_N = 3.0
    assert _error(dashboard) == "" and not dashboard.alert.visible
    data = dashboard.results.support
    assert data.params.F_N == 3.0 and data.result.success
    assert jobs.work_pool().executor("interactive") is not pool
    assert any("stopped" in r.getMessage() for r in caplog.records)
    state.reset()


# ---------------------------------------------------------------------- (c) disk cache

def _refuse_temp_files(monkeypatch, tmp_path):
    def refuse(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system (simulated)")
    monkeypatch.setattr(cache_mod.tempfile, "mkstemp", refuse)
    return tmp_path / "cache"


def _full_disk(monkeypatch, tmp_path):
    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device (simulated)")
    monkeypatch.setattr(cache_mod.os, "fsync", full)
    return tmp_path / "cache"


def _folder_under_a_file(monkeypatch, tmp_path):
    """Truly unwritable without simulation, also as root: the folder's parent is a file."""
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    return blocker / "cache"


SWEEP = dict(k_r=[3.0, 0.01], k_theta=[0.01, 3.0], F_N=1.0, tol=1e-2)


@pytest.fixture(scope="module")
def reference_sweep(tmp_path_factory):
    """The sweep computed with a working disk cache of its own."""
    old = os.environ.get(cache_mod.ENV_VAR)
    os.environ[cache_mod.ENV_VAR] = str(tmp_path_factory.mktemp("good-cache"))
    try:
        return regime_map(**SWEEP)
    finally:
        if old is None:
            os.environ.pop(cache_mod.ENV_VAR, None)
        else:
            os.environ[cache_mod.ENV_VAR] = old


@pytest.mark.parametrize("break_disk", [_refuse_temp_files, _full_disk, _folder_under_a_file],
                         ids=["read-only", "full", "not-a-folder"])
def test_a_sweep_on_a_broken_disk_cache_computes_with_one_warning(
        break_disk, reference_sweep, tmp_path, monkeypatch, caplog):
    folder = break_disk(monkeypatch, tmp_path)
    monkeypatch.setenv(cache_mod.ENV_VAR, str(folder))
    with caplog.at_level(logging.WARNING, logger=cache_mod.__name__):
        first = regime_map(**SWEEP)
        again = regime_map(**SWEEP)  # still no disk cache, and no second warning
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert len(warnings) == 1 and "not writable" in warnings[0], warnings
    for result in (first, again):
        assert bool(np.all(result.columns["success"]))
        for name in ("FTx_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0", "beta"):
            np.testing.assert_array_equal(result.columns[name], reference_sweep.columns[name])
    leftovers = [p for p in folder.rglob("*")] if folder.is_dir() else []
    assert [p for p in leftovers if p.is_file()] == []  # no entries, no temporary files


def _run_timeouts(doc, rounds: int = 20) -> None:
    """Run ``doc``'s one-shot timers (and those they add) as a server's loop would."""
    from bokeh.server.callbacks import TimeoutCallback

    for _ in range(rounds):
        due = [cb for cb in doc.session_callbacks if isinstance(cb, TimeoutCallback)]
        if not due:
            return
        for cb in due:
            cb.callback()


def test_a_second_copy_of_the_app_shares_the_workers(monkeypatch):
    """The page script run by a second handler of the app (as ``panel serve`` with several
    app paths, or an autoreload, does) builds its pages on the same worker processes as
    the first, not on workers of its own."""
    import weakref

    import panel as pn
    from bokeh.application.handlers.directory import DirectoryHandler
    from bokeh.document import Document
    from bokeh.server.contexts import BokehSessionContext

    from app import opening
    from app.page_lane import PageLane
    from app.views import Dashboard

    # A lane of this test's own: without a server no timer fires but the ones run here.
    monkeypatch.setattr(opening, "LANE", PageLane(opening.STEP_GAP_MS))
    app_dir = Path(jobs.__file__).parent
    pool = jobs.work_pool()
    built = []
    original = Dashboard.from_session.__func__
    monkeypatch.setattr(Dashboard, "from_session",
                        classmethod(lambda cls: built.append(original(cls)) or built[-1]))
    executors = {name: pool.executor(name) for name in jobs.LANES}
    for copy in range(2):
        handler = DirectoryHandler(filename=str(app_dir))
        assert not handler.failed, handler.error
        doc = Document()
        # A browser session behind the page (without one, the script builds nothing: that
        # is Panel's liveness probe).
        context = BokehSessionContext(f"copy-{copy}", None, doc)
        context._request = type("Request", (), {"arguments": {}, "remote_ip": "127.0.0.1",
                                                "cookies": {}, "headers": {}})()
        doc._session_context = weakref.ref(context)
        handler.modify_document(doc)
        assert not handler.failed, handler.error
        pn.state._on_load(doc)  # the browser has the page: the dashboard is built now,
        _run_timeouts(doc)      # in the steps the server's loop would run
    assert len(built) == 2  # the page was built twice ...
    assert jobs.work_pool() is pool  # ... on one pool of workers
    assert {name: pool.executor(name) for name in jobs.LANES} == executors
