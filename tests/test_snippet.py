"""This view as code: ``--print-python`` on the CLI commands and ``app.snippet``.

Each printed snippet is run (in a fresh namespace, or a fresh interpreter) and must give
the numbers the command prints with ``--json`` (or writes to its CSV), and those the
dashboard computes for its state.
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import model.cli as cli
from model.cli import main
from model.cli import snippet as cli_snippet
from model.runs.sweeps import read_csv
from model.contact.support import simulate_support

ROOT = Path(__file__).resolve().parents[1]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


#: Appended to a snippet under test: its results' records, as one JSON line.
FOOTER = """
import json as _json
from model.cli._common import jsonable as _jsonable
_records = {}
for _name in %r:
    _value = globals()[_name]
    _records[_name] = _value.to_dict() if hasattr(_value, "to_dict") else {}
    if getattr(_value, "series", None) is not None:
        _records[_name]["series_x"] = list(_value.series.x)
print("RECORDS " + _json.dumps(_jsonable(_records)))
"""


def execute(code: str, names=("result",), cwd=None) -> tuple[dict, str]:
    """Run a snippet in a fresh interpreter: the records of its variables ``names`` (as
    JSON gives them) and what the snippet itself printed."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", code + FOOTER % (tuple(names),)],
                          capture_output=True, text=True, cwd=cwd or ROOT, env=env,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    printed, _, records = done.stdout.rpartition("RECORDS ")
    return json.loads(records), printed


def as_json(value):
    return json.loads(json.dumps(cli._common.jsonable(value)))


def printed_json(capsys, *argv) -> dict:
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def snippet(capsys, *argv) -> str:
    code, out, err = run(capsys, *argv, "--print-python")
    assert code == 0 and "error" not in err, err
    compile(out, "<snippet>", "exec")  # valid Python before anything else
    return out


