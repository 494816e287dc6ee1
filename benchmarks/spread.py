"""Medians with their spread (min and max over the repeats) for the benchmark reports."""
from __future__ import annotations

import math
import statistics
import time


def spread(samples) -> dict:
    """Median, min, max and count of a list of measurements."""
    samples = list(samples)
    return {"median": statistics.median(samples), "min": min(samples), "max": max(samples),
            "n": len(samples)}


def repeats_for(seconds: float, min_total=0.2, lo=3, hi=15) -> int:
    """Repeats of a run lasting `seconds`: until about `min_total` s in all, at least `lo`."""
    return max(lo, min(hi, math.ceil(min_total / max(seconds, 1e-9))))


def cell(median, lo, hi, fmt=lambda v: f"{v:.3g}") -> str:
    """A table cell "median [min–max]"."""
    return f"{fmt(median)} [{fmt(lo)}–{fmt(hi)}]"


def cold_runs(fn, clear, min_total, lo=3, hi=15):
    """``spread`` of ``fn()``'s seconds over runs each after ``clear()`` (cold caches),
    repeated until about ``min_total`` seconds in all and at least ``lo`` times; and the
    last value."""
    times, value = [], None
    while len(times) < (repeats_for(times[0], min_total, lo, hi) if times else 1):
        clear()
        start = time.perf_counter()
        value = fn()
        times.append(time.perf_counter() - start)
    return spread(times), value
