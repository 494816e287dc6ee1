"""The dashboard under concurrent sessions: ``benchmarks/load_test.py --quick --browsers 2``
(6 protocol-level sessions against one ``panel serve app``: 15 s of the classroom profile,
a move every ~3 s whether or not the last one's data came, then 6 s of the continuous-drag
profile; two headless Chromium pages press theta0's arrow keys during the first round).

Checked: no errors (no failed or stalled session, no traceback in the server's log),
every session of both rounds and every real page got its updates, the update latency
stays bounded, the server's memory settles (bounded after cleanup, no growth from the
second round) and the server destroys every closed session. The latencies themselves are
reported by the script (with the issue's targets, met or not), not tested: this machine is
shared.
"""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from .serving import ROOT

#: An update that takes this long means the server fell over (the script's own time-out
#: for one update is 30 s); the quick run's p95 is well under a second here.
P95_BOUND_MS = 10_000.0


def run_quick(out: Path, *extra) -> tuple[dict, subprocess.CompletedProcess]:
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "load_test.py"), "--quick",
                           "--out", str(out), *extra], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)
    report_path = out / "load.json"
    assert report_path.exists(), done.stdout[-3000:] + done.stderr[-3000:]
    return json.loads(report_path.read_text()), done


def check(report: dict, done: subprocess.CompletedProcess, out: Path) -> None:
    sessions = report["settings"]["sessions"]
    assert report["n_errors"] == 0, "\n".join(report["errors"])
    assert [r["profile"] for r in report["rounds"]] == ["class", "drag"]
    for round_ in report["rounds"]:
        assert round_["sessions_with_updates"] == sessions
        # each session kept getting updates: a class session moves every 2-4 s
        assert round_["updates"]["per_session_min"] >= 3, round_["updates"]
        assert round_["updates"]["all"]["p95_ms"] < P95_BOUND_MS
    memory = report["memory_mb"]
    assert memory["after"]["total"] <= memory["bound_total"], memory
    assert memory["after_second_round"]["total"] <= memory["bound_total"], memory
    growth = memory["after_second_round"]["total"] - memory["after"]["total"]
    assert growth <= memory["second_round_growth_bound"], memory
    # the class left: the server replaced its idle workers by fresh ones (app.pages)
    assert all(r["workers_replaced"] for r in report["rounds"]), report["rounds"]
    for cleanup in (r["cleanup"] for r in report["rounds"]):
        assert cleanup["destroyed"] == cleanup["sessions"] == sessions, cleanup
        assert cleanup["open_after"] == 0, cleanup
    assert report["destroyed_before_close"] == 0
    assert report["passed"] and done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "| no errors | pass |" in (out / "load.md").read_text()


@pytest.mark.slow
def test_quick_load_with_real_pages(tmp_path, browser):  # browser: chromium is there
    report, done = run_quick(tmp_path, "--browsers", "2")
    check(report, done, tmp_path)
    pages = report["browser"]
    assert pages["presses"] >= 4 and pages["latencies"]["n"] == pages["presses"]
    assert pages["latencies"]["p95_ms"] < P95_BOUND_MS
