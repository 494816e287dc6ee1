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


def _trace(*marks):
    return [{"t": t, "stage": stage} for stage, t in marks]


def test_a_page_in_two_parts_has_each_part_timed(steps):
    trace = _trace(("page build starts", 10.0), ("job submitted", 10.1),
                   ("page objects built", 10.2), ("page models start", 10.21),
                   ("page first part sent", 10.41), ("page rest starts", 10.42),
                   ("page sent", 10.72), ("result sent", 10.8))
    [page] = steps.page_steps(trace)
    assert page == pytest.approx({"objects": 0.2, "models, part 1": 0.2,
                                  "models, part 2": 0.3})


def test_a_page_in_one_message_and_the_next_page_are_told_apart(steps):
    trace = _trace(("page build starts", 1.0), ("page objects built", 1.7),
                   ("page models start", 1.71), ("page sent", 2.74),
                   ("page build starts", 5.0), ("page objects built", 5.25),
                   ("page models start", 5.26), ("page sent", 5.8))
    first, second = steps.page_steps(trace)
    assert first == pytest.approx({"objects": 0.7, "models, whole": 1.03})
    assert second == pytest.approx({"objects": 0.25, "models, whole": 0.54})