def same(a, b) -> bool:
    """Equal, with NaN equal to NaN and None (JSON's NaN) equal to NaN."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple, np.ndarray)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if a is None or b is None:
        return (a is None or (isinstance(a, float) and math.isnan(a))) and \
               (b is None or (isinstance(b, float) and math.isnan(b)))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


SUPPORT_KEYS = ("t_out", "state_out", "F_mean_x", "F_mean_y", "W", "D_x", "D_y", "U_el", "K",
                "energy_residual", "dtheta_rms", "dr_rms", "r_min", "success", "status",
                "message", "params")


@pytest.mark.parametrize("argv", [
    ("support", "--regime", "pendulum", "--theta0", "1.2"),
    ("support", "--k-r", "0.7", "--k-theta", "0.05", "--F-N", "2.5", "--beta", "0.6",
     "--rtol", "1e-8", "--method", "explicit", "--samples", "50"),
])
def test_support_snippet_reproduces_the_json(capsys, argv):
    expected = printed_json(capsys, *argv)
    code = snippet(capsys, *argv)
    records, printed = execute(code)
    for key in SUPPORT_KEYS:
        assert same(records["result"][key], expected[key]), key
    assert "from model import" in code and "simulate_support(" in code
    # What the snippet prints are those numbers too.
    for key in ("t_out", "W", "D_y"):
        assert f"{key} = {expected[key]!r}" in printed, key


ARRAY_KEYS = ("FTx_over_mu0FN", "FTy_over_mu0FN", "Dy_over_Dx", "Nc_over_Nc0", "beta",
              "work_split", "dtheta_rms", "dr_rms", "success", "message", "params")


@pytest.mark.parametrize("argv", [
    ("array", "--regime", "soft", "--tol", "1e-2"),
    ("array", "--k-r", "0.5", "--k-theta", "0.2", "--F-N", "2", "--beta", "0.8", "--tol", "1e-2"),
    ("array", "--regime", "slider", "--theta0", "0.9"),
    ("array", "--regime", "pendulum", "--orientation", "fixed", "--beta", "0.7",
     "--rtol", "1e-7"),
])
def test_array_snippet_reproduces_the_json(capsys, argv):
    expected = printed_json(capsys, *argv)
    code = snippet(capsys, *argv)
    record = execute(code)[0]["result"]
    for key in ARRAY_KEYS:
        assert same(record[key], expected[key]), key
    wanted = "fixed_orientation(" if expected["orientation"] == "fixed" else "uniform_array("
    assert wanted in code


def test_sweep_snippet_writes_the_same_csv(capsys, tmp_path):
    argv = ("sweep", "orientation", "--regime", "slider", "--n", "5", "--F-N", "0.5")
    code, _, err = run(capsys, *argv, "--out", str(tmp_path / "cli.csv"))
    assert code == 0, err
    text = snippet(capsys, *argv, "--out", str(tmp_path / "snippet.csv"))
    assert not (tmp_path / "snippet.csv").exists()  # printing computes nothing
    execute(text, names=())
    by_cli, by_snippet = read_csv(tmp_path / "cli.csv"), read_csv(tmp_path / "snippet.csv")
    assert by_cli.columns.keys() == by_snippet.columns.keys()
    for name, column in by_cli.columns.items():
        assert same(list(column), list(by_snippet.columns[name])), name
    ignore = {"seconds"}
    assert {k: v for k, v in by_cli.settings.items() if k not in ignore} == \
           {k: v for k, v in by_snippet.settings.items() if k not in ignore}


def test_uniform_sweep_snippet_passes_every_setting(capsys, tmp_path):
    text = snippet(capsys, "sweep", "load", "--regime", "stiff", "--n", "2", "--tol", "0.02",
                   "--beta", "0.9", "--out", str(tmp_path / "x.csv"))
    for piece in ("from model import load_sweep", "regimes=('stiff',)", "n=2", "tol=0.02",
                  "beta=0.9", "workers=1"):
        assert piece in text, piece
    assert "progress" not in text


@pytest.mark.parametrize("argv, flag", [
    (("support", "--k-r", "-1", "--k-theta", "1"), "--k-r"),
    (("array", "--regime", "soft", "--theta0", "1", "--orientation", "uniform"), "--theta0"),
    (("sweep", "orientation", "--out", "x.csv"), "--regime"),
])
def test_bad_flags_are_usage_errors_and_print_no_snippet(capsys, argv, flag):
    code, out, err = run(capsys, *argv, "--print-python")
    assert code == 2 and out == "" and flag in err and "Traceback" not in err


def test_printing_leaves_the_model_functions_in_place(capsys):
    from model import fixed_orientation, uniform_array
    from model.cli import array, sweep
    from model.runs.sweeps import stiffness_sweep

    snippet(capsys, "support", "--regime", "stiff")
    snippet(capsys, "array", "--regime", "stiff", "--theta0", "1")
    assert cli.simulate_support is simulate_support
    assert array.fixed_orientation is fixed_orientation and array.uniform_array is uniform_array
    assert sweep.SWEEPS["stiffness"][0] is stiffness_sweep


def test_source_round_trips_values():
    from model import Params

    values = [0.1 + 0.2, 1e-300, 3, True, None, "self", (0.01, 3.0), ("stiff",), [1.5, 2.5],
              Params(0.3, 2.0, F_N=0.25, theta0=0.1, beta=0.5, lam=0.07)]
    namespace = {"Params": Params}
    for value in values:
        assert eval(cli_snippet.source(value), namespace) == value
    assert cli_snippet.params_source(Params(3.0, 0.01)) == "Params(k_r=3.0, k_theta=0.01, F_N=1.0)"
    with pytest.raises(TypeError):
        cli_snippet.source(object())


# --------------------------------------------------------------------------- the dashboard

@pytest.mark.parametrize("values", [
    dict(k_r=0.5, k_theta=0.2, F_N=2.0, theta0=30.0, beta_mode="fixed", beta=0.8,
         average="duration"),
    dict(k_r=3.0, k_theta=0.01, F_N=1.0, theta0=135.0, rtol=1e-8),
])
def test_view_as_python_reproduces_the_dashboard(values):
    from app import worker
    from app.snippet import view_as_python
    from app.state import ExplorerState

    state = ExplorerState(**values)
    code = view_as_python(state)
    records, printed = execute(code, names=("support", "fixed", "uniform"))
    shown = worker.compute_support(state.params, state.array_beta, state.rtol)
    expected = dict(shown.result.to_dict(), series_x=list(shown.series.x))
    assert same(records["support"], as_json(expected))
    assert same(records["fixed"], as_json(shown.fixed.to_dict()))
    row = worker.compute_uniform(state.k_r, state.k_theta, state.F_N, state.array_beta)
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Dy_over_Dx", "Nc_over_Nc0",
                "beta"):
        assert records["uniform"][key] == pytest.approx(row[key], rel=1e-12, abs=1e-15), key
    assert f"math.radians({float(values['theta0'])!r})" in code
    # Both averages the page shows, the headline's (the force the slab feels) first.
    assert (f"F_T,x/(mu0 F_N) = {row['FTx_over_mu0FN_duration']!r} (duration-weighted "
            f"average over supports: the headline's), {row['FTx_over_mu0FN']!r} (paper") \
        in printed
