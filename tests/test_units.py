"""Physical units of a pillar design (model.designs.units): the notes' worked example by hand,
parsing and its errors, the round trip, regimes along the speed and height lines."""
import math

import numpy as np
import pint
import pytest

from model.designs.distributions import Fixed, Pair
from model.contact.friction import mu0
from model.designs.design_point import evaluate, regime_intervals, speed_line
from model.contact.regimes import EXPLORED_MAP, MODEL_RANGE, REGIME_SPLIT, regime_of
from model.designs.units import BEAM_PREFACTORS, PillarDesign, ureg


def test_worked_example_by_hand():
    d = PillarDesign.example()
    # D = 5 um, h = 50 um, E = 1 GPa, nu = 0.4, rho = 920 kg/m^3, r0 = 10 um, V0 = 1 cm/s.
    m = 920 * math.pi * (5e-6) ** 2 * 50e-6 / 4
    k_r = 1e9 * (5e-6) ** 4 / (50e-6) ** 3
    G = 1e9 / (2 * 1.4)
    k_t = G * (5e-6) ** 4 / 50e-6
    assert d.mass == pytest.approx(m, rel=1e-12) and m == pytest.approx(9.0e-13, rel=0.01)
    assert d.k_r == pytest.approx(5.0, rel=1e-12)
    assert d.k_theta == pytest.approx(k_t, rel=1e-12) and k_t == pytest.approx(4.46e-9, rel=1e-3)
    x = d.dimensionless()
    assert x["k_r"] == pytest.approx((10e-6) ** 2 * k_r / (m * 0.01 ** 2), rel=1e-12)
    assert x["k_r"] == pytest.approx(5.5e6, rel=0.01)
    assert x["k_theta"] == pytest.approx(4.9e7, rel=0.01)
    # 1 mm x 1 mm slab on a 20 um square lattice: N_c0 = 2500 pillars; L0 = 1 mm / 10 um.
    assert d.N_c0 == pytest.approx(2500) and x["L0"] == pytest.approx(100)
    assert x["F_N"] == pytest.approx(10e-6 * 1e-3 / (2500 * m * 0.01 ** 2), rel=1e-12)
    assert x["zeta"] == pytest.approx(10.0)
    # k~_theta / k~_r = G h^2 / (E r0^2): geometry and material only.
    assert x["k_theta"] / x["k_r"] == pytest.approx(G * (50e-6) ** 2 / (1e9 * (10e-6) ** 2))
    assert d.regime() == "stiff"


def test_beam_prefactors_scale_the_stiffnesses():
    d = PillarDesign.example()
    b = d.replace(prefactor_r=BEAM_PREFACTORS["k_r"], prefactor_theta=BEAM_PREFACTORS["k_theta"])
    assert BEAM_PREFACTORS == {"k_r": pytest.approx(3 * math.pi / 64),
                               "k_theta": pytest.approx(math.pi / 32)}
    assert b.k_r == pytest.approx(d.k_r * 3 * math.pi / 64)
    assert b.k_theta == pytest.approx(d.k_theta * math.pi / 32)


def test_text_and_pint_quantities_and_units_agree():
    a = PillarDesign.example()
    b = PillarDesign.example(D="0.005 mm", h=ureg.Quantity(5e-5, "m"), E="1000 MPa",
                             F_N=pint.Quantity(1000.0, "uN"), V0="36 m/hr", rho="0.92 g/cm^3")
    for name in ("k_r", "k_theta", "F_N", "zeta", "L0"):
        assert b.dimensionless()[name] == pytest.approx(a.dimensionless()[name], rel=1e-12)
    g = PillarDesign.example(nu=None, G=f"{1 / 2.8} GPa")
    assert g.k_theta == pytest.approx(a.k_theta, rel=1e-12)


def test_round_trip_physical_dimensionless_physical():
    d = PillarDesign.example(V0="3 mm/s", L_x="0.3 mm", F_N="20 uN")
    x, s = d.dimensionless(), d.scales
    assert x["k_r"] * s.energy / d.r0 ** 2 == pytest.approx(d.k_r, rel=1e-13)
    assert x["k_theta"] * s.energy == pytest.approx(d.k_theta, rel=1e-13)
    assert x["F_N"] * d.N_c0 * s.force == pytest.approx(d.F_N, rel=1e-13)
    assert x["L0"] * d.r0 == pytest.approx(d.L_x, rel=1e-13)
    assert d.V0 / x["zeta"] == pytest.approx(d.V_s, rel=1e-13)
    # And back through the readable units of to_dict.
    readable = d.to_dict()
    units = readable.pop("units")
    again = PillarDesign(**{k: (f"{v} {units[k]}" if k in units else v)
                            for k, v in readable.items()})
    assert again.dimensionless() == pytest.approx(x, rel=1e-12)


@pytest.mark.parametrize("change, match", [
    (dict(E="-1 GPa"), r"E='-1 GPa' must be finite and positive"),
    (dict(D="5 kg"), r"D='5 kg' has dimension \[mass\]; D is a \[length\]"),
    (dict(V0="1 cm"), r"V0='1 cm' has dimension \[length\]"),
    (dict(h=50), r"h=50 has no unit"),
    (dict(rho="920"), r"rho='920' has no unit"),
    (dict(D="five um"), r"D='five um' cannot be read"),
    (dict(nu="0.4 m"), r"nu='0.4 m' must be dimensionless"),
    (dict(nu=0.7), r"nu=0.7 must be in"),
    (dict(G="1 GPa"), r"give the shear modulus G or Poisson's ratio nu"),
    (dict(nu=None), r"give the shear modulus G or Poisson's ratio nu"),
    (dict(mass_fraction=2), r"mass_fraction=2"),
    (dict(F_N="nan mN"), r"F_N='nan mN' must be finite"),
])
def test_bad_inputs_name_the_input(change, match):
    with pytest.raises(ValueError, match=match):
        PillarDesign.example(**change)


