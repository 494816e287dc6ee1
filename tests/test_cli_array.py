"""``python -m model array`` and ``python -m model sweep``: JSON, summaries, CSV, errors, Ctrl-C."""
import io
import json
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from model import fixed_orientation, uniform_array
from model.runs import sweeps
from model.cli import main
from model.cli.array import QUADRATURE_KEYS
from model.cli.sweep import ProgressBar
from model.contact.params import REGIMES

ARRAY_KEYS = {"FTx_over_mu0FN", "FTx_over_mu0FN_duration", "FTy_over_mu0FN", "Dy_over_Dx",
              "Nc_over_Nc0", "beta", "work_split", "quadrature_error", "success", "message",
              "params", "orientation", "dtheta_rms", "dr_rms"}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def strict_json(text: str) -> dict:
    def reject(constant):
        raise AssertionError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=reject)


def test_array_fixed_json(capsys):
    code, out, err = run(capsys, "array", "--regime", "slider", "--orientation", "fixed",
                         "--theta0", "1.2", "--json")
    assert (code, err) == (0, "")
    record = strict_json(out)
    assert ARRAY_KEYS <= record.keys() and record["orientation"] == "fixed"
    expected = fixed_orientation(REGIMES["slider"].replace(theta0=1.2))
    for key in ("FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0", "beta"):
        assert record[key] == getattr(expected, key), key
    assert record["FTx_over_mu0FN_duration"] == record["FTx_over_mu0FN"]
    assert record["quadrature_error"] == dict.fromkeys(QUADRATURE_KEYS, 0.0)
    assert record["work_split"] == expected.work_split
    assert record["params"]["theta0"] == 1.2 and record["success"] is True


def test_theta0_alone_means_fixed(capsys):
    code, out, _ = run(capsys, "array", "--k-r", "3", "--k-theta", "0.01", "--theta0", "0.5",
                       "--beta", "1", "--json")
    record = strict_json(out)
    assert code == 0 and record["orientation"] == "fixed"
    assert record["beta"] == 1.0 and record["params"]["theta0"] == 0.5


def test_array_uniform_json(capsys):
    code, out, err = run(capsys, "array", "--regime", "soft", "--tol", "1e-2", "--json")
    assert (code, err) == (0, "")
    record = strict_json(out)
    assert ARRAY_KEYS <= record.keys() and record["orientation"] == "uniform"
    expected = uniform_array(REGIMES["soft"], tol=1e-2)
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0", "beta",
                "n_members", "n_failed", "n_pivot"):
        assert record[key] == getattr(expected, key), key
    assert record["FTy_over_mu0FN"] == 0.0
    assert set(record["quadrature_error"]) == set(QUADRATURE_KEYS)
    assert record["quadrature_error"] == expected.quadrature_error


def test_array_summaries_name_both_averages(capsys):
    code, out, _ = run(capsys, "array", "--regime", "pendulum", "--tol", "1e-2")
    assert code == 0
    rows = {line.split()[0]: line for line in out.splitlines() if line.startswith("  ")}
    assert "paper average over supports (Eq. 10)" in rows["FTx_over_mu0FN"]
    assert "duration-weighted" in rows["FTx_over_mu0FN_duration"]
    assert "+-" in rows["FTx_over_mu0FN"] and "n_members" in rows
    code, out, _ = run(capsys, "array", "--regime", "pendulum", "--orientation", "fixed")
    assert code == 0 and "equal to the paper average" in out and "+-" not in out


def test_sweep_writes_csv(capsys, tmp_path):
    path = tmp_path / "map.csv"
    code, out, err = run(capsys, "sweep", "regime-map", "--n", "2", "--tol", "1e-2",
                         "--out", str(path))
    assert code == 0
    assert out.startswith("regime-map: 4 points, 4 succeeded") and out.count("\n") == 1
    assert "] 4/4" in err and err.endswith("\n")
    written = sweeps.read_csv(path)
    expected = sweeps.regime_map(n=2, tol=1e-2)
    assert list(written.columns) == list(expected.columns)
    for name, values in expected.columns.items():
        np.testing.assert_array_equal(written.columns[name], values, err_msg=name)


