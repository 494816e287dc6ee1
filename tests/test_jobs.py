"""The server's work pool (app/jobs.py): fair turns for clients and sessions, a bounded
queue, time budgets that stop a runaway job (and only it), shared results."""
from __future__ import annotations

import concurrent.futures as cf
import time

import pytest

from app.jobs import Lane, OverBudget, ServerBusy, WorkPool


@pytest.fixture
def pool():
    pools = []

    def make(workers=1, **options):
        p = WorkPool({"work": Lane("work", workers, 0, "test lane")}, **options)
        p.executor("work").submit(abs, -1).result(timeout=120)  # started and warm
        pools.append(p)
        return p
    yield make
    for p in pools:
        p.shutdown()


def _order(pool, jobs, seconds=0.15):
    """Submit ``jobs`` [(tag, client, session)] while the worker is busy; the tags in the
    order they finished (one worker: the order they ran)."""
    done = []
    blocker = pool.submit("work", None, time.sleep, 0.5, session="blocker")
    futures = []
    for tag, client, session in jobs:
        f = pool.submit("work", None, time.sleep, seconds, client=client, session=session)
        f.add_done_callback(lambda _f, tag=tag: done.append(tag))
        futures.append(f)
    cf.wait([blocker, *futures], timeout=60)
    return done


def test_one_sessions_pile_of_work_delays_another_by_at_most_one_job(pool):
    p = pool()
    jobs = [(f"A{i}", None, "A") for i in range(5)] + [("B0", None, "B")]
    order = _order(p, jobs)
    assert order.index("B0") <= 1, order  # after at most one of A's waiting jobs
    assert [t for t in order if t.startswith("A")] == [f"A{i}" for i in range(5)]


def test_one_client_with_many_sessions_cannot_starve_another_client(pool):
    p = pool()
    jobs = [(f"X{i}", "10.0.0.1", f"X{i}") for i in range(6)] + [("Y", "10.0.0.2", "Y")]
    order = _order(p, jobs)
    assert order.index("Y") <= 1, order


def test_a_full_queue_answers_busy_at_once(pool):
    p = pool(max_queued=2)
    running = p.submit("work", None, time.sleep, 1.0, session="s")
    time.sleep(0.2)
    queued = [p.submit("work", None, time.sleep, 0.0, session="s") for _ in range(2)]
    refused = p.submit("work", None, time.sleep, 0.0, session="t")
    with pytest.raises(ServerBusy, match="busy"):
        refused.result(timeout=0.1)
    assert all(f.result(timeout=30) is None for f in [running, *queued])


def test_a_job_past_its_budget_is_stopped_and_the_pool_goes_on(pool):
    p = pool()
    start = time.monotonic()
    runaway = p.submit("work", "runaway", time.sleep, 30, budget_s=0.5)
    with pytest.raises(OverBudget, match="0.5 s"):
        runaway.result(timeout=20)
    assert time.monotonic() - start < 10
    again = p.submit("work", "runaway", time.sleep, 30, budget_s=0.5)
    with pytest.raises(OverBudget):  # refused at once, nothing runs
        again.result(timeout=0.1)
    assert p.submit("work", "next", abs, -3).result(timeout=60) == 3  # a new worker


def test_a_job_stopped_with_another_ones_worker_runs_again(pool):
    p = pool(workers=2)
    innocent = p.submit("work", None, time.sleep, 1.0, budget_s=30)
    runaway = p.submit("work", None, time.sleep, 30, budget_s=0.4)
    with pytest.raises(OverBudget):
        runaway.result(timeout=20)
    assert innocent.result(timeout=60) is None  # run again, not failed


def test_the_start_of_new_workers_does_not_count_against_a_budget(pool, monkeypatch):
    # Workers started from a fresh interpreter (``spawn``, the fallback where there is no
    # fork server): the new worker imports the model and loads the compiled kernel (about
    # a second or more) before it answers; the job's 0.6 s budget starts once it does.
    import multiprocessing

    import app.lanes
    monkeypatch.setattr(app.lanes, "worker_context", lambda: multiprocessing.get_context("spawn"))
    p = pool()
    runaway = p.submit("work", None, time.sleep, 30, budget_s=0.3)
    with pytest.raises(OverBudget):
        runaway.result(timeout=20)
    start = time.monotonic()
    assert p.submit("work", None, time.sleep, 0.3, budget_s=0.6).result(timeout=60) is None
    assert time.monotonic() - start > 0.6  # the start-up did take longer than the budget


def test_workers_are_forked_by_a_fork_server_that_imported_the_model(pool):
    """A lane's workers come from ``multiprocessing``'s fork server (a child of this
    process) with ``app.worker`` preloaded, not from fresh interpreters; a lane restarted
    after a stopped job gets new ones from the same server."""
    import os

    import psutil

    from app.lanes import WORKER_MODULE, worker_context

    assert worker_context().get_start_method() == "forkserver"
    p = pool()
    first = p.submit("work", None, os.getpid).result(timeout=60)
    server = psutil.Process(first).parent()
    assert server.pid != os.getpid() and server.parent().pid == os.getpid()
    assert "forkserver" in " ".join(server.cmdline())
    # WORKER_MODULE was imported there: numba's compiled libraries are mapped in it.
    assert any("numba" in m.path for m in server.memory_maps()), WORKER_MODULE
    with pytest.raises(OverBudget):
        p.submit("work", None, time.sleep, 30, budget_s=0.3).result(timeout=20)
    second = p.submit("work", None, os.getpid).result(timeout=60)
    assert second != first and psutil.Process(second).parent().pid == server.pid


def test_identical_requests_are_computed_once_and_shared(pool):
    p = pool()
    blocker = p.submit("work", None, time.sleep, 0.3)
    first = p.submit("work", ("abs", -5), abs, -5, session="a")
    second = p.submit("work", ("abs", -5), abs, -5, session="b")
    assert first.result(timeout=30) == second.result(timeout=30) == 5
    blocker.result(timeout=30)
    assert p.stats()["work"]["started"] == 2  # the blocker and one abs (not two)
    hit = p.submit("work", ("abs", -5), abs, -5)
    assert hit.done() and hit.result() == 5  # from the shared cache


def test_a_cancelled_waiting_job_never_runs(pool):
    p = pool()
    blocker = p.submit("work", None, time.sleep, 0.4)
    waiting = p.submit("work", None, abs, -1)
    assert waiting.cancel()
    blocker.result(timeout=30)
    time.sleep(0.2)
    assert p.stats()["work"]["started"] == 1  # the blocker only


def test_the_shared_results_are_bounded_in_bytes_as_well_as_in_number():
    from app.result_cache import ResultCache

    cache = ResultCache(maxsize=100, max_bytes=50_000)
    for i in range(10):
        cache.put(i, bytes(10_000))  # ~10 kB each as pickled
    assert 0 < cache.nbytes <= 50_000 and len(cache) == 4
    assert cache.get(0) is None and cache.get(9) is not None  # the oldest went first
    cache.put("huge", bytes(60_000))  # larger than the whole cache: not kept
    assert cache.get("huge") is None and len(cache) == 4
    cache.put(9, b"")  # replacing an entry counts its new size only
    assert cache.nbytes == sum(cache._sizes.values())
    cache.clear()
    assert cache.nbytes == 0 and len(cache) == 0
