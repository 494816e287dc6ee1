"""model.validation: one check per kind of input; every message names the argument, the
value and what it must be (the fix)."""
import math
import re

import numpy as np
import pytest

from model.validation import (BETA, Interval, angles, choice, grid, instance, load_factor, number,
                              whole)

UNIT = Interval(0.0, 1.0, lo_open=True)


def test_interval_membership_and_text():
    assert 1.0 in UNIT and 0.0 not in UNIT and 1.0 + 1e-12 not in UNIT
    assert str(UNIT) == "(0, 1]" and str(Interval(0, 360, hi_open=True)) == "[0, 360)"
    assert Interval(0.01, 3.0).bounds == (0.01, 3.0)


@pytest.mark.parametrize("value", [0.5, 1, np.float32(0.25), 10**0])
def test_number_accepts(value):
    x = number("beta", value, UNIT)
    assert type(x) is float and x == float(value)


@pytest.mark.parametrize("value", [0.0, -1.0, 1.5, math.nan, math.inf, 10**400])
def test_number_rejects_out_of_range_naming_value_and_fix(value):
    with pytest.raises(ValueError) as info:
        number("beta", value, UNIT, "load factor beta")
    text = str(info.value)
    assert text.startswith(f"beta={value!r} is invalid: ")
    assert "load factor beta must be finite and in (0, 1]" in text


@pytest.mark.parametrize("value", ["0.5", b"1", None, [0.5], True, np.bool_(False), object()])
def test_number_rejects_non_numbers(value):
    with pytest.raises(ValueError, match=r"^k_r=.* is not a number; k_r must be a real number "
                                         r"in \(0, 1\]"):
        number("k_r", value, UNIT)


@pytest.mark.parametrize("value, expected", [(10, 10), (1e6, 1_000_000), (np.int64(7), 7)])
def test_whole_accepts(value, expected):
    n = whole("n", value, 1)
    assert n == expected and type(n) is int


@pytest.mark.parametrize("value", [0, 2.5, True, "3", math.inf, math.nan, None])
def test_whole_rejects_with_the_range(value):
    with pytest.raises(ValueError, match=r"^n=.* must be a whole number >= 1$"):
        whole("n", value, 1)
    with pytest.raises(ValueError, match=r"^samples=.* must be a whole number in \[1, 10\]$"):
        whole("samples", value if value != 0 else 11, 1, 10)


def test_choice():
    assert choice("method", "auto", ("auto", "implicit")) == "auto"
    for bad in ("AUTO", "", None, 3):
        with pytest.raises(ValueError, match=r"^method=.* is unknown; choose one of auto, implicit$"):
            choice("method", bad, ("auto", "implicit"))


def test_load_factor():
    assert load_factor("beta", "self") == "self" and load_factor("beta", 0.5) == 0.5
    # The interval is the model's (``BETA``), stated in the message.
    with pytest.raises(ValueError, match=r"^beta='auto' must be 'self' or a number in "
                                         + re.escape(str(BETA))):
        load_factor("beta", "auto")
    for bad in (0.0, 1.5, math.nan, "half"):
        with pytest.raises(ValueError, match=r"^beta=.* (is invalid|must be)"):
            load_factor("beta", bad, allow_self=bad != "half")
    with pytest.raises(ValueError, match=r"must be a number in " + re.escape(str(BETA)) + "$"):
        load_factor("beta", "self", allow_self=False)


def test_angles():
    a = angles("theta0", [0.0, 1.0], Interval(-2 * math.pi, 2 * math.pi))
    assert a.dtype == float and a.tolist() == [0.0, 1.0]
    assert angles("theta0", 0.5, Interval(0, 1)).shape == (1,)
    for bad in ([], [math.nan], [[1.0, 2.0]], "abc", None):
        with pytest.raises(ValueError, match=r"^theta0=.* must be a non-empty 1-D array of "
                                             r"finite angles"):
            angles("theta0", bad, Interval(0, 1))
    with pytest.raises(ValueError, match=r"^theta0=7.0 is invalid: every angle must be in "
                                         r"\[-6.28319, 6.28319\] rad"):
        angles("theta0", [1.0, 7.0], Interval(-2 * math.pi, 2 * math.pi))


def test_grid():
    assert grid("k_r", [0.1, 1]).tolist() == [0.1, 1.0]
    assert grid("theta0", [-1.0, 0.0], positive=False).tolist() == [-1.0, 0.0]
    with pytest.raises(ValueError, match=r"^k_r=\[0.0\] must be a non-empty 1-D sequence of "
                                         r"positive finite numbers"):
        grid("k_r", [0.0])
    with pytest.raises(ValueError, match="finite numbers"):
        grid("theta0", [math.inf], positive=False)


def test_instance():
    from model import Params

    p = Params(1.0, 1.0)
    assert instance("params", p, Params) is p
    with pytest.raises(TypeError, match="^params must be a model.Params, not dict$"):
        instance("params", {}, Params)


def _public_calls():
    from model import (Params, SolverOptions, fixed_orientation, orientation_sweep,
                       regime_map, simulate_support, uniform_array)

    p = Params(3.0, 3.0)
    return [
        ("k_r=-1.0", lambda: Params(-1.0, 1.0)),
        ("theta0=9.0", lambda: Params(1.0, 1.0, theta0=9.0)),
        ("rtol=1.0", lambda: SolverOptions(rtol=1.0)),
        ("method='rk4'", lambda: SolverOptions(method="rk4")),
        ("max_steps=5", lambda: SolverOptions(max_steps=5)),
        ("samples=-1", lambda: simulate_support(p, samples=-1)),
        ("beta=1.5", lambda: fixed_orientation(p, beta=1.5)),
        ("theta0=7.0", lambda: orientation_sweep(p, [1.0, 7.0])),
        ("beta_xtol=1.0", lambda: orientation_sweep(p, [1.0], beta_xtol=1.0)),
        ("tol=0.0", lambda: uniform_array(p, tol=0.0)),
        ("max_intervals=0", lambda: uniform_array(p, max_intervals=0)),
        ("n=0", lambda: regime_map(n=0)),
        ("workers=0", lambda: regime_map(n=1, workers=0)),
        ("k_r=[-1.0]", lambda: regime_map(k_r=[-1.0])),
        ("theta0=2.0", lambda: uniform_array(p.replace(theta0=2.0))),
        ("beta=0.5", lambda: uniform_array(p.replace(beta=0.5))),
    ]


@pytest.mark.parametrize("case", range(16))
def test_public_api_messages_name_value_and_fix(case):
    """Every public entry point reports a bad value as ``name=value`` followed by what the
    value must be (an interval, a kind of number, the choices, or what to pass instead)."""
    shown, call = _public_calls()[case]
    with pytest.raises(ValueError) as info:
        call()
    text = str(info.value)
    assert text.startswith(shown), text
    assert any(fix in text for fix in ("must be", "choose one of", "leave params", "pass beta")), \
        text
