"""Fuzzed command lines (hypothesis) for ``python -m model``, run in-process via ``main``.

Garbage flags and values end in exit code 2 with one line on stderr that names the flag,
never a traceback; a command line that parses runs (exit 0 or 1) and prints its result.
Every fuzzed run is bounded: ``support`` gets a step and time budget as its last flags,
``array`` is a fixed array, ``sweep`` writes into a missing folder (so it stops at the
usage check before computing anything); ``reproduce`` and real sweeps are never started.
"""
import json
import math

import pytest
from hypothesis import HealthCheck, Phase, event, given, settings
from hypothesis import strategies as st

from model.cli import build_parser, main

PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink)
FUZZ = settings(max_examples=300, deadline=30_000, database=None, phases=PHASES,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
# design and pillar are fuzzed, with budgets, in test_cli_design.py; pack (the app's
# offline explorer, a 2 MB file per run) has its usage errors tested in test_offline_pack.py;
# friction (reads a file) has its bad files tested in test_friction_fit.py.
COMMANDS = {"support", "array", "sweep", "reproduce", "warmup", "design", "pillar", "pack",
            "friction"}
MISSING_DIR = "/nonexistent-micropillar-dir/out.csv"

SUPPORT_FLAGS = ["--k-r", "--k-theta", "--F-N", "--theta0", "--beta", "--rtol", "--atol",
                 "--method", "--max-steps", "--tau-max", "--samples", "--regime", "--json"]
ARRAY_FLAGS = ["--k-r", "--k-theta", "--F-N", "--theta0", "--beta", "--rtol", "--atol",
               "--method", "--regime", "--orientation", "--tol", "--json"]
SWEEP_FLAGS = ["--n", "--F-N", "--regime", "--beta", "--tol", "--rtol", "--atol", "--method",
               "--workers", "--json", "--k-r"]
JUNK_FLAGS = ["--kr", "--k_r", "-k", "--", "--json=1", "--k-r=", "--F-N=abc", "-x", "---"]
# Values chosen to hit every kind of failure; all numbers here keep a run cheap.
VALUES = ["-1", "0", "1", "3", "0.5", "0.03", "2.0", "1e400", "-1e400", "nan", "inf",
          "-inf", "NaN", "abc", "", " ", "1,5", "0x10", "1_0", "\u0661", "1e-3", "pendulum",
          "slider", "soft", "stiff", "rigid", "self", "auto", "explicit", "implicit", "rk4",
          "fixed", "uniform", "10", "1.5", "1e9", "-0", "\x00", "\u00e9\u00e8", "1 2"]


def _cheap_text(text: str) -> bool:
    """Random text that is not a flag and not a big number (which could start a long run)."""
    if text.startswith("-"):
        return False
    try:
        return not abs(float(text)) > 1e3
    except ValueError:
        return True


RANDOM_TEXT = st.text(max_size=8).filter(_cheap_text)
VALUE = st.one_of(st.sampled_from(VALUES), RANDOM_TEXT)


def _tokens(flags):
    flag = st.sampled_from(flags + JUNK_FLAGS)
    pair = st.tuples(flag, VALUE).map(list)
    joined = st.tuples(flag, VALUE).map(lambda fv: [f"{fv[0]}={fv[1]}"])
    return st.lists(st.one_of(pair, joined, flag.map(lambda f: [f]), VALUE.map(lambda v: [v])),
                    max_size=6).map(lambda parts: [t for part in parts for t in part])


# Mostly good values, so that fuzzed command lines also run (exit 0 or 1).
GOOD = {"--k-r": ["0.01", "0.3", "3"], "--k-theta": ["0.01", "0.3", "3"],
        "--F-N": ["0.1", "1", "10"], "--theta0": ["0", "3.141592653589793", "-1", "1.5"],
        "--beta": ["0.5", "1"], "--rtol": ["1e-4", "1e-6"], "--atol": ["1e-8"],
        "--method": ["auto", "explicit", "implicit"], "--samples": ["0", "5"],
        "--regime": ["pendulum", "slider", "stiff", "soft"], "--json": []}


def _near_valid(command, flags, extra_good):
    good = {**GOOD, **extra_good}

    def pair(flag):
        values = good.get(flag, [])
        if not values:
            return st.just([flag])
        good_value = st.sampled_from(values)
        return st.tuples(st.just(flag), st.one_of(good_value, good_value, good_value,
                                                  good_value, VALUE)).map(list)

    tokens = st.lists(st.sampled_from([f for f in flags if f in good]).flatmap(pair),
                      max_size=5).map(lambda parts: [t for part in parts for t in part])
    return st.tuples(st.sampled_from(GOOD["--regime"]), tokens).map(
        lambda rt: [command, "--regime", rt[0], *rt[1]])


ARGV = st.one_of(
    # budgets first: a fuzzed budget can only be smaller (VALUE holds no big numbers)
    _near_valid("support", SUPPORT_FLAGS, {"--max-steps": ["10", "5000"],
                                          "--tau-max": ["3", "1000"]}).map(
        lambda a: [a[0], "--max-steps", "20000", "--tau-max", "2000", *a[1:]]),
    _near_valid("array", ARRAY_FLAGS, {"--beta": ["self", "0.5"], "--rtol": ["1e-5"],
                                       "--method": ["auto", "explicit"]}).map(
        lambda a: [*a, "--orientation", "fixed"]),
    _tokens(SUPPORT_FLAGS).map(lambda t: ["support", *t, "--max-steps", "20000",
                                          "--tau-max", "2000"]),
    _tokens(ARRAY_FLAGS).map(lambda t: ["array", *t, "--orientation", "fixed"]),
    st.tuples(st.sampled_from(["regime-map", "load", "stiffness", "orientation", "fig5", ""]),
              _tokens(SWEEP_FLAGS)).map(lambda kt: ["sweep", kt[0], *kt[1], "--out",
                                                    MISSING_DIR]),
    st.lists(VALUE, max_size=4).filter(lambda t: not t or t[0] not in COMMANDS),
)


def run(capsys, argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@FUZZ
@given(argv=ARGV)
def test_fuzzed_command_lines_fail_cleanly_or_run(capsys, argv):
    code, out, err = run(capsys, argv)
    event(f"{argv[0] if argv else 'no command'}: exit {code}")
    assert "Traceback" not in out + err
    assert code in (0, 1, 2), (code, err)
    if code == 2:
        assert out == "" and err.endswith("\n")
        if not argv:  # no command: the usage
            assert err.startswith("usage: python -m model")
        else:  # one line naming the problem
            assert err.count("\n") == 1 and err.startswith("python -m model")
            assert ": error: " in err
        return
    if "-h" in argv or "--help" in argv:
        assert code == 0 and "usage:" in out
        return
    assert argv[0] in ("support", "array"), argv  # sweeps into a missing folder never run
    assert out.strip()
    if "--json" in argv:
        record = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
        assert record["success"] is (code == 0)
    else:
        assert "success" in out


# (flag, value) pairs the documentation calls bad, for the support command.
BAD_SUPPORT = {
    "--k-r": ["0", "-1", "nan", "inf", "abc", "", "1e400", "2e6"],
    "--k-theta": ["0", "-0.5", "NaN", "-inf", "x", "1e7"],
    "--F-N": ["0", "-1", "nan", "inf", "1e4", "one"],
    "--theta0": ["7", "-7", "nan", "inf", "pi", "6.3"],
    "--beta": ["0", "1.5", "-1", "nan", "self", "abc"],
    "--rtol": ["0", "1", "1e-15", "nan", "-1e-6", "tight"],
    "--atol": ["0", "1", "1e-17", "nan", "inf"],
    "--method": ["rk4", "AUTO", "", "dop853"],
    "--max-steps": ["5", "1.5", "inf", "nan", "abc", "1e9", "-10"],
    "--samples": ["-1", "1e7", "1.5", "nan", "many"],
    "--tau-max": ["0.5", "1e9", "nan", "inf", "-1"],
    "--regime": ["rigid", "", "Soft", "pendulum "],
}
BAD_PAIRS = [(flag, value) for flag, values in BAD_SUPPORT.items() for value in values]
GOOD_BASE = st.lists(st.sampled_from([["--regime", "stiff"], ["--k-r", "3", "--k-theta", "3"],
                                      ["--F-N", "2"], ["--theta0", "1"], ["--json"],
                                      ["--rtol", "1e-5"], ["--beta", "0.5"]]),
                     max_size=3).map(lambda parts: [t for part in parts for t in part])


@FUZZ
@given(bad=st.sampled_from(BAD_PAIRS), base=GOOD_BASE, joined=st.booleans())
def test_a_bad_value_is_named_on_one_line(capsys, bad, base, joined):
    flag, value = bad
    pair = [f"{flag}={value}"] if joined else [flag, value]
    # last, so that no good value of the same flag overrides it
    code, out, err = run(capsys, ["support", "--regime", "stiff", *base, *pair])
    assert (code, out) == (2, ""), err
    assert err.count("\n") == 1 and err.startswith("python -m model")
    assert flag in err, err


@settings(max_examples=40, deadline=30_000, database=None, phases=PHASES,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(k_r=st.floats(0.01, 3.0), k_theta=st.floats(0.01, 3.0), F_N=st.floats(0.1, 10.0),
       theta0=st.floats(-math.pi, math.pi), rtol=st.sampled_from(["1e-4", "1e-5", "1e-6"]))
def test_valid_command_lines_print_strict_json(capsys, k_r, k_theta, F_N, theta0, rtol):
    argv = ["support", "--k-r", repr(k_r), "--k-theta", repr(k_theta), "--F-N", repr(F_N),
            f"--theta0={theta0!r}", "--rtol", rtol, "--json"]
    code, out, err = run(capsys, argv)
    assert code == 0 and err == "", err
    record = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
    assert record["success"] is True and record["t_out"] > 0
    assert record["params"]["k_r"] == k_r and record["params"]["theta0"] == theta0


def test_fuzz_never_starts_expensive_commands():
    """The guard of the fuzzers above: every command the parser knows is accounted for."""
    import argparse

    subparsers = next(a for a in build_parser()._actions
                      if isinstance(a, argparse._SubParsersAction))
    assert set(subparsers.choices) == COMMANDS
