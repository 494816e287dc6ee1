"""The benchmark scripts run (``--quick``) so they cannot rot; their reports are checked."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(script: str, out: Path, *extra) -> str:
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / script), "--quick",
                           "--out", str(out), *extra], cwd=ROOT, capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout


@pytest.mark.slow
def test_support_benchmark_quick(tmp_path):
    _run("bench_support.py", tmp_path)
    report = (tmp_path / "support.md").read_text()
    assert "RK45/auto" in report and "Failed runs" in report
    data = json.loads((tmp_path / "support.json").read_text())
    assert data  # raw numbers written
    # The compiled methods beat scipy's RK45 at equal error on the default case.
    assert "| pendulum pi/2 |" in report


@pytest.mark.slow
def test_arrays_benchmark_quick(tmp_path):
    _run("bench_arrays.py", tmp_path)
    data = json.loads((tmp_path / "arrays.json").read_text())
    assert {"timings", "tolerance_costs", "throughput", "peak_rss_mb"} <= data.keys()
    assert all(r["median_ms"] > 0 for r in data["timings"])
    assert data["throughput"]["batch_per_s"] > data["throughput"]["single_per_s"]
