"""The benchmark scripts run (``--quick``) so they cannot rot; their reports are checked."""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(script: str, out: Path, *extra) -> str:
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / script), "--quick",
                           "--out", str(out), *extra], cwd=ROOT, capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout


def _spread_ok(lo, med, hi) -> bool:
    return 0 < lo <= med <= hi


@pytest.mark.slow
def test_support_benchmark_quick(tmp_path):
    _run("bench_support.py", tmp_path)
    report = (tmp_path / "support.md").read_text()
    assert "RK45/auto" in report and "Failed runs" in report
    assert "Scipy runs cut by the time cap:" in report
    # Every timing table gives the median with its min and max.
    assert "auto us [min–max]" in report and "us median [min–max]" in report
    data = json.loads((tmp_path / "support.json").read_text())
    assert data  # raw numbers written
    # The compiled methods beat scipy's RK45 at equal error on the default case.
    assert "| pendulum pi/2 |" in report
    for case in data["cases"].values():
        for rows in case["rows"].values():
            for r in (r for r in rows if r["success"]):
                assert _spread_ok(r["min_s"], r["seconds"], r["max_s"]) and r["n_runs"] >= 1
            for r in (r for r in rows if not r["success"]):
                assert r["status"]  # a cut or failed run says why
    # The work-precision figure has, per case, a panel against the energy-balance residual.
    html = tmp_path / "work_precision.html"
    if html.exists():  # bokeh installed
        text = html.read_text()
        for case in data["cases"]:
            assert f"error: {case}" in text and f"rel_energy: {case}" in text
        assert "energy-balance residual" in text
    png = tmp_path / "work_precision.png"
    if png.exists():  # two panels side by side: 500 px each (matplotlib) or 700 (browser)
        assert struct.unpack(">I", png.read_bytes()[16:20])[0] >= 1000


@pytest.mark.slow
def test_map_benchmark_quick(tmp_path):
    """The regime-map benchmark times a map and its first 8 x 8 picture, with the errors."""
    _run("bench_map.py", tmp_path)
    maps = json.loads((tmp_path / "map.json").read_text())["maps"]
    assert [(m["n"], m["F_N"]) for m in maps] == [(12, 3.0), (8, 3.0)]
    for m in maps:
        assert m["succeeded"] == m["points"] == m["n"] ** 2 and m["wall_s"] > 0
        assert m["max_quadrature_error"] <= 1e-3 and m["max_beta_residual"] <= 1e-4
    assert 0 < maps[0]["coarse_s"] < maps[0]["wall_s"]  # the 8 x 8 subgrid came first
    assert "| 3 | 8x8 | 1 |" in (tmp_path / "map.md").read_text()


@pytest.mark.slow
def test_arrays_benchmark_quick(tmp_path):
    _run("bench_arrays.py", tmp_path)
    data = json.loads((tmp_path / "arrays.json").read_text())
    assert {"timings", "tolerance_costs", "throughput", "peak_rss_mb"} <= data.keys()
    assert all(r["median_ms"] > 0 for r in data["timings"])
    for r in data["timings"] + data["tolerance_costs"]:
        ms = r.get("median_ms", r.get("ms"))
        assert _spread_ok(r["min_ms"], ms, r["max_ms"]) and r["runs"] >= 1
    # Both throughputs measured and reported; which is faster is the benchmark's finding
    # (a timing compared inside a test flakes on a busy machine).
    assert data["throughput"]["batch_per_s"] > 0 and data["throughput"]["single_per_s"] > 0
    report = (tmp_path / "arrays.md").read_text()
    assert report.count("ms median [min–max]") == 2 and "trajectories/s in one batch" in report


@pytest.fixture(scope="module")
def dashboard_run(tmp_path_factory):
    """One quick ``run_all.py`` of the dashboard's server side, with its report: (folder,
    the printed output, the report's text). Shared by the tests below."""
    out = tmp_path_factory.mktemp("run_all")
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "run_all.py"), "--quick",
                           "--no-browser", "--only", "bench_dashboard.py", "--out", str(out),
                           "--report", str(out / "report.md")],
                          cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return out, done.stdout, (out / "report.md").read_text()


