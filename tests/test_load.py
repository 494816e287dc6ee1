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
