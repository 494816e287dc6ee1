"""Real pages opened together: ``benchmarks/bench_class_arrival.py --chromium`` (headless
Chromium pages, each an address of its own behind the server's ``--use-xheaders``, all
opened at the same moment). Checked: every page got its dashboard, none was turned away
or failed, and the report gives each page's time. The times themselves are reported by the
script, not tested: this machine is shared."""
import json
import subprocess
import sys

import pytest

from .serving import ROOT


@pytest.mark.slow
def test_chromium_pages_opened_together_each_get_the_dashboard(browser, tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_class_arrival.py"),
                           "--chromium", "--pages", "3", "--rounds", "1", "--out",
                           str(tmp_path)], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    report = json.loads((tmp_path / "class_arrival.json").read_text())
    assert report["chromium"] is True
    [(url, server)] = report["servers"].items()
    [row] = server["rounds"]
    assert server["errors"] == [], server["errors"]
    assert len(row["open_s"]) == 3 and all(t > 0 for t in row["open_s"]), row
    assert row["busy_pages"] == 0, row  # an address each: no page sent to the busy page
    assert "3 Chromium pages opened at once" in done.stdout and f"{url}: page open" in done.stdout
    log = (tmp_path / "class-arrival-serve.log").read_text()
    assert "Traceback" not in log, log[-3000:]
