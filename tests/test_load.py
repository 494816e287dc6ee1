"""The dashboard under concurrent sessions: ``benchmarks/load_test.py --quick`` (6 sessions
moving sliders for 15 s against one ``panel serve app``, then a second, shorter round).

Checked: no errors (no failed or stalled session, no traceback in the server's log),
every session got its updates, the update latency stays bounded, the server's memory
settles (bounded after cleanup, no growth from the second round) and the server destroys
every closed session. The latencies themselves are reported by the script, not tested.
"""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: An update that takes this long means the server fell over (the script's own time-out
#: for one update is 30 s); the quick run's p95 is well under a second here.
P95_BOUND_MS = 10_000.0


def run_quick(out: Path, *extra) -> tuple[dict, subprocess.CompletedProcess]:
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "load_test.py"), "--quick",
                           "--out", str(out), *extra], cwd=ROOT, capture_output=True, text=True,
                          timeout=400)
    report_path = out / "load.json"
    assert report_path.exists(), done.stdout[-3000:] + done.stderr[-3000:]
    return json.loads(report_path.read_text()), done


def check(report: dict, done: subprocess.CompletedProcess, out: Path) -> None:
    sessions = report["settings"]["sessions"]
    assert report["n_errors"] == 0, "\n".join(report["errors"])
    assert report["sessions_with_updates"] == sessions
    assert report["updates"]["per_session_min"] >= 3  # each session kept getting updates
    assert report["updates"]["all"]["p95_ms"] < P95_BOUND_MS
    memory = report["memory_mb"]
    assert memory["after"]["total"] <= memory["bound_total"], memory
    assert memory["after_second_round"]["total"] <= memory["bound_total"], memory
    growth = memory["after_second_round"]["total"] - memory["after"]["total"]
    assert growth <= memory["second_round_growth_bound"], memory
    for cleanup in (report["cleanup"], report["second_round"]["cleanup"]):
        assert cleanup["destroyed"] == cleanup["sessions"] == sessions, cleanup
        assert cleanup["open_after"] == 0, cleanup
    assert report["destroyed_before_close"] == 0
    assert report["passed"] and done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "| no errors | pass |" in (out / "load.md").read_text()


@pytest.mark.slow
def test_quick_load(tmp_path):
    report, done = run_quick(tmp_path)
    check(report, done, tmp_path)
