"""The dashboard latency benchmark runs (``--quick``) in the browser environment."""
import json
import subprocess
import sys

from .serving import ROOT


def test_dashboard_benchmark_quick(tmp_path, browser):  # browser: chromium is there
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_dashboard.py"),
                           "--quick", "--out", str(tmp_path)], cwd=ROOT, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    data = json.loads((tmp_path / "dashboard.json").read_text())
    assert data["server"]["support view compute"]["n"] > 0
    assert data["browser"]["key press -> redrawn"]["p95_ms"] < 1e4  # every press redrew
    # Each press is followed through the server (its trace) to the page, in order.
    stages = [k.removeprefix("key press -> ") for k in data["browser"] if k.startswith("key press")]
    for stage in ("server receives", "job submitted", "result sent", "browser receives"):
        assert data["browser"][f"key press -> {stage}"]["n"] > 0, stages
    medians = [data["browser"][f"key press -> {s}"]["p50_ms"] for s in
               ("server receives", "result sent", "drawn")]
    assert medians == sorted(medians), medians