@pytest.mark.slow
def test_run_all_dashboard_server_side(dashboard_run):
    """run_all.py runs a script and totals its time; the dashboard table has min/max."""
    out, stdout, _ = dashboard_run
    summary = json.loads((out / "run_all.json").read_text())
    assert list(summary["scripts"]) == ["bench_dashboard.py"]
    assert summary["total"]["wall_s"] > 0 and "total" in stdout
    report = (out / "dashboard.md").read_text()
    assert "median ms [min–max]" in report and "| support view compute |" in report
    data = json.loads((out / "dashboard.json").read_text())
    for s in data["server"].values():
        assert _spread_ok(s["min_ms"], s["p50_ms"], s["max_ms"])
    cost = data["server_cost"]
    for move in ("theta0", "k_r"):
        payload = cost[f"{move} move payload"]
        assert payload["binary_kB"] > payload["json_kB"] > 0  # the arrays travel as binary
        assert cost[f"{move} move: update + patch"]["p50_ms"] > 0
    assert "binary buffers" in report


def _row(report: str, name: str) -> list[str]:
    line = next(ln for ln in report.splitlines() if ln.startswith(f"| {name} |"))
    return [c.strip() for c in line.strip("|").split("|")]


@pytest.mark.slow
def test_report_gives_the_machine_date_load_and_spreads_of_the_run(dashboard_run):
    """``--report`` writes a page from the run's JSON: the machine and versions, the date,
    the load around each script, and each figure as median [min–max] from that run."""
    out, _, report = dashboard_run
    summary = json.loads((out / "run_all.json").read_text())
    machine, run = summary["machine"], summary["scripts"]["bench_dashboard.py"]
    assert f"on {machine['date']} in **quick** mode" in report
    assert f"machine: {machine['cpu']}, {machine['cores']} cores" in report
    for lib in ("python", "numpy", "numba", "panel"):
        assert f"{lib} {machine[lib]}" in report
    load = " / ".join(f"{v:.2f}" for v in run["loadavg_before"])
    assert _row(report, "bench_dashboard.py")[3] == load
    assert f"load average {load} before" in report
    data = json.loads((out / "dashboard.json").read_text())
    for name, s in data["server"].items():  # the page's figures are the JSON's
        assert _row(report, name)[2] == f"{s['p50_ms']:.1f} [{s['min_ms']:.1f}–{s['max_ms']:.1f}]"


@pytest.mark.slow
def test_report_takes_no_figure_from_an_earlier_run(dashboard_run, tmp_path):
    """A benchmark's JSON older than the run (left over in the folder) gives no figures."""
    out, _, report = dashboard_run
    shutil.copytree(out, tmp_path / "run")
    json_path = tmp_path / "run" / "dashboard.json"
    started = json.loads((tmp_path / "run" / "run_all.json").read_text())[
        "scripts"]["bench_dashboard.py"]["started"]
    os.utime(json_path, (started - 60, started - 60))
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "report.py"),
                           str(tmp_path / "run"), str(tmp_path / "stale.md")],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    stale = (tmp_path / "stale.md").read_text()
    assert "No figures: `bench_dashboard.py` wrote no `dashboard.json` during this run." in stale
    assert "| support view compute |" in report and "| support view compute |" not in stale


#: Ways a script would put the repository on the import path, or reach past a cache.
_PATH_EDITS = re.compile(r"sys\.path\s*(\.(insert|append|extend)|\[|=|\+=)|"
                         r"environ\[[\"']PYTHONPATH|PYTHONPATH[\"']\s*:|noqa: E402|__wrapped__")


def test_no_benchmark_edits_the_import_path():
    """The benchmarks import the installed package: none edits ``sys.path`` or the
    ``PYTHONPATH`` of its children, and none calls a cached function's ``__wrapped__``."""
    scripts = sorted((ROOT / "benchmarks").glob("*.py"))
    assert len(scripts) > 20
    found = [f"{p.name}:{i}: {line.strip()}" for p in scripts
             for i, line in enumerate(p.read_text().splitlines(), 1) if _PATH_EDITS.search(line)]
    assert not found, "\n".join(found)


