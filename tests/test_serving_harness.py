"""The browser tests' server stops with the test process that started it: an interrupted
run (an xdist worker stopped mid-test) leaves no ``panel serve`` behind
(``tests/browser/serving.py``, ``_stop_with_parent``)."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent

PARENT = """
import os, subprocess, sys
from browser.serving import _stop_with_parent
child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         preexec_fn=_stop_with_parent)
print(child.pid, flush=True)
os._exit(1)  # dies without cleaning up, as a stopped worker does
"""


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(") ")[-1][0] != "Z"  # a zombie has ended
    except FileNotFoundError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="prctl is Linux's")
def test_a_process_started_for_the_tests_ends_with_its_parent():
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        p for p in (str(TESTS), os.environ.get("PYTHONPATH")) if p))
    out = subprocess.run([sys.executable, "-c", PARENT], env=env, capture_output=True,
                         text=True, timeout=60)
    pid = int(out.stdout.split()[0])
    deadline = time.monotonic() + 10
    while _alive(pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    alive = _alive(pid)
    if alive:
        os.kill(pid, 9)
    assert not alive, "the child outlived the process that started it"
