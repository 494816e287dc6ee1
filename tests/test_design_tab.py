"""The Design tab without a server: physical inputs -> the dimensionless point, the array
readouts for the edited distribution, the optimum on request, and the URL round trip.

The design used here is the notes' LDPE pillars with a load and speed that put them inside
the paper's map (k~_r ~ 0.055, k~_theta ~ 0.49, F~_N ~ 0.44: the slider quadrant), so
the arrays take about a second.
"""
import math

import pytest

from app.state import ExplorerState
from app.defaults import DEFAULTS, DESIGN_INPUTS
from app.urlstate import parse
from app.views.page import Dashboard
from model import Params
from model.designs.distribution_array import distribution_array
from model.designs.distributions import VonMises
from model.contact.friction import mu0

FAST = "?tab=design&d_FN=1%20N&d_V0=100%20m/s&d_Vs=10%20m/s"


def _hand_point():
    """k~_r, k~_theta, F~_N of FAST, from the paper's scalings written out in SI."""
    D, h, E, nu, rho, r0 = 5e-6, 50e-6, 1e9, 0.4, 920.0, 10e-6
    N_c0, F_N, V0 = (1e-3 * 1e-3) / (20e-6 * 20e-6), 1.0, 100.0
    m = rho * math.pi * D ** 2 * h / 4
    G = E / (2 * (1 + nu))
    energy = m * V0 ** 2
    return {"k_r": r0 ** 2 * E * D ** 4 / h ** 3 / energy, "k_theta": G * D ** 4 / h / energy,
            "F_N": r0 * F_N / (N_c0 * energy)}


@pytest.fixture(scope="module")
def page():
    state = ExplorerState()
    assert state.load_query(FAST) == []
    return Dashboard(state)


def test_the_tab_computes_its_point(page):
    r = page.results
    assert r.errors.get("design_point", "") == ""
    point = r.design_point["point"]
    for key, value in _hand_point().items():
        assert point[key] == pytest.approx(value, rel=1e-12), key
    assert point["zeta"] == pytest.approx(10.0) and point["L0"] == pytest.approx(100.0)
    assert r.design_point["status"] == "in_map"
    assert r.design_point["regime"] == "slider"  # k~_r below, k~_theta above sqrt(0.03)
    # The speed line is the diagonal k~ ~ V0^-2 through the design's point.
    line = r.design_point["speed_line"]
    for V, kr, kt in zip(line["V0_m_per_s"], line["k_r"], line["k_theta"]):
        assert kr == pytest.approx(point["k_r"] * (100.0 / V) ** 2, rel=1e-9)
        assert kt / kr == pytest.approx(point["k_theta"] / point["k_r"], rel=1e-9)
    text = page.design.point_text.object
    assert "slider" in text and "inside the paper's explored map" in text
    assert f"{point['k_r']:.3g}" in text


def test_the_readouts_are_the_model_array_in_physical_units(page):
    r, s = page.results, page.state
    assert s.distribution == {"family": "vonmises", "mean_deg": 90.0, "kappa": 4.0}
    a = r.design_array
    assert a is not None and a["success"], a and a["message"]
    hand = _hand_point()
    params = Params(k_r=hand["k_r"], k_theta=hand["k_theta"], F_N=hand["F_N"], zeta=10.0,
                    L0=100.0)
    ref = distribution_array(params, VonMises(math.pi / 2, 4.0), tol=1e-4)
    err = a["array"]["quadrature_error"]["FTx_over_mu0FN"] + ref.quadrature_error[
        "FTx_over_mu0FN"]
    assert a["array"]["FTx_over_mu0FN"] == pytest.approx(ref.FTx_over_mu0FN, abs=3 * err + 1e-4)
    # Back in newtons: F_T,x = (F_T,x/(mu0 F_N)) mu0 F_N with the total load of 1 N.
    assert a["FTx_N"] == pytest.approx(a["array"]["FTx_over_mu0FN"] * mu0(params) * 1.0,
                                       rel=1e-12)
    assert a["power_W"] == pytest.approx(a["FTx_N"] * 100.0, rel=1e-12)
    assert f"{a['array']['FTx_over_mu0FN']:.4f}" in page.design.readouts.object
    assert r.design_polar is not None and len(r.design_polar.columns["theta0"]) > 10


