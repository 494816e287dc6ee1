"""Real pillars lie far outside the paper's map: the model answers for k~_r, k~_theta
anywhere in [1e-3, 1e6] (finite results, a named outcome, a statement that the point is
outside the explored map, bounded cost under a time budget), tends to the rigid-surface
limit as both stiffnesses grow (docs/model.md, "Real pillars: beyond the explored map"),
and computes a design beyond the model range scaled along its speed line."""
import math

import pytest

from model import Params
from model.designs.design_point import evaluate, model_point
from model.designs.distribution_array import OUTCOMES, distribution_array
from model.designs.distributions import Uniform, VonMises
from model.designs.units import PillarDesign

NUMBERS = ("FTx_over_mu0FN", "FTx_over_mu0FN_duration", "FTy_over_mu0FN", "Dy_over_Dx",
           "Nc_over_Nc0", "beta", "Uel_over_W")


def finite(record: dict) -> bool:
    return all(math.isfinite(record[k]) for k in NUMBERS)


@pytest.mark.parametrize("k_r, k_theta", [(1e-3, 1e-3), (1e-3, 1e6), (1e6, 1e-3),
                                          (1e6, 1e6), (1e-3, 30.0), (300.0, 3e4)])
def test_anywhere_in_the_model_range_gives_finite_results_and_a_named_outcome(k_r, k_theta):
    """The corners of [1e-3, 1e6]^2 and points between; a 3 s budget bounds the cost (the
    compliant-radial, stiff-torsional corner rings for longer than that and says so).

    How far 3 s goes depends on the machine: on a slow or busy one no member of a stiff
    corner may finish. The result must then say so (no value, never a made-up one), and
    the same point with a larger budget must answer."""
    def run(budget):
        a = distribution_array(Params(k_r=k_r, k_theta=k_theta, F_N=1.0),
                               VonMises(math.radians(60), 4.0), tol=1e-3, budget=budget)
        r = a.to_dict()
        assert r["outcome"] in OUTCOMES and r["success"] is (r["outcome"] == "ok")
        assert r["map_status"] == "outside_map"
        assert "outside the paper's explored map" in r["message"]
        return a, r

    a, r = run(3.0)
    if a.n_failed == a.n_members:
        # Nothing finished in time: a named budget outcome and no number at all.
        assert r["outcome"] == "contacts_cut" and not r["success"]
        assert f"none of the {a.n_members} members finished" in r["message"]
        assert not any(math.isfinite(r[k]) for k in NUMBERS), r
        a, r = run(60.0)
    assert finite(r), r
    assert 0.0 < r["FTx_over_mu0FN"] < 1.5 and 0.0 < r["beta"] <= 1.0


def test_stiff_arrays_tend_to_the_rigid_surface_limit():
    """k~_r = k~_theta -> infinity at fixed F~_N: the support no longer moves, so its
    friction is f_N mu(1) = f_N mu0 along +x for the whole contact and tau_out = L0:
    F_T,x/(mu0 F_N) -> 1, F_T,y -> 0, D_y/D_x -> 0, N_c/N_c0 -> 1, beta -> 1."""
    gaps = []
    for k in (1e2, 1e4, 1e6):
        a = distribution_array(Params(k_r=k, k_theta=k, F_N=1.0), Uniform(), tol=1e-4)
        assert a.success, a.message
        gaps.append(abs(a.FTx_over_mu0FN - 1.0))
        assert a.FTy_over_mu0FN == 0.0 and a.Dy_over_Dx < 1e-3
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 1e-6
    assert a.Nc_over_Nc0 == pytest.approx(1.0, abs=1e-5)
    assert a.beta == pytest.approx(1.0, abs=1e-5)
    # A concentrated distribution sees the same limit: every orientation is rigid.
    v = distribution_array(Params(k_r=1e6, k_theta=1e6, F_N=1.0), VonMises(1.0, 50.0))
    assert v.FTx_over_mu0FN == pytest.approx(1.0, abs=1e-6)
    assert abs(v.FTy_over_mu0FN) < 1e-6


def test_a_real_pillar_at_one_centimetre_per_second_is_scaled_and_answers():
    """The worked example (LDPE pillars at V0 = 1 cm/s) has k~ ~ 5e6 and 5e7: beyond the
    model range, computed where its speed line enters it (k~_theta = 1e6), with the status
    saying so; under a 2 s budget the array ends with a named outcome, finite, and at the
    rigid-surface limit to within the cut contacts' error."""
    design = PillarDesign.example()
    d = design.dimensionless()
    assert d["k_r"] > 1e6 and d["k_theta"] > 1e6
    point, status, message = model_point(design)
    assert status == "scaled" and "quasi-static" in message
    assert point["k_theta"] == pytest.approx(1e6)
    # Scaled as by a faster slab: the deflections F~_N / k~ are kept.
    assert point["F_N"] / point["k_r"] == pytest.approx(d["F_N"] / d["k_r"])
    r = evaluate(design, budget=2.0).to_dict()
    assert r["status"] == "scaled" and r["array"]["outcome"] in OUTCOMES
    assert finite(r["array"]) and math.isfinite(r["FTx_N"]) and math.isfinite(r["power_W"])
    assert r["FTx_over_mu0FN"] == pytest.approx(1.0, abs=0.02)


def test_a_design_the_model_cannot_reach_is_refused_with_the_remedy():
    """Far too fast a slab for soft pillars puts k~ below 1e-3: no computation, the speed
    that brings the design into range is named."""
    design = PillarDesign.example(V0="1000 km/s")
    with pytest.raises(ValueError, match=r"below the model range .* V0 <= "):
        model_point(design)
