"""``python -m model``: JSON and readable output, exit codes, one-line usage errors."""
import json
import math
import re
import subprocess
import sys

import numpy as np
import pytest

from model import cli
from model.cli import main
from model.contact.params import REGIMES, Params
from model.contact.support import simulate_support

ROW = re.compile(r"^  (?P<name>\S+)\s{2,}(?P<value>\S+(?: \S+)*)(?:  .*)?$")
REQUIRED_KEYS = {"t_out", "state_out", "F_mean_x", "F_mean_y", "W", "D_x", "D_y", "U_el", "K",
                 "energy_residual", "dtheta_rms", "dr_rms", "r_min", "success", "message", "stats"}


def _strict_json(text: str) -> dict:
    def reject(constant):
        raise AssertionError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=reject)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_json_keys_and_values(capsys):
    code, out, err = run(capsys, "support", "--k-r", "3", "--k-theta", "0.01", "--theta0", "1.2",
                         "--json")
    assert (code, err) == (0, "")
    record = _strict_json(out)
    assert REQUIRED_KEYS <= record.keys()
    assert record["success"] is True and record["status"] == 0
    assert record["params"]["k_r"] == 3.0 and record["params"]["theta0"] == 1.2
    assert len(record["state_out"]) == 5
    expected = simulate_support(Params(3.0, 0.01, theta0=1.2)).to_dict()
    for key in REQUIRED_KEYS - {"stats", "state_out"}:
        assert record[key] == expected[key], key
    assert record["state_out"] == expected["state_out"]
    balance = record["D_x"] + record["D_y"] + record["U_el"] + record["K"] + record["energy_residual"]
    assert balance == pytest.approx(record["W"], rel=1e-12)


def test_regime_sets_stiffness_and_flags_override(capsys):
    code, out, _ = run(capsys, "support", "--regime", "slider", "--k-theta", "2", "--F-N", "0.5",
                       "--json")
    params = _strict_json(out)["params"]
    assert code == 0
    assert (params["k_r"], params["k_theta"], params["F_N"]) == (REGIMES["slider"].k_r, 2.0, 0.5)


def test_solver_flags_reach_the_solver(capsys, monkeypatch):
    calls = []

    def recording(params, **options):
        calls.append((params, options))
        return simulate_support(params, **options)

    monkeypatch.setattr(cli, "simulate_support", recording)
    run(capsys, "support", "--regime", "stiff", "--rtol", "1e-9", "--atol", "1e-12",
        "--method", "explicit", "--max-steps", "5e4", "--tau-max", "500")
    run(capsys, "support", "--regime", "stiff", "--beta", "0.5", "--rtol", "1e-4", "--samples", "3")
    assert calls == [
        (REGIMES["stiff"], dict(rtol=1e-9, atol=1e-12, method="explicit", samples=0, max_steps=50_000,
                                   tau_max=500.0)),
        (REGIMES["stiff"].replace(beta=0.5),
         dict(rtol=1e-4, atol=1e-6, method="auto", samples=3, max_steps=1_000_000,
              tau_max=1e5)),
    ]


def test_samples_add_a_series(capsys):
    code, out, _ = run(capsys, "support", "--regime", "pendulum", "--samples", "50", "--json")
    record = _strict_json(out)
    assert code == 0
    lengths = {key: len(values) for key, values in record["series"].items()}
    assert set(lengths.values()) == {50}
    assert record["series"]["tau"][-1] == pytest.approx(record["t_out"], rel=1e-12)


def test_unsuccessful_run_prints_and_exits_1(capsys):
    code, out, err = run(capsys, "support", "--regime", "soft", "--F-N", "10", "--max-steps", "10",
                         "--json")
    record = _strict_json(out)
    assert code == 1 and err == ""
    assert record["success"] is False and record["status"] != 0 and record["message"]


def test_readable_summary(capsys):
    code, out, err = run(capsys, "support", "--regime", "pendulum", "--theta0", "1")
    assert (code, err) == (0, "")
    lines = out.splitlines()
    for title in ("Parameters (dimensionless)", "Results", "Solver"):
        assert title in lines
    # "  name  value  meaning": names left-aligned, values right-aligned, each in one column
    table = [ROW.match(line) for line in lines if line.startswith("  ")]
    assert all(table) and len(table) > 25
    assert len({m.end("value") for m in table}) == 1
    rows = {m["name"]: m["value"] for m in table}
    assert float(rows["k_r"]) == 3.0 and float(rows["theta0"]) == 1.0
    result = simulate_support(REGIMES["pendulum"].replace(theta0=1.0))
    for name in ("t_out", "W", "energy_residual", "r_min"):
        assert float(rows[name]) == pytest.approx(getattr(result, name), rel=1e-7), name
    assert float(rows["F_mean_x"]) == pytest.approx(result.F_mean[0], rel=1e-7)
    assert rows["success"] == "yes"


