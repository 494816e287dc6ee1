"""The load test with real pages among the protocol clients: two headless Chromium pages
press theta0's arrow keys while four protocol-level sessions move sliders
(``benchmarks/load_test.py --browsers``); every page gets its updates, nothing fails."""
import json
import subprocess
import sys

import pytest

from .serving import ROOT


@pytest.mark.slow
def test_pages_get_their_updates_under_load(tmp_path, browser):  # browser: chromium is there
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "load_test.py"),
                           "--sessions", "4", "--browsers", "2", "--duration", "12",
                           "--drag-duration", "8",
                           "--out", str(tmp_path)], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)
    report_path = tmp_path / "load.json"
    assert report_path.exists(), done.stdout[-3000:] + done.stderr[-3000:]
    report = json.loads(report_path.read_text())
    assert report["n_errors"] == 0, "\n".join(report["errors"])
    pages = report["browser"]
    assert pages["presses"] >= 4 and pages["latencies"]["n"] == pages["presses"]
    assert pages["latencies"]["p95_ms"] < 10_000
    assert [r["sessions_with_updates"] for r in report["rounds"]] == [4, 4]
    assert report["passed"] and done.returncode == 0, done.stdout[-3000:]