def test_busy_core_runs_the_command_beside_a_spinning_process():
    """``busy_core.py`` keeps a spinner running while the command runs (the command sees a
    process using a whole core), passes the command's exit code on and leaves no spinner."""
    probe = ("import os, sys, time\n"
             "def spinners():\n"
             "    found = []\n"
             "    for pid in filter(str.isdigit, os.listdir('/proc')):\n"
             "        try:\n"
             "            cmd = open(f'/proc/{pid}/cmdline', 'rb').read()\n"
             "        except OSError:\n"
             "            continue\n"
             "        if b'deadline = ' + b'time.monotonic()' in cmd:\n"
             "            found.append(pid)\n"
             "    return found\n"
             "def stat(pid):\n"
             "    f = open(f'/proc/{pid}/stat').read().rsplit(')', 1)[1].split()\n"
             "    return f[0], (int(f[11]) + int(f[12])) / os.sysconf('SC_CLK_TCK')\n"
             "pids = spinners()\n"
             "assert len(pids) == 1, pids\n"
             "c0 = stat(pids[0])[1]; states = []\n"
             "for _ in range(20):\n"
             "    time.sleep(0.05); states.append(stat(pids[0])[0])\n"
             "used = stat(pids[0])[1] - c0\n"
             # always running or runnable (a sleeping process shows S): its share of a core
             # is what the machine's load leaves it, so only 'some CPU' is asked for
             "assert set(states) == {'R'} and used > 0.02, (states, used)\n"
             "sys.exit(7)\n")
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "busy_core.py"), "--",
                           sys.executable, "-c", probe], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 7, done.stderr
    assert "1 core(s) kept busy" in done.stderr
    left = subprocess.run(["pgrep", "-f", "deadline = time.monotonic"], capture_output=True)
    assert left.returncode == 1, "a spinner outlived the command"


def test_cpu_by_process_sums_a_commands_processes_by_kind(tmp_path):
    """``cpu_by_process.py`` counts the CPU of the command's descendants (here a child
    that spins ~1 s), by kind, and passes the command's exit code on."""
    spin = ("import subprocess, sys; subprocess.run([sys.executable, '-c', 'import time\\n"
            "t = time.process_time()\\nwhile time.process_time() - t < 1.0: pass']); "
            "sys.exit(3)")
    out = tmp_path / "cpu.json"
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "cpu_by_process.py"),
                           "--interval", "0.1", "--out", str(out), "--", sys.executable,
                           "-c", spin], capture_output=True, text=True, timeout=60)
    assert done.returncode == 3, done.stderr
    report = json.loads(out.read_text())
    assert [r["kind"] for r in report["rows"]] == ["python -c import"], report
    assert 0.7 <= report["rows"][0]["cpu_s"] <= 1.5, report  # the child's spin, seen
    assert report["rows"][0]["processes"] == 2, report  # the command and its child
    # The whole machine was busy at least as long as the child spun.
    assert report["machine_busy_s"] >= 0.7, report
    assert "the machine busy" in done.stderr
    assert "| process kind | CPU s | share | processes |" in done.stdout


@pytest.mark.slow
def test_friction_fit_benchmark_quick(tmp_path):
    _run("bench_friction_fit.py", tmp_path)
    report = (tmp_path / "friction_fit.md").read_text()
    assert "| fit_friction |" in report and "| curve_fit |" in report
    data = json.loads((tmp_path / "friction_fit.json").read_text())
    for r in data["fit"].values():
        s = r["seconds"]
        assert _spread_ok(s["min"], s["median"], s["max"]) and r["converged"] == r["runs"]
    assert data["speeds"]["n"] == 5 and data["speeds"]["success"]
    t = data["speeds"]["seconds"]
    assert _spread_ok(t["min"], t["median"], t["max"]) and t["n"] == 2
    assert "median [min–max] over 2 runs" in report