def test_regime_quadrants():
    s = REGIME_SPLIT
    assert EXPLORED_MAP[0] < s < EXPLORED_MAP[1]
    assert [regime_of(a, b) for a, b in ((3, 0.01), (0.01, 3), (3, 3), (0.03, 0.03))] == \
        ["pendulum", "slider", "stiff", "soft"]


def middle(lo, hi):
    """A point inside (lo, hi), either end possibly 0 or infinite."""
    if lo > 0 and math.isfinite(hi):
        return math.sqrt(lo * hi)
    return hi / 2 if lo == 0 else 2 * lo


@pytest.mark.parametrize("geometry", [dict(), dict(h="20 um", r0="40 um")])
def test_regime_intervals_agree_with_the_regime_at_each_speed_and_height(geometry):
    d = PillarDesign.example(**geometry)
    iv = regime_intervals(d)
    reached = 0
    for regime, span in iv["V0_m_per_s"].items():
        if span is None:
            continue
        lo, hi = span
        mid = middle(lo, hi)
        assert d.replace(V0=f"{mid} m/s").regime() == regime
        reached += 1
    assert reached == 3  # speed moves along a diagonal: one middle regime is out of reach
    for regime, span in iv["h_m"].items():
        if span is None:
            continue
        lo, hi = span
        mid = middle(lo, hi)
        assert d.replace(h=f"{mid} m").regime() == regime
    lo, hi = iv["V0_in_explored_map_m_per_s"]
    inside = d.replace(V0=f"{math.sqrt(lo * hi)} m/s").dimensionless()
    assert all(EXPLORED_MAP[0] <= inside[k] <= EXPLORED_MAP[1] for k in ("k_r", "k_theta"))


def test_evaluate_in_the_map_gives_physical_results_from_the_array():
    # 100 m/s brings the worked example's pillars into the paper's map.
    d = PillarDesign.example(V0="100 m/s", V_s="10 m/s", L_x="0.1 mm", L_y="0.1 mm",
                             F_N="0.01 uN")
    r = evaluate(d, Pair(1.0))
    assert r.status == "in_map" and r.success, r.array.message
    a, p = r.array, d.params()
    assert r.computed["k_r"] == pytest.approx(p.k_r)
    assert r.FTx_N == pytest.approx(a.FTx_over_mu0FN * mu0(p) * d.F_N, rel=1e-12)
    assert r.power_W == pytest.approx(r.FTx_N * 100.0)
    split = a.work_split
    assert r.dissipated_power_W == pytest.approx(r.power_W * (split["D_x"] + split["D_y"]))
    assert r.contact_time_s == pytest.approx(a.Nc_over_Nc0 * 10 * 10e-6 / 100.0, rel=1e-12)
    assert r.excursion_r_um == pytest.approx(a.dr_rms * 10.0, rel=1e-12)
    assert r.to_dict()["regime"] == r.regime == regime_of(p.k_r, p.k_theta)


def test_evaluate_beyond_the_model_range_scales_along_the_speed_line_and_says_so():
    d = PillarDesign.example(L_x="0.1 mm", L_y="0.1 mm", F_N="1 uN")
    x = d.dimensionless()
    assert max(x["k_r"], x["k_theta"]) > MODEL_RANGE[1]
    r = evaluate(d, Fixed(1.0))
    assert r.status == "scaled" and "as at V0" in r.status_message
    c = r.computed
    assert max(c["k_r"], c["k_theta"]) == pytest.approx(MODEL_RANGE[1])
    # Deflections F~_N/k~ and the stiffness ratio are those of the design.
    assert c["F_N"] / c["k_r"] == pytest.approx(x["F_N"] / x["k_r"], rel=1e-12)
    assert c["k_theta"] / c["k_r"] == pytest.approx(x["k_theta"] / x["k_r"], rel=1e-12)
    assert r.success and np.isfinite(r.FTx_N)
    # Stiff pillars: the drive force is the rigid-contact one, mu0 F_N, to ~1e-4.
    assert r.array.FTx_over_mu0FN == pytest.approx(1.0, abs=1e-3)


def test_evaluate_refuses_a_design_below_the_model_range_with_the_speed_that_fixes_it():
    d = PillarDesign.example(V0="1 km/s", V_s="100 m/s")
    with pytest.raises(ValueError, match=r"V0=1000 m/s puts k~_r = .* V0 <= .* m/s"):
        evaluate(d)


def test_speed_line_is_a_diagonal_through_the_design():
    d = PillarDesign.example(V0="1 m/s")  # inside the model range: on its own line
    line = speed_line(d, n=41)
    x = d.dimensionless()
    logs = np.log10(np.column_stack([line["k_r"], line["k_theta"]]))
    assert np.allclose(np.diff(logs[:, 1]) / np.diff(logs[:, 0]), 1.0)  # slope 1: a diagonal
    assert np.allclose(line["k_theta"] / line["k_r"], x["k_theta"] / x["k_r"])
    assert max(line["k_r"][0], line["k_theta"][0]) == pytest.approx(MODEL_RANGE[1])
    assert min(line["k_r"][-1], line["k_theta"][-1]) == pytest.approx(MODEL_RANGE[0])
    at = np.interp(math.log(d.V0), np.log(line["V0_m_per_s"]), np.log(line["k_r"]))
    assert math.exp(at) == pytest.approx(x["k_r"], rel=1e-9)
    with pytest.raises(ValueError, match="V_min"):
        speed_line(d, V_min="1 m/s", V_max="1 cm/s")
    with pytest.raises(ValueError, match="V0="):
        speed_line(d, V_min="1 m")
