"""``benchmarks/bench_page_steps.py``: the steps of each page's build read from the
server's trace (``app.trace``), a page in two parts and one in a single message."""
from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def steps(monkeypatch):
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    import bench_page_steps

    return bench_page_steps


def _step(name, seconds):
    return {"t": 0.0, "stage": "page step", "step": name, "seconds": seconds}


def test_a_page_in_parts_has_each_part_timed(steps):
    trace = [{"t": 10.0, "stage": "page build starts"}, {"t": 10.1, "stage": "job submitted"},
             _step("objects, part 1", 0.2), _step("objects, part 2", 0.1),
             {"t": 10.4, "stage": "page objects built"}, _step("models, part 1", 0.2),
             _step("models, part 2", 0.3), _step("models, part 3", 0.25),
             {"t": 10.72, "stage": "page sent"}, {"t": 10.8, "stage": "result sent"}]
    [page] = steps.page_steps(trace)
    assert page == {"objects, part 1": 0.2, "objects, part 2": 0.1, "models, part 1": 0.2,
                    "models, part 2": 0.3, "models, part 3": 0.25}


def test_a_page_in_one_message_and_the_next_page_are_told_apart(steps):
    trace = [{"t": 1.0, "stage": "page build starts"}, _step("objects", 0.7),
             _step("models, whole", 1.03), {"t": 5.0, "stage": "page build starts"},
             _step("objects", 0.25), _step("models, whole", 0.54)]
    first, second = steps.page_steps(trace)
    assert first == {"objects": 0.7, "models, whole": 1.03}
    assert second == {"objects": 0.25, "models, whole": 0.54}