def test_message_benchmark_encodes_real_moves_both_ways(tmp_path):
    """``bench_messages.py``: a move's message encoded by Bokeh's serializer and by one that
    makes references as met gives the same message (the script checks it and fails
    otherwise), on the dashboard's page as served; each figure with its spread."""
    out = _run("bench_messages.py", tmp_path)
    found = json.loads((tmp_path / "bench_messages.json").read_text())
    assert found["models"] >= 400 and 1 <= found["messages"] <= 6, found
    for key in ("bokeh_ms", "as_met_ms", "events", "buffers", "json_bytes"):
        assert _spread_ok(found[key]["min"], found[key]["median"], found[key]["max"]), key
    rows = found["rows"]
    assert all(r["buffers"] >= 1 and r["events"] >= 1 for r in rows), rows
    assert {r["slider"] for r in rows} <= {"F_N", "k_r", "k_theta", "theta0"}
    assert "Bokeh's table of references" in out and f"{found['models']} models" in out


@pytest.mark.slow
def test_served_moves_are_measured_and_profiled(tmp_path):
    """``bench_dashboard.py --served K --served-profile``: the served server's CPU per move
    over blocks, the messages and arrays per move, and where its time went (py-spy), or why
    there is no profile."""
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_dashboard.py"),
                           "--quick", "--no-browser", "--served", "1", "--served-profile",
                           "--out", str(tmp_path)], cwd=ROOT, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    served = json.loads((tmp_path / "dashboard.json").read_text())["served"]
    assert len(served["ms"]) == 2 and all(ms > 0 for ms in served["ms"]), served
    assert all(n >= 1 for n in served["messages per move"]), served
    assert all(n >= 1 for n in served["arrays per move"]), served
    report = (tmp_path / "dashboard.md").read_text()
    assert "Served, 1 sessions, 2 blocks of 3 moves" in report
    profiled = served["profile"]
    if "error" in profiled:  # py-spy is the bench extra's, not the tests'; or not allowed
        assert profiled["error"].startswith("py-spy"), profiled  # says why
        assert f"No profile of the served moves: {profiled['error']}" in report
    else:
        assert profiled["by_process"]["server"] > 0 and "server" in profiled["layers"]
        assert "Where the served server's time went" in report
    assert (tmp_path / "served-profile.txt").exists() == ("error" not in profiled)


def test_served_profile_needs_served_sessions(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_dashboard.py"),
                           "--served-profile", "--out", str(tmp_path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "--served-profile needs --served K" in done.stderr


def test_profile_summary_counts_waiting_threads_as_idle(tmp_path):
    """``load_profile.py``: a thread blocked in its selector or on a condition is waiting,
    not busy; the busy samples go to the layer of their innermost frame."""
    loop = "<module> (panel:8);BaseEventLoop.run_forever (asyncio/base_events.py:607)"
    raw = tmp_path / "raw.txt"
    raw.write_text("\n".join([
        f"{loop};EpollSelector.select (selectors.py:468) 50",
        "Thread._bootstrap (threading.py:1002);_PollLikeSelector.select (selectors.py:415) 30",
        "Thread._bootstrap (threading.py:1002);Condition.wait (threading.py:327) 10",
        f"{loop};patch_doc.create (bokeh/protocol/messages/patch_doc.py:89);"
        "Serializer.__init__ (bokeh/core/serialization.py:226) 7",
        f"{loop};Parameter.__set__ (param/parameterized.py:2058) 3"]) + "\n")
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "load_profile.py"),
                           str(raw)], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = [[c.strip() for c in line.strip("|").split("|")]
            for line in done.stdout.splitlines() if line.startswith("| server |")]
    assert [(r[1], r[2], r[3]) for r in rows] == [
        ("idle (waiting)", "90", ""), ("Bokeh serialisation (JSON, buffers)", "7", "70%"),
        ("param", "3", "30%")], rows


