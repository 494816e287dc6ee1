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


def test_page_open_benchmark_measures_a_served_dashboard(tmp_path, app_server, browser):
    """``bench_page_open.py --url``: the server behind the URL is found, each open's CPU
    and wall time recorded (the warming open left out); a URL without a port is refused."""
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_page_open.py"),
                           "--opens", "1", "--url", app_server, "--out", str(tmp_path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    data = json.loads((tmp_path / "page_open.json").read_text())
    got = data["servers"][app_server.rstrip("/")]
    assert len(got["runs"]) == 1
    assert got["server_cpu_s"]["median"] > 0.05 and got["open_s"]["median"] > 0.1, got
    bad = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_page_open.py"),
                          "--url", "localhost"], cwd=ROOT, capture_output=True, text=True,
                         timeout=60)
    assert bad.returncode == 2 and "--url 'localhost'" in bad.stderr
