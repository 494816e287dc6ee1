"""Orientation distributions and their p-weighted arrays (model.designs.distributions,
model.designs.distribution_array): normalisation, limits, symmetry, and agreement with an
independent dense reference."""
import math

import numpy as np
import pytest

from model import Params, fixed_orientation, orientation_sweep, uniform_array
from model.designs.distribution_array import distribution_array
from model.designs.distributions import (Fixed, Histogram, Mixture, Pair, Rotated, Uniform, VonMises,
                                 from_dict, rotated)
from model.contact.params import REGIMES

CIRCLE = np.linspace(0.0, 2 * math.pi, 200_001)


def total_mass(dist):
    return np.trapezoid(dist.density(CIRCLE), CIRCLE) + sum(w for _, w in dist.atoms())


@pytest.mark.parametrize("dist", [
    Uniform(), VonMises(1.0, 0.0), VonMises(-2.0, 3.0), VonMises(0.3, 1e4), Fixed(0.4),
    Pair(2.0), Histogram((0.0, 1.0, 2.5), (1.0, 3.0)),
    Mixture((VonMises(1.0, 5.0), Fixed(2.0), Uniform()), (2.0, 1.0, 1.0))],
    ids=lambda d: type(d).__name__)
def test_every_distribution_has_unit_mass(dist):
    # Trapezoid rule on a 3e-5 rad grid: exact to ~1e-5 across a histogram's jumps.
    assert total_mass(dist) == pytest.approx(1.0, abs=5e-5)


def test_von_mises_density_formula_and_limits():
    from scipy.special import i0

    theta = np.linspace(-math.pi, math.pi, 7)
    d = VonMises(0.5, 2.0)
    expected = np.exp(2.0 * np.cos(theta - 0.5)) / (2 * math.pi * i0(2.0))
    np.testing.assert_allclose(d.density(theta), expected, rtol=1e-13)
    np.testing.assert_allclose(VonMises(1.0, 0.0).density(theta), 1 / (2 * math.pi))
    # Large kappa: no overflow, the peak is sqrt(kappa / 2 pi).
    peak = VonMises(0.0, 1e6).density(np.array([0.0, 1.0]))
    assert np.all(np.isfinite(peak)) and peak[0] == pytest.approx(math.sqrt(1e6 / (2 * math.pi)),
                                                                   rel=1e-6)


def test_rotation_by_psi_shifts_the_density_and_the_atoms():
    base = VonMises(1.0, 3.0)
    r = rotated(base, 0.4)
    theta = np.linspace(-3, 3, 11)
    np.testing.assert_allclose(r.density(theta), VonMises(0.6, 3.0).density(theta), rtol=1e-13)
    assert Rotated(Fixed(1.0), 0.4).atoms() == ((pytest.approx(0.6), 1.0),)
    assert rotated(base, 0.0) is base


@pytest.mark.parametrize("dist", [
    Fixed(0.3), Pair(1.2), Uniform(), VonMises(1.0, 4.0),
    Mixture((VonMises(1.0, 4.0), Fixed(0.5)), (0.25, 0.75)),
    Histogram((0.0, 1.0, 2.0), (0.5, 0.5)), Rotated(VonMises(1.0, 4.0), 0.2)],
    ids=lambda d: type(d).__name__)
def test_to_dict_round_trip(dist):
    back = from_dict(dist.to_dict())
    theta = np.linspace(-3, 3, 13)
    np.testing.assert_allclose(back.density(theta), dist.density(theta), rtol=1e-12, atol=1e-15)
    assert [(pytest.approx(t), pytest.approx(w)) for t, w in back.atoms()] == list(dist.atoms())


@pytest.mark.parametrize("make, match", [
    (lambda: VonMises(0.0, -1.0), "kappa=-1.0"),
    (lambda: VonMises(0.0, float("nan")), "kappa=nan"),
    (lambda: VonMises(float("inf"), 1.0), "mean=inf"),
    (lambda: Fixed("a"), "theta0='a'"),
    (lambda: Mixture((Fixed(0.0),), (-1.0,)), "weights="),
    (lambda: Mixture((Fixed(0.0), Uniform()), (1.0,)), "one weight per component"),
    (lambda: Histogram((), ()), "non-empty"),
    (lambda: Histogram((0.0, 1.0), (0.0,)), "not all 0"),
    (lambda: Histogram((1.0, 0.0), (1.0,)), "increasing"),
    (lambda: from_dict({"family": "gauss"}), "family='gauss'"),
])
def test_bad_distributions_are_named(make, match):
    with pytest.raises(ValueError, match=match):
        make()