def test_the_density_is_drawn_over_the_polar_curve(page):
    from app.figures import sources
    src = sources(page.design.polar_figure)
    assert len(src["polar_FTx"].data["x"]) > 10
    assert len(src["design_density"].data["x"]) > 10
    page.state.dist_family = "pair"
    try:
        assert len(src["design_density"].data["x"]) == 0
        assert len(src["design_atoms"].data["xs"]) == 2  # +theta0 and -theta0
    finally:
        page.state.dist_family = "vonmises"


def test_optimise_sets_the_optimum_and_shows_the_gain(page):
    s, r = page.state, page.results
    s.dist_family = "pair"
    r.optimise()  # synchronous without a server
    o = r.design_optimum
    assert o is not None and o["family"] == "pair", r.errors
    assert s.dist_family == "pair"
    assert s.dist_deg == pytest.approx(o["theta0_deg"] % 360.0)
    assert o["FTx_over_mu0FN"] <= o["uniform_FTx_over_mu0FN"] + o["error_estimate"]
    assert "less friction" in page.design.optimum_text.object
    # The readouts follow the optimum's distribution.
    assert r.design_array["array"]["distribution"]["family"] == "pair"
    r.cancel_optimum()
    assert r.optimum_note == "Nothing to cancel."


@pytest.mark.parametrize("name, text, named", [
    ("design_E", "1 kg", "E="), ("design_D", "5 xx", "D="), ("design_V0", "fast", "V0="),
    ("design_rho", "-920 kg/m^3", "rho=")])
def test_a_bad_input_is_named_and_nothing_is_computed(name, text, named):
    state = ExplorerState()
    state.load_query(FAST)
    setattr(state, name, text)
    page = Dashboard(state)
    r = page.results
    assert named in r.errors["design_point"]
    assert r.design_point is None and r.design_array is None and r.design_polar is None
    assert not r.errors.get("design_array") and not r.errors.get("design_polar")
    assert named in page.design.point_text.object


def test_the_url_round_trip():
    s = ExplorerState()
    assert not any(k.startswith(("d_", "dist", "kappa", "psi")) for k in s.to_query())
    s.param.update(design_D="7 um", design_G="0.5 GPa", design_V0="2 m/s",
                   dist_family="fixed", dist_deg=30.0, dist_kappa=2.5, dist_psi=-15.0,
                   tab="design")
    query = s.to_query()
    assert query["d_D"] == "7 um" and query["dist"] == "fixed" and query["psi_deg"] == "-15"
    assert "d_h" not in query  # defaults are not written
    t = ExplorerState()
    assert t.load_query(s.to_search()) == []
    assert t.values() == s.values()
    assert t.design_inputs["G"] == "0.5 GPa" and "nu" not in t.design_inputs


def test_unusable_url_values_keep_defaults_with_a_notice():
    values, notices = parse("?d_E=3%20m&kappa=-1&dist=gauss")
    assert values == {}
    assert len(notices) == 3 and "d_E" in notices[0]
    assert set(DESIGN_INPUTS) <= set(DEFAULTS)


def test_a_mixture_of_two_weighted_components_is_edited_computed_and_drawn(page):
    from app.figures import sources
    s, r = page.state, page.results
    src = sources(page.design.polar_figure)
    try:
        s.param.update(dist_family="vonmises", dist_deg=90.0, dist_kappa=4.0, mix_weight=0.25,
                       dist2_family="fixed", dist2_deg=30.0)
        assert s.distribution == {"family": "mixture", "weights": [0.75, 0.25], "components": [
            {"family": "vonmises", "mean_deg": 90.0, "kappa": 4.0},
            {"family": "fixed", "theta0_deg": 30.0}]}
        a = r.design_array
        assert a is not None and a["array"]["distribution"]["family"] == "mixture"
        # The array is linear in the distribution at a fixed beta: the mixture's F_T,x is
        # the weighted sum of its components' at the mixture's beta.
        hand = _hand_point()
        p = Params(k_r=hand["k_r"], k_theta=hand["k_theta"], F_N=hand["F_N"], zeta=10.0,
                   L0=100.0)
        beta = a["array"]["beta"]
        vm = distribution_array(p, VonMises(math.pi / 2, 4.0), beta=beta, tol=1e-4)
        from model.designs.distributions import Fixed
        fx = distribution_array(p, Fixed(math.radians(30.0)), beta=beta)
        mixed = 0.75 * vm.FTx_over_mu0FN + 0.25 * fx.FTx_over_mu0FN
        assert a["array"]["FTx_over_mu0FN"] == pytest.approx(mixed, abs=3e-3)
        # Drawn: the von Mises density and the fixed component's point mass.
        assert len(src["design_density"].data["x"]) > 10
        assert len(src["design_atoms"].data["xs"]) == 1
        assert not page.design.family2.disabled and page.design.kappa2.disabled
    finally:
        s.param.update(mix_weight=0.0, dist2_family="fixed", dist2_deg=0.0)
    assert page.design.family2.disabled


