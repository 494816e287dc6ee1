"""The 95 % band of a fitted friction law (``FrictionFit.band``): the delta method on the
fit's covariance, checked against a Monte-Carlo draw of the coefficients from that
covariance and against refits of fresh noisy data."""
import math
from pathlib import Path

import numpy as np
import pytest

from model.contact.friction import law
from model.lab.friction_curve import FrictionCurve, read_curve
from model.lab.friction_example import TRUE_LAW
from model.lab.friction_fit import fit_friction

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "flat_friction.csv"
#: 100 speeds from 0.01 to 100 V_s, as in test_friction_fit.
SPEEDS = np.geomspace(1e-2, 1e2, 100) * TRUE_LAW.V_s


def _draw(seed, noise=0.02, v=SPEEDS):
    return TRUE_LAW.mu(v) + np.random.default_rng(seed).normal(0.0, noise, v.size)

#: Where the band is checked: below, across and above the peak of the curve.
V = np.geomspace(3e-2, 30, 9) * TRUE_LAW.V_s


def _monte_carlo(fit, v, n=20_000, seed=0):
    """mu(v) for ``n`` coefficient vectors (mu_s, A, B, ln V_s) drawn from the fit's
    covariance: shape (n, len(v))."""
    p = [fit.values["mu_s"], fit.values["A"], fit.values["B"], math.log(fit.values["V_s"])]
    draws = np.random.default_rng(seed).multivariate_normal(p, fit.covariance, size=n)
    return law(v[None, :] * np.exp(-draws[:, 3:4]), draws[:, 0:1], draws[:, 1:2], draws[:, 2:3])


@pytest.mark.parametrize("weighted", [False, True], ids=["scatter", "mu_err"])
def test_the_band_is_the_spread_of_coefficients_drawn_from_the_covariance(weighted):
    err = np.full(SPEEDS.size, 0.005) if weighted else None
    fit = fit_friction(FrictionCurve(SPEEDS, _draw(4, noise=0.005), err))
    lo, hi = fit.band(V)
    mu = fit.predict(V)
    assert np.all(lo < mu) and np.all(mu < hi)
    half = (hi - lo) / 2
    assert half == pytest.approx(hi - mu, rel=1e-12)  # symmetric about the fit
    samples = _monte_carlo(fit, V)
    spread = fit.quantile * samples.std(axis=0)
    assert half == pytest.approx(spread, rel=0.05)
    inside = np.mean((samples >= lo) & (samples <= hi), axis=0)
    assert np.all(np.abs(inside - 0.95) < 0.02), inside


def test_the_band_holds_the_true_curve_in_about_95_percent_of_refits():
    """Fresh noise, a new fit each time: its band covers the true mu(v) ~95 % of the time."""
    truth = TRUE_LAW.mu(V)
    hits = np.zeros(V.size)
    n = 40
    for seed in range(n):
        fit = fit_friction(FrictionCurve(SPEEDS, _draw(100 + seed)))
        lo, hi = fit.band(V)
        hits += (lo <= truth) & (truth <= hi)
    assert np.all(hits >= 0.85 * n), hits / n


def test_the_band_of_the_example_file_is_narrow_where_measured():
    fit = fit_friction(read_curve(EXAMPLE))
    v = np.geomspace(fit.values["V_s"] / 30, fit.values["V_s"] * 30, 5)
    lo, hi = fit.band(v)
    assert np.all(np.isfinite(lo) & np.isfinite(hi))
    assert np.all(hi - lo < 0.05)  # noise 0.02 on 40 points
    assert fit.band(v[2])[0].shape == ()  # a scalar speed gives scalars


def test_undetermined_coefficients_give_an_unbounded_band():
    """Plateau-only data leave mu_s and A apart undetermined: the band says so by its
    width, not by a narrow band that would pass for knowledge."""
    v = np.geomspace(50, 1000, 40) * TRUE_LAW.V_s
    fit = fit_friction(FrictionCurve(v, _draw(3, noise=0.01, v=v)))
    lo, hi = fit.band(np.array([TRUE_LAW.V_s]))  # at V_s, far below the data
    assert not np.all(hi - lo < 0.5), (lo, hi)