@pytest.mark.parametrize("text, match", [
    ("", "is empty"), ("theta0_deg,weight\n", "is empty"),
    ("theta0_deg,weight\n10,abc\n", "non-numeric"), ("angle,weight\n10,1\n", "header"),
    ("theta0_deg,weight\n10,1\n15,1\n40,1\n", "equally spaced"),
    ("theta0_deg,weight\n10,0\n20,0\n", "not all 0"),
    ("# measured\ntheta0_deg,weight\n10,1\n20,-1\n", "negative weight -1 on line 4"),
    ("theta0_deg,weight\n10,1\n20,inf\n", "not finite"),
    ("theta0_deg,weight\n10,1,3\n", "line 2 has 3 columns"),
    ("lower_deg,upper_deg,weight\n0,200,1\n200,400,1\n", "span at most 360"),
])
def test_bad_histogram_files_are_named_before_any_work(tmp_path, text, match, monkeypatch):
    import model.designs.distribution_array as da

    def boom(*args, **kwargs):
        raise AssertionError("a contact was integrated")

    monkeypatch.setattr(da, "run_contacts", boom)
    path = tmp_path / "h.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=match):
        Histogram.from_csv(path)


def test_histogram_csv_forms_agree(tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    a.write_text("theta0_deg,weight\n10,1\n30,2\n50,1\n")
    b.write_text("lower_deg,upper_deg,weight\n0,20,1\n20,40,2\n40,60,1\n")
    ha, hb = Histogram.from_csv(a), Histogram.from_csv(b)
    np.testing.assert_allclose(ha.edges, hb.edges, atol=1e-12)
    np.testing.assert_allclose(ha.weights, [0.25, 0.5, 0.25])


# --------------------------------------------------------------------------- arrays

@pytest.mark.parametrize("name", list(REGIMES))
def test_uniform_distribution_reproduces_uniform_array(name):
    p = REGIMES[name]
    u = uniform_array(p, tol=1e-3)
    d = distribution_array(p, Uniform(), tol=1e-3)
    assert d.success, d.message
    for key in ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "Nc_over_Nc0", "Dy_over_Dx"):
        slack = u.quadrature_error[key] + d.quadrature_error[key] + 1e-6
        assert abs(getattr(d, key) - getattr(u, key)) <= slack, key
    assert d.beta == pytest.approx(u.beta, abs=1e-4)
    assert d.FTy_over_mu0FN == 0.0  # the folded odd weight of a symmetric density
    assert d.map_status == "in_map" and d.message == "ok"


@pytest.mark.parametrize("name", ["pendulum", "slider"])
@pytest.mark.parametrize("theta0", [0.7, 2.2])
def test_pair_has_no_transverse_force_and_the_fixed_friction(name, theta0):
    p = REGIMES[name]
    d = distribution_array(p, Pair(theta0), tol=1e-6, rtol=1e-8)  # beta to tol/100
    f = fixed_orientation(p.replace(theta0=theta0), rtol=1e-8)
    assert d.FTy_over_mu0FN == 0.0
    assert d.FTx_over_mu0FN == pytest.approx(f.FTx_over_mu0FN, abs=1e-6)
    assert d.beta == pytest.approx(f.beta, abs=1e-6)
    assert f.FTy_over_mu0FN != 0.0  # the fixed array does push sideways


