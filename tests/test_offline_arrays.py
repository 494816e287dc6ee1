"""The offline explorer's arrays (app/offline/arrays.js, solvers.js) against the Python model.

One model, two implementations: Node runs the JavaScript uniform array (the quadrature
over theta0 of model/arrays/uniform.py, wrapped in the self-consistent beta of model/arrays/beta.py) and
the fixed arrays with their self-consistent beta (model/arrays/fixed.py), and the results are
compared with Python's on a grid covering the four regimes (model.contact.params.REGIMES) and
loads 0.1-10 (docs/offline.md, "Agreement").

* Uniform arrays at tol 1e-3: F_T,x/(mu0 F_N) (both averages) and N_c/N_c0 within tol of
  Python's, beta within tol beta, D_y/D_x within tol plus both error estimates.
* Fixed arrays at rtol 1e-8: beta and F_T,x/(mu0 F_N) within 1e-5 relative, and the same
  note where beta has no exact root (tau_out jumps across it).
* The budgets: a uniform array that runs out of contacts or intervals says so.
"""
from __future__ import annotations

import json
import math
import subprocess
from importlib import resources

import pytest

from model import REGIMES, orientation_sweep, uniform_array
from model.contact.friction import mu0

from test_offline_kernel import _node

RUNNER = resources.files("app.offline") / "node_arrays.js"
TOL = 1e-3
LOADS = (0.1, 1.0, 10.0)


def run_js(calls: list[dict]) -> list[dict]:
    """Results of app/offline/arrays.js for ``calls`` ({fn, args}), one Node process."""
    done = subprocess.run([_node(), str(RUNNER)], input=json.dumps(calls), text=True,
                          capture_output=True, timeout=900)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def _springs(name):
    return dict(k_r=REGIMES[name].k_r, k_theta=REGIMES[name].k_theta)


STATES = [(name, F) for name in REGIMES for F in LOADS]


@pytest.fixture(scope="module")
def uniform_js():
    calls = [dict(fn="uniformArray", args=[dict(_springs(n), F_N=F), dict(tol=TOL)])
             for n, F in STATES]
    return dict(zip(STATES, run_js(calls)))


@pytest.mark.parametrize("name,F_N", STATES)
def test_uniform_array_agrees_with_python(uniform_js, name, F_N):
    js = uniform_js[(name, F_N)]
    assert "error" not in js, js
    py = uniform_array(REGIMES[name].replace(F_N=F_N), tol=TOL)
    where = f"{name}, F_N = {F_N}"
    assert js["success"] and py.success, (where, js["message"], py.message)
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Nc_over_Nc0"):
        assert abs(js[key] - getattr(py, key)) <= TOL, (where, key, js[key], getattr(py, key))
    assert abs(js["beta"] - py.beta) <= TOL * py.beta, (where, js["beta"], py.beta)
    bound = TOL + js["quadrature_error"]["Dy_over_Dx"] + py.quadrature_error["Dy_over_Dx"]
    assert abs(js["Dy_over_Dx"] - py.Dy_over_Dx) <= bound, (where, js["Dy_over_Dx"], py.Dy_over_Dx)
    # The error estimates are the quadrature's own: met, as in Python.
    assert js["quadrature_error"]["FTx_over_mu0FN"] <= TOL
    assert js["quadrature_error"]["Nc_over_Nc0"] <= TOL


def test_fixed_beta_agrees_with_python():
    theta0 = [0.3, 1.5, 2.8]
    calls = [dict(fn="orientationSweep", args=[dict(_springs(n), F_N=F, rtol=1e-8), theta0, "self"])
             for n, F in STATES]
    for (name, F_N), js in zip(STATES, run_js(calls)):
        py = orientation_sweep(REGIMES[name].replace(F_N=F_N), theta0, beta="self", rtol=1e-8)
        for i, t in enumerate(theta0):
            where = f"{name}, F_N = {F_N}, theta0 = {t}"
            # Where tau_out jumps across the root (no exact root), both say so, at the same
            # beta; the contact there is on either side of the jump.
            assert js["beta_note"][i] == py.beta_note[i], where
            assert math.isclose(js["beta"][i], py.beta[i], rel_tol=1e-5), (where, js["beta"][i], py.beta[i])
            if py.beta_note[i]:
                assert not js["success"][i], where
                continue
            assert js["success"][i], where
            ftx = js["F_mean_x"][i] / mu0()
            assert math.isclose(ftx, py.FTx_over_mu0FN[i], rel_tol=1e-5), (where, ftx)