def test_sweep_orientation_and_load_options(capsys, tmp_path):
    path = tmp_path / "polar.csv"
    code, _, _ = run(capsys, "sweep", "orientation", "--regime", "pendulum", "--n", "3",
                     "--F-N", "2", "--out", str(path))
    table = sweeps.read_csv(path)
    assert code == 0 and table.kind == "orientation" and table.settings["F_N"] == 2.0
    np.testing.assert_allclose(table.columns["theta0"], [math.pi / 6, math.pi / 2, 5 * math.pi / 6])
    code, _, _ = run(capsys, "sweep", "load", "--regime", "stiff", "--n", "2", "--tol", "1e-2",
                     "--workers", "2", "--out", str(path))
    table = sweeps.read_csv(path)
    assert code == 0 and table.columns["regime"].tolist() == ["stiff", "stiff"]
    assert table.settings["workers"] == 2


BAD = [
    (["array", "--regime", "soft", "--k-r", "-1"], "--k-r", "k_r=-1.0 is invalid"),
    (["array", "--k-r", "1"], "--k-theta", "required unless --regime is given"),
    (["array", "--regime", "soft", "--F-N", "0"], "--F-N", "F_N=0.0 is invalid"),
    (["array", "--regime", "soft", "--beta", "1.5"], "--beta", "beta=1.5 is invalid"),
    (["array", "--regime", "soft", "--beta", "half"], "--beta", "'half' is not a number"),
    (["array", "--regime", "soft", "--tol", "0"], "--tol", "tol=0.0 is invalid"),
    (["array", "--regime", "soft", "--rtol", "1"], "--rtol", "rtol=1.0 is invalid"),
    (["array", "--regime", "soft", "--orientation", "fixed", "--tol", "1e-2"], "--tol",
     "only with --orientation uniform"),
    (["array", "--regime", "soft", "--orientation", "uniform", "--theta0", "1"], "--theta0",
     "only with --orientation fixed"),
    (["array", "--regime", "soft", "--theta0", "9"], "--theta0", "theta0=9.0 is invalid"),
    (["array", "--regime", "soft", "--orientation", "random"], "--orientation", "invalid choice"),
    (["sweep", "regime-map", "--n", "0", "--out", "x.csv"], "--n", "n=0 must be"),
    (["sweep", "regime-map", "--n", "2.5", "--out", "x.csv"], "--n", "'2.5' is not a whole number"),
    (["sweep", "stiffness", "--workers", "0", "--out", "x.csv"], "--workers", "workers=0 must be"),
    (["sweep", "stiffness", "--tol", "1", "--out", "x.csv"], "--tol", "tol=1.0 is invalid"),
    (["sweep", "stiffness", "--F-N", "-2", "--out", "x.csv"], "--F-N", "F_N=-2.0 is invalid"),
    (["sweep", "load", "--F-N", "2", "--out", "x.csv"], "--F-N", "not used by the load sweep"),
    (["sweep", "regime-map", "--regime", "soft", "--out", "x.csv"], "--regime", "not used by"),
    (["sweep", "orientation", "--out", "x.csv"], "--regime", "required for the orientation"),
    (["sweep", "orientation", "--regime", "soft", "--workers", "2", "--out", "x.csv"],
     "--workers", "not used by the orientation sweep"),
    (["sweep", "load", "--scheduler", "nowhere", "--out", "x.csv"], "--scheduler",
     "scheduler='nowhere' is not a reachable address"),
    (["sweep", "load", "--scheduler", "tcp://h:1", "--workers", "2", "--out", "x.csv"],
     "--workers", "workers=2 must be 1 when a scheduler is given"),
    (["sweep", "load", "--out", "/no/such/dir/x.csv"], "--out", "does not exist"),
    (["sweep", "load"], "--out", "required"),
    (["sweep", "polar", "--out", "x.csv"], "kind", "invalid choice: 'polar'"),
]


