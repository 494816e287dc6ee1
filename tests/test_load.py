"""Memory handed back after a class: what ``app.pages.release_memory`` does, checked in
this process. The served load test (``benchmarks/load_test.py --quick`` with two real pages
among the sessions) is in ``tests/browser/test_load_browser.py``.
"""
import sys
from pathlib import Path

import pytest


def _rss_mb() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


@pytest.mark.skipif(not Path("/proc/self/status").exists() or sys.platform != "linux",
                    reason="reads the resident memory from /proc")
def test_memory_freed_by_ended_sessions_goes_back_to_the_system():
    """What ``app.pages.release_memory`` (run a few seconds after sessions end) is for: the
    heap keeps freed blocks that live objects are scattered between, as after a class."""
    from app.pages import release_memory

    release_memory()
    blocks = [bytes(4000) for _ in range(40_000)]  # ~160 MB of heap blocks
    kept = blocks[::50]  # a few stay alive all over the heap
    del blocks
    before = _rss_mb()
    release_memory()
    after = _rss_mb()
    assert len(kept) == 800
    assert before - after > 80, (before, after)  # most of the 160 MB is handed back


def test_the_load_test_serves_with_the_images_allocator():
    """The load test measures the server as the image runs it: glibc's allocator in two
    arenas (Dockerfile ENV), or CPython's own when asked for comparison."""
    import json
    import subprocess

    from tests.dockerfile_replay import ROOT, dockerfile, image_env

    env = image_env(dockerfile())
    assert env["PYTHONMALLOC"] == "malloc" and env["MALLOC_ARENA_MAX"] == "2"
    code = ("import json, load_test as t; print(json.dumps([t.server_env(), "
            "t.server_env('python')]))\ntry:\n    t.server_env('jemalloc')\n"
            "except ValueError as e:\n    print(e)")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT / "benchmarks",
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    first, error = done.stdout.strip().splitlines()[-2:]
    image, python = json.loads(first)
    assert image == {"PYTHONMALLOC": "malloc", "MALLOC_ARENA_MAX": "2"}
    assert python["PYTHONMALLOC"] == "pymalloc"
    assert "allocator 'jemalloc'" in error


def test_the_departures_benchmark_serves_both_settings(tmp_path):
    """``benchmarks/bench_departures.py --quick``: pages leaving while one works, served
    with the collection deferred and at every departure; each measured and reported."""
    import json
    import subprocess

    root = Path(__file__).resolve().parents[1]
    done = subprocess.run([sys.executable, "benchmarks/bench_departures.py", "--quick",
                           "--out", str(tmp_path)], cwd=root, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads((tmp_path / "bench_departures.json").read_text())
    assert list(found["settings"]) == ["deferred (0.5)", "at every departure (0)"]
    for setting in found["settings"].values():
        assert setting["liveness"]["n"] > 20 and setting["moves"]["n"] > 5, setting
        assert setting["rss_mb"] > 50
    assert "1 of 4 pages leaving one by one" in done.stdout
    assert "collected at every departure (0): /liveness" in done.stdout