def test_optimise_for_the_largest_sideways_force_under_a_bound(page):
    # Here every fixed orientation has F_T,x/(mu0 F_N) >= 0.98 and |F_T,y| up to ~0.03.
    s, r = page.state, page.results
    try:
        s.param.update(dist_family="fixed", opt_objective="max-FTy", opt_bound=0.95)
        assert "largest |F_T,y|" in page.design.optimum_text.object
        assert page.design.bound.name == "bound on F_T,x/(μ₀F_N)"
        r.optimise()
        o = r.design_optimum
        assert o is not None and o["objective"] == "max-FTy" and o["max_FTx"] == 0.95, r.errors
        assert not o["feasible"] and "could not be met" in page.design.optimum_text.object
        s.opt_bound = 0.997  # a new question drops the old answer
        assert r.design_optimum is None
        r.optimise()
        o = r.design_optimum
        assert o["feasible"] and o["FTx_over_mu0FN"] <= 0.997 + o["error_estimate"]
        assert abs(o["FTy_over_mu0FN"]) > 0.005
        assert s.dist_family == "fixed" and s.mix_weight == 0.0
        assert s.dist_deg == pytest.approx(o["theta0_deg"] % 360.0)
        assert "F_T,y/(μ₀F_N)" in page.design.optimum_text.object
    finally:
        s.param.update(dist_family="vonmises", dist_deg=90.0, opt_objective="min-FTx",
                       opt_bound=None)


@pytest.mark.parametrize("family, objective, mixed, searched", [
    ("uniform", "min-FTx", 0.0, "pair"), ("pair", "max-FTy", 0.0, "fixed"),
    ("vonmises", "max-FTy", 0.0, "vonmises"), ("fixed", "min-FTx", 0.5, "mixture")])
def test_the_family_searched_follows_the_editor_and_the_objective(family, objective, mixed,
                                                                   searched):
    from app.results import optimum_family
    s = ExplorerState(dist_family=family, opt_objective=objective, mix_weight=mixed)
    assert optimum_family(s) == searched


def test_an_optimum_mixture_fills_both_components():
    s = ExplorerState()
    s.set_distribution({"family": "mixture", "weights": [0.6, 0.4], "components": [
        {"family": "fixed", "theta0_deg": 20.0}, {"family": "fixed", "theta0_deg": -70.0}]})
    assert (s.dist_family, s.dist_deg, s.dist2_family, s.dist2_deg) == ("fixed", 20.0, "fixed",
                                                                        290.0)
    assert s.mix_weight == pytest.approx(0.4)
    s.set_distribution({"family": "pair", "theta0_deg": 45.0})
    assert s.mix_weight == 0.0 and s.distribution == {"family": "pair", "theta0_deg": 45.0}


def test_the_mixture_and_the_objective_are_in_the_url():
    s = ExplorerState()
    assert not any(k in s.to_query() for k in ("mix", "dist2", "objective", "bound"))
    s.param.update(mix_weight=0.3, dist2_family="vonmises", dist2_deg=200.0, dist2_kappa=8.0,
                   opt_objective="max-FTy", opt_bound=0.97)
    query = s.to_query()
    assert query["mix"] == "0.3" and query["dist2"] == "vonmises" and query["kappa2"] == "8"
    assert query["objective"] == "max-FTy" and query["bound"] == "0.97"
    t = ExplorerState()
    assert t.load_query(s.to_search()) == []
    assert t.values() == s.values() and t.distribution == s.distribution
    values, notices = parse("?mix=1.5&objective=fastest&bound=-1&dist2=gauss")
    assert values == {} and len(notices) == 4
    assert "mix='1\\.5' is not usable (a number in [0, 1]" in notices[0]
    assert "bound='-1' is not usable (a number in [0, 2]" in notices[2]
