"""``benchmarks/bench_class_arrival.py`` runs (pages opened together on a served dashboard)
so it cannot rot; its report is checked. Its Chromium mode: tests/browser/test_class_arrival.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_class_arrival_opens_pages_at_once_and_times_each(tmp_path):
    """``bench_class_arrival.py``: pages opened together on a served dashboard, each from
    an address of its own; every page's open and first plot timed, none turned away."""
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_class_arrival.py"),
                           "--pages", "3", "--rounds", "1", "--out", str(tmp_path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    report = json.loads((tmp_path / "class_arrival.json").read_text())
    [(url, server)] = report["servers"].items()
    [row] = server["rounds"]
    assert server["errors"] == [] and row["busy_pages"] == 0, server
    assert len(row["open_s"]) == len(row["first_plot_s"]) == 3, row
    # Page by page, the dashboard's first message read <= it applied <= its first plot
    # (then so for the sorted lists, which is what can be compared).
    steps = zip(sorted(row["first_part_s"]), sorted(row["open_s"]), sorted(row["first_plot_s"]))
    assert all(0 < read <= opened <= plot for read, opened, plot in steps), row
    assert 0 < server["open_p50_s"] <= server["open_max_s"], server
    assert f"{url}: page open p50" in done.stdout and "3 pages opened at once" in done.stdout


def test_class_arrival_refuses_pages_it_cannot_give_addresses(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_class_arrival.py"),
                           "--pages", "0", "--out", str(tmp_path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "--pages 0 --rounds 3: give 1-240 pages" in done.stderr
