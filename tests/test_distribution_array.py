"""model.designs.distribution_array's bookkeeping: members reused across the beta iterations, a
time budget honoured inside the contacts, and the named outcome of every result."""
import math

import numpy as np
import pytest

import model.designs.distribution_array as da
from model import Params
from model.designs.distribution_array import MIN_STEPS, distribution_array
from model.designs.distribution_result import OUTCOMES
from model.designs.distributions import Pair, Uniform, VonMises
from model.contact.params import REGIMES
from model.designs.design_point import evaluate
from model.designs.units import PillarDesign

#: The notes' LDPE pillars at V0 = 1 cm/s, beyond the model range: computed scaled to
#: k~_theta = 1e6, where the members near theta0 = 0 ring for a million steps each.
STIFF = PillarDesign.example()


def spy_on_contacts(monkeypatch):
    calls = []
    real = da.run_contacts

    def spy(params, theta, options, beta):
        out = real(params, theta, options, beta=beta)
        calls.append((np.asarray(theta).copy(), float(beta[0]), options.max_steps, out[0]))
        return out
    monkeypatch.setattr(da, "run_contacts", spy)
    return calls


@pytest.mark.parametrize("name", ["pendulum", "slider", "soft"])
def test_no_contact_is_integrated_twice(monkeypatch, name):
    calls = spy_on_contacts(monkeypatch)
    d = distribution_array(REGIMES[name], VonMises(1.0, 4.0), tol=1e-3)
    assert d.success and d.outcome == "ok", d.message
    keys = [(beta, t) for theta, beta, _, _ in calls for t in theta.tolist()]
    assert len(keys) == len(set(keys)) == d.stats["trajectories"]


def test_a_spent_budget_cuts_the_ringing_contacts_and_says_so(monkeypatch):
    calls = spy_on_contacts(monkeypatch)
    r = evaluate(STIFF, VonMises(0.0, 50.0), budget=1e-6)
    a = r.array
    assert r.status == "scaled" and not r.success
    assert a.outcome == "contacts_cut"
    assert "time budget of 1e-06 s ran out inside the contacts" in a.message
    assert OUTCOMES["contacts_cut"][1] in a.message  # the remedy
    # With no time left every batch got the floor of steps, and those that needed more
    # were cut (before, one contact here ran a million steps, minutes for the array).
    assert all(steps == MIN_STEPS for _, _, steps, _ in calls)
    assert 0 < a.n_failed < a.n_members
    values = [a.FTx_over_mu0FN, a.Nc_over_Nc0, a.beta, r.FTx_N, r.power_W,
              r.dissipated_power_W, r.contact_time_s]
    assert all(math.isfinite(v) for v in values)


def test_a_budget_large_enough_changes_nothing():
    p = REGIMES["pendulum"]
    free = distribution_array(p, VonMises(1.0, 4.0), tol=1e-3)
    budgeted = distribution_array(p, VonMises(1.0, 4.0), tol=1e-3, budget=600.0)
    assert budgeted.outcome == "ok"
    assert budgeted.FTx_over_mu0FN == free.FTx_over_mu0FN
    assert budgeted.beta == free.beta


def test_when_every_member_is_cut_the_result_says_so_without_warnings():
    # One orientation (a pair folds onto one member) that rings far beyond MIN_STEPS.
    p = Params(k_r=1e6, k_theta=1e6, F_N=1e3, L0=100.0)
    with np.errstate(all="raise"):
        a = distribution_array(p, Pair(0.02), budget=1e-6)
    assert not a.success and a.outcome == "contacts_cut"
    assert a.n_failed == a.n_members == 1
    assert "none of the 1 members finished its contact" in a.message
    # No member, no value: NaN with the reason, never a made-up number such as 0 -- nor
    # the self-consistent beta's starting guess (1), which nothing was solved on.
    assert math.isnan(a.FTx_over_mu0FN) and math.isnan(a.Nc_over_Nc0)
    assert math.isnan(a.beta) and math.isnan(a.to_dict()["beta"])
    # A fixed beta is the caller's input: reported as given.
    with np.errstate(all="raise"):
        fixed = distribution_array(p, Pair(0.02), budget=1e-6, beta=0.5)
    assert fixed.n_failed == fixed.n_members and fixed.beta == 0.5


@pytest.mark.parametrize("kwargs, outcome", [
    (dict(max_intervals=1, tol=1e-7), "tolerance_not_met"),
    (dict(max_steps=100, beta=1.0), "members_failed")])
def test_each_outcome_is_named_with_its_remedy(kwargs, outcome):
    p = Params(k_r=1e6, k_theta=1e-3) if outcome == "members_failed" else REGIMES["slider"]
    a = distribution_array(p, Uniform(), **kwargs)
    assert not a.success and a.outcome == outcome
    assert a.message.startswith(OUTCOMES[outcome][0])
    assert OUTCOMES[outcome][1] in a.message
    assert a.to_dict()["outcome"] == outcome