def test_subprocess_json():
    proc = subprocess.run(
        [sys.executable, "-m", "model", "support", "--k-r", "3", "--k-theta", "0.01", "--F-N", "1",
         "--theta0", "1.5708", "--json"],
        capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    record = _strict_json(proc.stdout)
    assert REQUIRED_KEYS <= record.keys() and record["success"] is True
    assert math.isfinite(record["t_out"]) and record["t_out"] > 0


BAD = [
    (["--k-r", "-1", "--k-theta", "1"], "--k-r", "k_r=-1.0 is invalid"),
    (["--k-r", "1", "--k-theta", "0"], "--k-theta", "k_theta=0.0 is invalid"),
    (["--k-r", "abc", "--k-theta", "1"], "--k-r", "'abc' is not a number"),
    (["--k-r", "nan", "--k-theta", "1"], "--k-r", "k_r=nan is invalid"),
    (["--regime", "soft", "--F-N", "inf"], "--F-N", "F_N=inf is invalid"),
    (["--regime", "soft", "--F-N", "0"], "--F-N", "F_N=0.0 is invalid"),
    (["--regime", "soft", "--theta0", "7"], "--theta0", "theta0=7.0 is invalid"),
    (["--regime", "soft", "--theta0=-inf"], "--theta0", "theta0=-inf is invalid"),
    (["--regime", "soft", "--beta", "1.5"], "--beta", "beta=1.5 is invalid"),
    (["--regime", "soft", "--beta", "0"], "--beta", "beta=0.0 is invalid"),
    (["--regime", "soft", "--rtol", "1"], "--rtol", "rtol=1.0 is invalid"),
    (["--regime", "soft", "--rtol", "nan"], "--rtol", "rtol=nan is invalid"),
    (["--regime", "soft", "--atol", "0"], "--atol", "atol=0.0 is invalid"),
    (["--regime", "soft", "--method", "rk4"], "--method", "invalid choice: 'rk4'"),
    (["--regime", "soft", "--max-steps", "5"], "--max-steps", "max_steps=5 must be a whole number"),
    (["--regime", "soft", "--max-steps", "1.5"], "--max-steps", "'1.5' is not a whole number"),
    (["--regime", "soft", "--max-steps", "inf"], "--max-steps", "'inf' is not a whole number"),
    (["--regime", "soft", "--samples", "-1"], "--samples", "samples=-1 must be a whole number"),
    (["--regime", "soft", "--samples", "1e7"], "--samples", "samples=10000000 must be"),
    (["--regime", "soft", "--samples", "nan"], "--samples", "'nan' is not a whole number"),
    (["--regime", "rigid"], "--regime", "invalid choice: 'rigid'"),
    (["--k-theta", "1"], "--k-r", "required unless --regime is given"),
    (["--k-r", "1"], "--k-theta", "required unless --regime is given"),
    (["--regime", "soft", "--k-r"], "--k-r", "expected one argument"),
    (["--regime", "soft", "--tau-max", "0.5"], "--tau-max", "tau_max=0.5 is invalid"),
]


@pytest.mark.parametrize("argv, flag, detail", BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_values_exit_2_with_one_line(capsys, argv, flag, detail):
    code, out, err = run(capsys, "support", *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.endswith("\n")
    assert err.startswith(f"python -m model support: error: {flag}: ")
    assert detail in err


def test_unknown_flag_is_named(capsys):
    code, out, err = run(capsys, "support", "--regime", "soft", "--kr", "3")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("python -m model: error: unrecognized arguments: --kr 3")


def test_unknown_command(capsys):
    code, _, err = run(capsys, "simulate")
    assert code == 2 and err.count("\n") == 1 and "invalid choice: 'simulate'" in err


def test_no_command_prints_help_and_exits_2(capsys):
    code, out, err = run(capsys)
    assert code == 2 and out == ""
    assert err.startswith("usage: python -m model") and "support" in err


def test_help_exits_0(capsys):
    code, out, _ = run(capsys, "support", "--help")
    assert code == 0
    for flag in ("--k-r", "--k-theta", "--F-N", "--theta0", "--beta", "--rtol", "--atol",
                 "--method", "--samples", "--max-steps", "--regime", "--json"):
        assert flag in out


def test_warmup_reports_time(capsys):
    code, out, _ = run(capsys, "warmup")
    assert code == 0 and re.match(r"kernel ready in \d+\.\d\d s", out)


def test_time_budget_flag(capsys):
    code, out, _ = run(capsys, "support", "--regime", "soft", "--tau-max", "3", "--json")
    assert code == 1 and json.loads(out)["status"] == 2


def test_long_contact_with_samples_keeps_a_bounded_record(capsys):
    """``support --max-steps 1e7 --samples 10`` kept every accepted step (2.8 GB before a
    MemoryError at 1e7 steps) to return 10 samples. The kernel now keeps at most
    MAX_NODES nodes, evenly thinned over the contact: this contact of over 100 000 nodes
    (N_SUB per explicit step; at least two thinnings) returns samples that end at its exit
    state and agree with an unthinned run at a looser tolerance."""
    from model import _kernel
    from model._kernel.record import N_SUB
    from model.arrays.contacts import run_contacts
    from model.contact.options import SolverOptions

    argv = ["--k-r", "0.01", "--k-theta", "0.01", "--F-N", "10"]
    code, out, err = run(capsys, "support", *argv, "--rtol", "1e-14", "--max-steps", "1e7",
                         "--samples", "10", "--json")
    record = _strict_json(out)
    st = record["stats"]
    candidates = N_SUB * st["n_steps_explicit"] + st["n_steps_implicit"] + 1
    assert code == 0 and err == "" and candidates > 2 * _kernel.MAX_NODES
    params = Params(k_r=0.01, k_theta=0.01, F_N=10.0)
    _, nodes = run_contacts(params, params.theta0, SolverOptions(rtol=1e-14, max_steps=10**7),
                            record=True)
    assert len(nodes) <= _kernel.MAX_NODES
    assert nodes[-1, 0] == record["t_out"]  # the exit is always a node
    series = record["series"]
    assert series["tau"][-1] == record["t_out"]
    assert series["x"][-1] == pytest.approx(record["state_out"][0], abs=1e-9)
    loose = simulate_support(params, rtol=1e-10, samples=10)
    st = loose.stats
    assert N_SUB * st["n_steps_explicit"] + st["n_steps_implicit"] < _kernel.MAX_NODES  # all kept
    for name in ("x", "y", "v_x", "v_y", "theta"):
        np.testing.assert_allclose(series[name], getattr(loose.series, name), rtol=1e-5,
                                   atol=1e-5, err_msg=name)