@pytest.mark.parametrize("name", ["pendulum", "soft"])
def test_von_mises_tends_to_fixed_and_to_uniform(name):
    p = REGIMES[name]
    m = 1.1
    f = fixed_orientation(p.replace(theta0=m), rtol=1e-7)
    previous = math.inf
    for kappa in (1e2, 1e4, 1e6):
        d = distribution_array(p, VonMises(m, kappa), tol=1e-5)
        gap = abs(d.FTx_over_mu0FN - f.FTx_over_mu0FN) + abs(d.FTy_over_mu0FN - f.FTy_over_mu0FN)
        assert gap < previous or gap < 1e-5  # converges like 1/kappa
        previous = gap
    assert previous < 1e-4
    zero = distribution_array(p, VonMises(m, 0.0), tol=1e-3)
    uni = distribution_array(p, Uniform(), tol=1e-3)
    assert zero.FTx_over_mu0FN == pytest.approx(uni.FTx_over_mu0FN, abs=1e-12)
    assert zero.FTy_over_mu0FN == pytest.approx(0.0, abs=1e-12)


def test_psi_rotates_and_the_mirror_flips_the_transverse_force():
    p = REGIMES["slider"]
    a = distribution_array(p, VonMises(1.0, 4.0), psi=0.3)
    b = distribution_array(p, VonMises(0.7, 4.0))
    assert a.FTx_over_mu0FN == pytest.approx(b.FTx_over_mu0FN, abs=1e-9)
    c = distribution_array(p, VonMises(-0.7, 4.0))
    assert c.FTy_over_mu0FN == pytest.approx(-b.FTy_over_mu0FN, abs=1e-9)
    assert c.FTx_over_mu0FN == pytest.approx(b.FTx_over_mu0FN, abs=1e-9)


def test_mixture_is_linear_at_fixed_beta():
    p = REGIMES["pendulum"]
    A, B = VonMises(1.0, 3.0), Fixed(2.5)
    a = distribution_array(p, A, beta=0.9, tol=1e-6)
    b = distribution_array(p, B, beta=0.9, tol=1e-6)
    m = distribution_array(p, Mixture((A, B), (0.3, 0.7)), beta=0.9, tol=1e-6)
    for key in ("FTx_over_mu0FN", "FTy_over_mu0FN", "Nc_over_Nc0"):
        assert getattr(m, key) == pytest.approx(0.3 * getattr(a, key) + 0.7 * getattr(b, key),
                                                abs=3e-6)


def _reference(params, dist, beta, n=720):
    """p-weighted averages by the midpoint rule on the full circle (spectrally accurate
    for smooth periodic integrands), on fixed-orientation arrays at rtol 1e-10."""
    theta = (np.arange(n) + 0.5) * 2 * math.pi / n - math.pi
    w = dist.density(theta) * 2 * math.pi / n

    def at(b):
        s = orientation_sweep(params, theta, beta=b, rtol=1e-10)
        assert np.all(s.success)
        return s

    if beta == "self":
        from scipy.optimize import brentq

        b = brentq(lambda b: b - params.L0 / (w @ at(b).contacts.t_out), 0.05, 1.0, xtol=1e-12)
    else:
        b = beta
    s = at(b)
    return w @ s.FTx_over_mu0FN, w @ s.FTy_over_mu0FN, w @ s.Nc_over_Nc0, b


@pytest.mark.parametrize("k_r, k_theta, F_N, beta", [
    (3.0, 0.01, 1.0, 0.9), (0.03, 0.03, 1.0, "self"), (3.0, 3.0, 3.0, 0.7),
    (0.3, 0.1, 0.5, "self")])
def test_von_mises_agrees_with_a_tight_reference(k_r, k_theta, F_N, beta):
    p = Params(k_r, k_theta, F_N=F_N)
    dist = VonMises(1.0, 3.0)
    fx, fy, nc, b = _reference(p, dist, beta)
    d = distribution_array(p, dist, beta=beta, tol=1e-5)
    assert d.success, d.message
    assert d.FTx_over_mu0FN == pytest.approx(fx, abs=3e-5)
    assert d.FTy_over_mu0FN == pytest.approx(fy, abs=3e-5)
    assert d.Nc_over_Nc0 == pytest.approx(nc, abs=3e-5)
    assert d.beta == pytest.approx(b, abs=1e-5)


