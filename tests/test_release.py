"""After the class left (app/pages.py ``release_memory``): the shared results are cut down
to their idle bound in bytes, and idle worker processes are replaced by fresh ones, while
a server with open sessions or waiting work keeps both."""
from __future__ import annotations

import os
import time

import numpy as np
import pytest

from app import jobs, pages
from app.jobs import Lane, WorkPool
from app.result_cache import IDLE_CACHE_BYTES, ResultCache


def test_the_idle_cache_keeps_the_most_recent_results_within_its_byte_bound():
    cache = ResultCache(max_bytes=64 * 2**20)
    for i in range(40):  # 40 results of ~0.5 MB: 20 MB
        cache.put(("support", i), np.full(65_536, float(i)))
    assert cache.nbytes > 4 * IDLE_CACHE_BYTES
    cache.get(("support", 0))  # used again: now the most recent
    cache.shrink()
    assert 0 < cache.nbytes <= IDLE_CACHE_BYTES
    assert cache.get(("support", 0)) is not None and cache.get(("support", 39)) is not None
    assert cache.get(("support", 1)) is None  # the least recently used went first


def _worker_pid() -> int:
    return os.getpid()


@pytest.fixture
def server_pool(monkeypatch):
    """The server's work pool, replaced by one with a single one-worker lane."""
    pool = WorkPool({"work": Lane("work", 1, 0, "test lane")})
    pool.executor("work").submit(abs, -1).result(timeout=120)  # started and warm
    monkeypatch.setattr(jobs, "_POOL", pool)
    yield pool
    pool.shutdown()


def _fill(pool: WorkPool, n: int = 20) -> None:
    for i in range(n):  # results of ~0.5 MB each, as a class leaves them
        pool.cache.put(("support", i), np.full(65_536, float(i)))


def test_after_the_last_session_the_workers_are_fresh_and_the_cache_small(server_pool):
    pid = server_pool.submit("work", None, _worker_pid).result(timeout=60)
    _fill(server_pool)
    done = pages.release_memory(lambda: 0)
    assert done == {"idle": True, "recycled": True, "cache_bytes": server_pool.cache.nbytes,
                    "settled": True}
    assert server_pool.cache.nbytes <= IDLE_CACHE_BYTES
    fresh = server_pool.submit("work", None, _worker_pid).result(timeout=120)
    assert fresh != pid  # a new worker process


def test_open_sessions_keep_their_workers_and_results(server_pool):
    pid = server_pool.submit("work", None, _worker_pid).result(timeout=60)
    _fill(server_pool)
    before = server_pool.cache.nbytes
    assert pages.release_memory(lambda: 1)["idle"] is False
    assert pages.release_memory(None)["idle"] is False  # no server: nothing to count
    assert server_pool.cache.nbytes == before
    assert server_pool.submit("work", None, _worker_pid).result(timeout=60) == pid


def test_waiting_work_keeps_the_workers(server_pool):
    pid = server_pool.submit("work", None, _worker_pid).result(timeout=60)
    running = server_pool.submit("work", None, time.sleep, 1.0)
    time.sleep(0.2)
    done = pages.release_memory(lambda: 0)
    assert done["idle"] is False and done["recycled"] is False
    running.result(timeout=60)
    assert server_pool.submit("work", None, _worker_pid).result(timeout=60) == pid


def test_the_session_count_is_read_from_the_server_without_the_ended_session():
    class Server:
        sessions = {"a": object(), "b": object()}.values()

    class Context:
        server_context = Server()

    count = pages.sessions_of(Context())
    assert count() == 2
    assert "Context" not in repr(count.__closure__)  # only the server's context is kept
    assert pages.sessions_of(object()) is None
