"""Validation of ``SolverOptions``: tolerances, method names, budgets."""
import dataclasses
import math

import pytest

from model.contact.options import METHODS, SolverOptions


def test_defaults():
    o = SolverOptions()
    assert (o.rtol, o.atol, o.method, o.max_steps, o.tau_max) == (1e-6, 1e-8, "auto", 1_000_000, 1e5)


@pytest.mark.parametrize("rtol", [1e-14, 1e-10, 1e-6, 1e-2])
def test_rtol_range_is_closed(rtol):
    o = SolverOptions(rtol=rtol)
    assert o.rtol == rtol and o.atol == pytest.approx(rtol / 100, rel=1e-15)


@pytest.mark.parametrize("rtol", [0.0, -1e-6, 9.99e-15, 0.011, 1.0, math.nan, math.inf, -math.inf])
def test_rtol_out_of_range(rtol):
    with pytest.raises(ValueError, match=r"^rtol=.*\[1e-14, 0\.01\]"):
        SolverOptions(rtol=rtol)


@pytest.mark.parametrize("atol", [1e-16, 1e-9, 1e-2])
def test_atol_range_is_closed(atol):
    assert SolverOptions(atol=atol).atol == atol


@pytest.mark.parametrize("atol", [0.0, -1e-9, 9e-17, 0.02, math.nan, math.inf])
def test_atol_out_of_range(atol):
    with pytest.raises(ValueError, match=r"^atol=.*\[1e-16, 0\.01\]"):
        SolverOptions(atol=atol)


@pytest.mark.parametrize("name", ["rtol", "atol", "tau_max"])
@pytest.mark.parametrize("bad", ["abc", [1e-6]])
def test_non_numbers(name, bad):
    with pytest.raises(ValueError, match=rf"^{name}=.* is not a number"):
        SolverOptions(**{name: bad})


@pytest.mark.parametrize("method", METHODS)
def test_known_methods(method):
    assert SolverOptions(method=method).method == method


def test_method_names():
    assert METHODS == ("auto", "explicit", "implicit", "reference", "reference-radau")


@pytest.mark.parametrize("method", ["rk45", "AUTO", "", None, "dop853"])
def test_unknown_method(method):
    with pytest.raises(ValueError, match=r"^method=.* is unknown; choose one of auto, explicit"):
        SolverOptions(method=method)


@pytest.mark.parametrize("steps, expected", [(10, 10), (1e6, 1_000_000), (100_000_000, 100_000_000)])
def test_max_steps_whole_numbers(steps, expected):
    o = SolverOptions(max_steps=steps)
    assert o.max_steps == expected and type(o.max_steps) is int


@pytest.mark.parametrize("steps", [9, 0, -1, 1e8 + 1, 100.5, True, math.nan, math.inf])
def test_max_steps_rejected(steps):
    with pytest.raises(ValueError, match="^max_steps="):
        SolverOptions(max_steps=steps)


@pytest.mark.parametrize("tau_max", [0.5, 1e9, math.nan, -1.0])
def test_tau_max_rejected(tau_max):
    with pytest.raises(ValueError, match="^tau_max="):
        SolverOptions(tau_max=tau_max)


def test_frozen_and_hashable():
    o = SolverOptions(rtol=1e-8)
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.rtol = 1e-6
    assert o == SolverOptions(rtol=1e-8, atol=1e-10) and hash(o) == hash(SolverOptions(rtol=1e-8))


@pytest.mark.parametrize("call", ["uniform", "fixed"])
def test_arrays_refuse_the_single_contact_reference_method(call):
    from model import Params, fixed_orientation, uniform_array

    params = Params(k_r=3.0, k_theta=0.01, F_N=1.0)
    with pytest.raises(ValueError, match="method='reference' is for single contacts"):
        if call == "uniform":
            uniform_array(params, method="reference")
        else:
            fixed_orientation(params.replace(theta0=1.0), method="reference")