def test_concentrated_mass_costs_no_trajectory_where_the_density_vanishes(monkeypatch):
    import model.designs.distribution_array as da

    seen = []
    real = da.run_contacts

    def spy(params, theta, *args, **kwargs):
        seen.append(np.array(theta, dtype=float, ndmin=1))
        return real(params, theta, *args, **kwargs)

    monkeypatch.setattr(da, "run_contacts", spy)
    dist = VonMises(1.0, 1e4)
    d = distribution_array(REGIMES["pendulum"], dist, tol=2e-3)
    assert d.success, d.message
    theta = np.concatenate(seen)
    # Every integrated orientation carries mass; nodes beyond ~12 standard deviations
    # (|theta - 1| > 0.12 rad) were skipped although the partition covers [0, pi].
    assert np.all(np.abs(theta - 1.0) < 0.15)
    assert d.n_members > np.unique(theta).size


def test_a_budget_bounds_the_refinement():
    d = distribution_array(REGIMES["slider"], VonMises(2.0, 2.0), tol=1e-7, budget=0.05)
    assert not d.success and "time budget" in d.message
    assert math.isfinite(d.FTx_over_mu0FN)
    # Cut short, the result carries no error bar that looks like a converged one: none at
    # all when beta was not settled, else the bounds that hold whatever the cut members do.
    error = d.quadrature_error["FTx_over_mu0FN"]
    if d.outcome == "beta_cut" or "FTx_over_mu0FN" not in d.bounds:
        assert math.isnan(error)
    else:
        lo, hi = d.bounds["FTx_over_mu0FN"]
        assert lo <= d.FTx_over_mu0FN <= hi and error == max(hi - d.FTx_over_mu0FN,
                                                             d.FTx_over_mu0FN - lo)


@pytest.mark.parametrize("kwargs, match", [
    (dict(tol=0.0), "tol=0.0"), (dict(beta="auto"), "beta='auto'"), (dict(psi=math.nan), "psi="),
    (dict(budget=-1), "budget=-1"), (dict(beta=1.5), "beta=1.5"),
    (dict(method="reference"), "method='reference'")])
def test_bad_arguments_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        distribution_array(REGIMES["pendulum"], VonMises(1.0, 1.0), **kwargs)


@pytest.mark.parametrize("k_r, k_theta", [(1e6, 1e6), (1e6, 1e-3), (1e-3, 1e6), (1e-3, 1e-3)])
def test_corners_of_the_model_range_answer_with_finite_results_and_a_status(k_r, k_theta):
    d = distribution_array(Params(k_r, k_theta), Pair(1.0), max_steps=200_000)
    assert d.success, d.message
    assert d.map_status == "outside_map" and "outside the paper's explored map" in d.message
    values = [d.FTx_over_mu0FN, d.FTy_over_mu0FN, d.Nc_over_Nc0, d.beta, d.Dy_over_Dx]
    assert all(math.isfinite(v) for v in values)
    if min(k_r, k_theta) == 1e6:
        # Rigid pillars: the slab feels the rigid-contact friction mu0 F_N.
        assert d.FTx_over_mu0FN == pytest.approx(1.0, abs=1e-4)
    # A step budget too small for the stiff ringing is reported, not hidden.
    if max(k_r, k_theta) == 1e6:
        short = distribution_array(Params(k_r, k_theta), Pair(1.0), max_steps=100, beta=1.0)
        assert not short.success and "did not finish" in short.message


def test_a_budget_stops_the_beta_iteration_at_the_best_beta_so_far():
    p = Params(0.01, 3.0, F_N=2.0)
    full = distribution_array(p, Uniform(), tol=1e-4)
    cut = distribution_array(p, Uniform(), tol=1e-4, budget=1e-6)
    assert full.success and not cut.success and "before the self-consistent beta" in cut.message
    assert cut.stats["trajectories"] < full.stats["trajectories"]
    assert math.isfinite(cut.FTx_over_mu0FN) and abs(cut.beta - full.beta) < 0.1


def test_fields_of_params_the_array_would_ignore_are_refused():
    with pytest.raises(ValueError, match="theta0=1.0 is not used by distribution_array"):
        distribution_array(REGIMES["pendulum"].replace(theta0=1.0), Uniform())
    with pytest.raises(ValueError, match="beta=0.5 in params would be ignored"):
        distribution_array(REGIMES["pendulum"].replace(beta=0.5), Uniform())