def test_profile_summary_counts_each_dashboard_function_with_what_it_calls(tmp_path):
    """``load_profile.py``: a dashboard function's share is of the server's busy samples
    with it on the stack (counted once per stack, lines merged); waiting and the sleeping
    watchdog are not busy."""
    loop = "<module> (panel:8);BaseEventLoop.run_forever (asyncio/base_events.py:607)"
    locked = "Slot._locked.<locals>.locked (app/slot.py:278)"
    raw = tmp_path / "raw.txt"
    raw.write_text("\n".join([
        f"{loop};EpollSelector.select (selectors.py:468) 40",
        "Thread._bootstrap (threading.py:1002);WorkPool._watch (app/jobs.py:210) 20",
        f"{loop};{locked};SupportView._draw_support (app/views/support.py:153);"
        "Parameter.__set__ (param/parameterized.py:2058) 6",
        f"{loop};{locked};SupportView._draw_support (app/views/support.py:163);"
        "SupportView._draw_support (app/views/support.py:170) 2",
        f"{loop};{locked};HeadlineView._write (app/views/readouts.py:310) 4",
        f"{loop};Serializer.__init__ (bokeh/core/serialization.py:226) 8"]) + "\n")
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "load_profile.py"),
                           str(raw)], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = {r[0].strip("` "): (r[1].strip(), r[2].strip()) for r in
            ([c for c in line.strip("|").split("|")] for line in done.stdout.splitlines()
             if line.startswith("| `") and "(app/" in line and "server:" not in line)}
    assert rows == {"Slot._locked.<locals>.locked (app/slot.py)": ("12", "60%"),
                    "SupportView._draw_support (app/views/support.py)": ("8", "40%"),
                    "HeadlineView._write (app/views/readouts.py)": ("4", "20%")}, rows


@pytest.mark.slow
def test_diagnostics_benchmark_measures_both_settings(tmp_path):
    """``bench_diagnostics.py``: a page build and slider moves with Bokeh's diagnostics on
    and off, each figure with its spread, and the attribute misses a move makes."""
    out = _run("bench_diagnostics.py", tmp_path)
    found = json.loads((tmp_path / "bench_diagnostics.json").read_text())
    assert found["rounds"] == 1 and found["moves"] == 4
    for setting in ("on", "off"):
        for key in ("build_s", "move_ms"):
            s = found[setting][key]
            assert _spread_ok(s["min"], s["median"], s["max"]), (setting, key, s)
        assert found[setting]["misses_per_move"]["median"] >= 1, found[setting]
    assert "diagnostics on" in out and "diagnostics off" in out
    from bokeh.settings import settings
    assert settings.perform_error_diagnostics() is True  # this process untouched


@pytest.mark.slow
def test_steady_design_benchmark_measures_both_designs(tmp_path):
    """``bench_steady_design.py``: a page build and slider moves with Panel's design and the
    served dashboard's, each figure with its spread; only Panel's works its design out at a
    move."""
    out = _run("bench_steady_design.py", tmp_path)
    found = json.loads((tmp_path / "bench_steady_design.json").read_text())
    assert found["rounds"] == 1 and found["moves"] == 4
    for design in ("native", "steady"):
        for key in ("build_s", "move_ms"):
            s = found[design][key]
            assert _spread_ok(s["min"], s["median"], s["max"]), (design, key, s)
    assert found["native"]["worked_out_per_move"] >= 1, found["native"]
    assert found["steady"]["worked_out_per_move"] == 0, found["steady"]
    assert "native:" in out and "steady:" in out


@pytest.mark.slow
def test_worker_start_benchmark_measures_both_ways(tmp_path):
    """``bench_worker_start.py``: a lane's new workers answering, forked by the server's fork
    server (its own first round apart) and spawned, each figure with its spread."""
    out = _run("bench_worker_start.py", tmp_path)
    found = json.loads((tmp_path / "worker_start.json").read_text())
    assert set(found) == {"spawn", "server's (fork server)",
                          "server's (fork server), first round (the fork server starts)"}
    assert [len(found[k]["wall_s"]) for k in sorted(found)] == [1, 1, 2]
    for name, r in found.items():
        for key in ("wall_s", "cpu_s", "rss_mb", "pss_mb"):
            assert all(v > 0 for v in r[key]), (name, key, r)
        assert all(pss <= rss for pss, rss in zip(r["pss_mb"], r["rss_mb"])), (name, r)
    assert "| spawn | 2 |" in out and "| server's (fork server) | 1 |" in out