@pytest.mark.parametrize("argv, flag, detail", BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_flags_exit_2_with_one_line(capsys, argv, flag, detail):
    if "--scheduler" in argv:
        pytest.importorskip("distributed")
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.endswith("\n")
    assert err.startswith(f"python -m model {argv[0]}") and f"error: {flag}: " in err
    assert detail in err


def test_ctrl_c_cancels_cleanly(tmp_path):
    """SIGINT to the whole process group, as a terminal's Ctrl-C: exit 130, no traceback.

    The sweep starts as from a terminal, whatever this test process inherited: Ctrl-C at
    its default disposition and not blocked (a process that ignores or blocks SIGINT
    passes that on to its children, and the sweep then ran to its end in the full suite),
    and it computes into an empty cache of its own (cached points end in milliseconds)."""
    path = tmp_path / "map.csv"
    env = {**os.environ, "MICROPILLAR_CACHE_DIR": str(tmp_path / "cache")}
    here = (signal.getsignal(signal.SIGINT), signal.pthread_sigmask(signal.SIG_BLOCK, []))

    def as_from_a_terminal():
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
        signal.signal(signal.SIGINT, signal.SIG_DFL)
    proc = subprocess.Popen(
        [sys.executable, "-m", "model", "sweep", "regime-map", "--n", "6", "--workers", "2",
         "--out", str(path)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        start_new_session=True, env=env, preexec_fn=as_from_a_terminal)
    try:
        seen = b""
        while b"/36" not in seen:  # the first progress line
            chunk = proc.stderr.read(1)
            assert chunk, f"sweep ended early: {seen!r}"
            seen += chunk
        start = time.perf_counter()
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    err = (seen + err).decode()
    assert proc.returncode == 130 and out == b"", f"{err}\n(this process's SIGINT: {here})"
    assert "Traceback" not in err and "cancelled after" in err
    assert time.perf_counter() - start < 10
    assert not path.exists()


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_bar_redraws_on_a_terminal_and_logs_tenths_elsewhere():
    term, log = _Terminal(), io.StringIO()
    for stream in (term, log):
        bar = ProgressBar(stream, width=10)
        for done in range(1, 21):
            bar(done, 20)
        bar.close()
    assert term.getvalue().count("\r") == 20 and term.getvalue().endswith(" s\n")
    assert term.getvalue().rsplit("\r", 1)[1].startswith("[##########] 20/20")
    lines = log.getvalue().splitlines()
    assert "\r" not in log.getvalue() and len(lines) == 11
    assert lines[0].startswith("[..........] 1/20") and lines[-1].startswith("[##########] 20/20")


# --------------------------------------------------------------------------- resources, --out

@pytest.fixture
def no_sweep(monkeypatch):
    """Every sweep function replaced by one that fails the test: the checks below must
    answer before any sweep starts (or builds its parameter sets)."""
    from model.cli import sweep as sweep_cli

    def started(**kwargs):
        pytest.fail("the sweep started although its arguments were refused")

    monkeypatch.setattr(sweep_cli, "SWEEPS", {k: (started, v[1])
                                               for k, v in sweep_cli.SWEEPS.items()})


HUGE = [
    (["regime-map", "--n", "100000"], "--n", "10,000,000,000 points of the regime-map sweep"),
    (["orientation", "--regime", "soft", "--n", "1e8"], "--n", "100,000,000 points"),
    (["load", "--n", "1e12"], "--n", "4,000,000,000,000 points"),
    (["stiffness", "--n", "1e11"], "--n", "600,000,000,000 points"),
    (["load", "--workers", "100000"], "--workers", "100,000 worker processes"),
]


@pytest.mark.parametrize("argv, flag, detail", HUGE, ids=[" ".join(h[0]) for h in HUGE])
def test_sweep_size_is_checked_against_memory_before_starting(capsys, tmp_path, no_sweep,
                                                              argv, flag, detail):
    code, out, err = run(capsys, "sweep", *argv, "--out", str(tmp_path / "x.csv"))
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert f"error: {flag}: " in err and detail in err and "of memory" in err
    assert list(tmp_path.iterdir()) == []


def test_orientation_sweep_of_1e8_angles_is_one_line_in_a_fresh_process(tmp_path):
    """Once a traceback (the arrays of 1e8 contacts); now the usage error, exit 2."""
    proc = subprocess.run(
        [sys.executable, "-m", "model", "sweep", "orientation", "--regime", "soft", "--n",
         "1e8", "--out", str(tmp_path / "polar.csv")],
        capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert proc.stderr.startswith("python -m model sweep: error: --n: ")


def test_support_samples_are_checked_against_memory(capsys, monkeypatch):
    from model.cli import _common

    monkeypatch.setattr(_common, "memory_budget", lambda: 10_000_000)
    code, out, err = run(capsys, "support", "--regime", "soft", "--samples", "1000000",
                         "--json")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "error: --samples: 1,000,000 samples would need about" in err


@pytest.mark.parametrize("kind", ["regime-map", "orientation"])
def test_out_on_a_folder_is_refused_before_any_work(capsys, tmp_path, no_sweep, kind):
    argv = ["sweep", kind, "--out", str(tmp_path)]
    if kind == "orientation":
        argv[2:2] = ["--regime", "soft"]
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "error: --out: " in err and "is a folder" in err


def test_out_in_an_unwritable_folder_is_refused_before_any_work(capsys, tmp_path, no_sweep,
                                                                monkeypatch):
    """The check creates a file there (root ignores permission bits, so the refusal of a
    read-only folder is simulated where the file is created)."""
    import errno

    from model.cli import _common

    def refuse(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(_common.tempfile, "mkstemp", refuse)
    code, out, err = run(capsys, "sweep", "regime-map", "--out", str(tmp_path / "x.csv"))
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "error: --out: cannot write into" in err and "Permission denied" in err


def test_out_on_a_device_is_refused(capsys, no_sweep):
    code, _, err = run(capsys, "sweep", "regime-map", "--out", os.devnull)
    assert code == 2 and "is not a regular file" in err


def test_csv_is_replaced_whole_or_not_at_all(capsys, tmp_path, monkeypatch):
    """A write that fails half-way leaves the previous file as it was, and no temporary
    file; a write that succeeds replaces it in one step."""
    path = tmp_path / "polar.csv"
    path.write_text("previous\n")

    def half_then_fail(out, columns, header):
        out.write("# kind: orientation\ntheta0,")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(sweeps.csvfile, "write", half_then_fail)
    code, _, err = run(capsys, "sweep", "orientation", "--regime", "stiff", "--n", "2",
                       "--out", str(path))
    assert code == 2 and "error: --out: cannot write" in err and "No space left" in err
    assert path.read_text() == "previous\n"
    assert [p.name for p in tmp_path.iterdir()] == ["polar.csv"]
    monkeypatch.undo()
    code, _, _ = run(capsys, "sweep", "orientation", "--regime", "stiff", "--n", "2",
                     "--out", str(path))
    assert code == 0 and sweeps.read_csv(path).kind == "orientation"
    assert [p.name for p in tmp_path.iterdir()] == ["polar.csv"]
    assert oct(path.stat().st_mode & 0o777) != oct(0o600)  # the mode of a file open() makes


def test_reproduce_out_is_checked_before_any_work(capsys, tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("x")
    code, _, err = run(capsys, "reproduce", "--out", str(afile))
    assert code == 2 and "error: --out: " in err and "not a folder" in err
    code, _, err = run(capsys, "reproduce", "--out", str(afile / "below"))
    assert code == 2 and "error: --out: cannot write into" in err


def test_output_closed_early_is_a_quiet_exit(tmp_path):
    """``... --json | head -c 10``: the reader leaves; exit 141 and no traceback."""
    proc = subprocess.Popen([sys.executable, "-m", "model", "support", "--regime", "soft",
                             "--samples", "2000", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.read(10)
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 141 and "Traceback" not in err, err
