"""The dashboard under concurrent sessions: ``benchmarks/load_test.py --quick`` (6 sessions
against one ``panel serve app``: 15 s of the classroom profile, a move every ~3 s whether
or not the last one's data came, then 6 s of the continuous-drag profile).

Checked: no errors (no failed or stalled session, no traceback in the server's log),
every session of both rounds got its updates, the update latency stays bounded, the
server's memory settles (bounded after cleanup, no growth from the second round) and the
server destroys every closed session. The latencies themselves are reported by the
script (with the issue's targets, met or not), not tested: this machine is shared.
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
def test_quick_load(tmp_path):
    report, done = run_quick(tmp_path)
    check(report, done, tmp_path)


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
