"""``--cpu-report`` (``tests/cpu_report.py``) charges each test the CPU of the processes it
starts, also when the work spans two tests, and merges the xdist workers' parts."""
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent

#: A child that spins on the CPU for SPIN_S of its own CPU time.
SPIN_S = 0.6
SAMPLE = textwrap.dedent(f"""
    import subprocess, sys, time

    SPIN = ("import time\\nt = time.process_time()\\n"
            "while time.process_time() - t < {SPIN_S}: pass")
    left = []

    def test_a_child_spins():
        subprocess.run([sys.executable, "-c", SPIN], check=True)

    def test_b_starts_a_child_that_outlives_it():
        import psutil
        left.append(subprocess.Popen([sys.executable, "-c", SPIN]))
        child = psutil.Process(left[-1].pid)
        while sum(child.cpu_times()[:2]) < {SPIN_S / 3}:  # it has spun a while
            time.sleep(0.01)

    def test_c_waits_for_it():
        left.pop().wait()

    def test_d_sleeps():
        time.sleep(0.3)

    # A child that ignores SIGCHLD, as Chromium's zygote does: the grandchild it starts is
    # reaped without a trace in anyone's CPU times.
    ZYGOTE = (
        "import os, signal, subprocess, sys, time\\n"
        "signal.signal(signal.SIGCHLD, signal.SIG_IGN)\\n"
        "pid = subprocess.Popen([sys.executable, '-c', sys.argv[1]]).pid\\n"
        "while True:\\n"
        "    try:\\n"
        "        os.kill(pid, 0)\\n"
        "    except ProcessLookupError:\\n"
        "        break\\n"
        "    time.sleep(0.01)\\n")

    def test_f_a_grandchild_reaped_without_a_trace():
        subprocess.run([sys.executable, "-c", ZYGOTE, SPIN], check=True)
""")
#: A second module (with xdist, on the other worker: ``--dist loadfile``).
SECOND = SAMPLE.split("left = []")[0] + textwrap.dedent("""
    def test_e_spins_elsewhere():
        subprocess.run([sys.executable, "-c", SPIN], check=True)
""")


def _run(tmp_path: Path, *args: str) -> dict:
    (tmp_path / "test_sample.py").write_text(SAMPLE, encoding="utf-8")
    (tmp_path / "test_second.py").write_text(SECOND, encoding="utf-8")
    report = tmp_path / "cpu.json"
    stale = tmp_path / "cpu.json.parts"  # left by a run that was stopped
    stale.mkdir()
    (stale / "gw9.jsonl").write_text('{"test": "gone.py::test_old", "cpu_s": 9.0}\n')
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(TESTS), os.environ.get(
        "PYTHONPATH", "")])}
    command = [sys.executable, "-m", "pytest", "-p", "cpu_report", "-p", "no:cacheprovider",
               "-q", "--cpu-report", str(report), *args, "test_sample.py", "test_second.py"]
    done = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert "costliest modules" in done.stdout
    assert not (tmp_path / "cpu.json.parts").exists()
    return json.loads(report.read_text(encoding="utf-8"))


@pytest.mark.parametrize("workers", [["-n0"], ["-n", "2", "--dist", "loadfile"]],
                         ids=["one process", "xdist"])
def test_each_test_is_charged_its_processes_cpu(tmp_path, workers):
    found = _run(tmp_path, *workers)
    cpu = {row["test"].split("::")[1]: row["cpu_s"] for row in found["by_test"]}
    assert sorted(cpu) == ["test_a_child_spins", "test_b_starts_a_child_that_outlives_it",
                           "test_c_waits_for_it", "test_d_sleeps", "test_e_spins_elsewhere",
                           "test_f_a_grandchild_reaped_without_a_trace"]
    # the child's spin, and a Python start (~0.05 s here)
    assert SPIN_S <= cpu["test_a_child_spins"] < SPIN_S + 0.5
    # the second child is charged to the two tests it ran during, once
    shared = cpu["test_b_starts_a_child_that_outlives_it"] + cpu["test_c_waits_for_it"]
    assert SPIN_S <= shared < SPIN_S + 0.5, cpu
    assert cpu["test_b_starts_a_child_that_outlives_it"] >= SPIN_S / 3, cpu
    assert 0 <= cpu["test_d_sleeps"] < 0.1
    # seen while it ran: all but its last tenth of a second
    assert SPIN_S - 0.15 <= cpu["test_f_a_grandchild_reaped_without_a_trace"] < SPIN_S + 0.5
    module = found["modules"]["test_sample.py"]
    assert module["tests"] == 5
    assert module["cpu_s"] == pytest.approx(sum(cpu.values()) - cpu["test_e_spins_elsewhere"],
                                            abs=0.01)
    assert SPIN_S <= cpu["test_e_spins_elsewhere"] < SPIN_S + 0.5
    assert found["tests"] == 6