def test_a_key_press_contact_starts_from_the_last_one():
    """The page's support after a theta0 key press (arrays.js "contact" with ``previous``:
    the last contact's beta and slope start the secant): the same beta, notes and forces as
    Python's fixed arrays there, to the solver's tolerance, as when solved from scratch."""
    import numpy as np

    theta0 = np.radians(np.arange(85.0, 125.0, 5.0))
    for name in REGIMES:
        base = dict(_springs(name), F_N=1.0, rtol=1e-6, samples=400)
        calls = [dict(fn="job", args=["contact", dict(beta="self", input=dict(base, theta0=theta0[0]))])]
        first = run_js(calls)[0]
        got = [first]
        for t in theta0[1:]:  # each press warm-started from the one before, as in the page
            last = got[-1]
            previous = None if last["beta_note"] else dict(beta=last["params"]["beta"],
                                                            slope=last.get("beta_slope"))
            got.append(run_js([dict(fn="job", args=["contact", dict(
                beta="self", previous=previous, input=dict(base, theta0=float(t)))])])[0])
        py = orientation_sweep(REGIMES[name].replace(F_N=1.0), theta0, beta="self", rtol=1e-6)
        assert [g["beta_note"] for g in got] == list(py.beta_note), name
        np.testing.assert_allclose([g["params"]["beta"] for g in got], py.beta, rtol=1e-6,
                                   err_msg=name)
        ok = np.array([not note for note in py.beta_note])
        np.testing.assert_allclose(np.array([g["F_mean_x"] for g in got])[ok] / mu0(),
                                   py.FTx_over_mu0FN[ok], rtol=1e-5, err_msg=name)


def test_polar_sweep_solves_each_beta_from_its_neighbours():
    """The page's polar sweep (72 orientations, rtol 1e-6) starts each orientation's
    secant from its neighbours' beta: the same betas and notes as Python's bracket (to its
    tolerance 1e-8), at most 6 contacts per orientation (3.1-5.8 here; the bracket alone
    took 6.4-12: 459-870 contacts per sweep)."""
    import numpy as np

    theta0 = np.radians(np.arange(0.0, 360.0, 5.0))
    calls = [dict(fn="orientationSweep", args=[dict(_springs(n), F_N=1.0, rtol=1e-6),
                                               theta0.tolist(), "self"]) for n in REGIMES]
    for name, js in zip(REGIMES, run_js(calls)):
        py = orientation_sweep(REGIMES[name].replace(F_N=1.0), theta0, beta="self", rtol=1e-6)
        assert js["beta_note"] == list(py.beta_note), name
        np.testing.assert_allclose(js["beta"], py.beta, rtol=1e-6, err_msg=name)
        ok = np.array([not note for note in py.beta_note])
        np.testing.assert_allclose(np.array(js["F_mean_x"])[ok] / mu0(),
                                   py.FTx_over_mu0FN[ok], rtol=1e-5, err_msg=name)
        assert js["contacts"] <= 6 * theta0.size, (name, js["contacts"])

def test_fixed_beta_number_is_used_as_given():
    js = run_js([dict(fn="fixedArray", args=[dict(_springs("slider"), theta0=1.0), 0.5])])[0]
    assert js["beta"] == 0.5 and js["contact"]["params"]["beta"] == 0.5 and js["beta_note"] == ""


def test_budgets_say_when_they_ran_out():
    base = dict(_springs("slider"), F_N=1.0)
    contacts, intervals, bad = run_js([
        dict(fn="uniformArray", args=[base, dict(tol=TOL, max_contacts=40)]),
        dict(fn="uniformArray", args=[base, dict(tol=1e-6, beta=1.0, max_intervals=4)]),
        dict(fn="uniformArray", args=[base, dict(tol=0.9)])])
    assert not contacts["success"] and "budget of 40 contacts" in contacts["message"]
    assert contacts["stats"]["trajectories"] <= 40
    assert not intervals["success"]
    assert "quadrature tolerance not met within max_intervals" in intervals["message"]
    assert intervals["stats"]["intervals"] <= 4
    assert "tol=0.9" in bad["error"]
