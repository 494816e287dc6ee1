"""Validation, immutability and the named regimes of ``Params``."""
import dataclasses
import math

import pytest

from model.arrays.beta import BETA_MIN
from model.contact.params import DEFAULTS, REGIMES, Params

FIELDS = [f.name for f in dataclasses.fields(Params)]


@pytest.mark.parametrize("name", FIELDS)
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_values_are_rejected(name, bad):
    with pytest.raises(ValueError, match=rf"^{name}=.* is invalid"):
        Params(**{"k_r": 1.0, "k_theta": 1.0, name: bad})


@pytest.mark.parametrize("name", FIELDS)
@pytest.mark.parametrize("bad", ["abc", None, [1.0], "", object()])
def test_non_numbers_are_rejected(name, bad):
    with pytest.raises(ValueError, match=rf"^{name}=.* is not a number"):
        Params(**{"k_r": 1.0, "k_theta": 1.0, name: bad})


@pytest.mark.parametrize("name", ["k_r", "k_theta", "F_N", "beta", "mu_s", "A", "zeta", "L0"])
@pytest.mark.parametrize("bad", [0.0, -0.0, -1e-300, -1.0])
def test_positive_fields_reject_zero_and_negative(name, bad):
    with pytest.raises(ValueError, match=rf"^{name}="):
        Params(**{"k_r": 1.0, "k_theta": 1.0, name: bad})


@pytest.mark.parametrize("beta", [BETA_MIN, 0.5, 1.0])
def test_beta_in_its_physical_interval(beta):
    assert Params(1.0, 1.0, beta=beta).beta == beta


@pytest.mark.parametrize("beta", [5e-324, 1e-12, 0.999 * BETA_MIN])
def test_beta_below_its_physical_limit_is_rejected(beta):
    """beta = N_c0/N_c < 1e-3 (contacts over a thousand slab lengths) gave energies of
    1e285 W on the page; the bound is the one the self-consistent solver brackets, and the
    controls read it."""
    from model.controls import CONTROLS
    from model.validation import BETA

    assert BETA.bounds == CONTROLS["beta"].bounds == (BETA_MIN, 1.0) and BETA_MIN == 1e-3
    with pytest.raises(ValueError, match=r"^beta=.* must be finite and in \[0\.001, 1\]"):
        Params(1.0, 1.0, beta=beta)


@pytest.mark.parametrize("beta", [1.0 + 1e-12, 2.0])
def test_beta_above_one_is_rejected(beta):
    with pytest.raises(ValueError, match="beta"):
        Params(1.0, 1.0, beta=beta)


@pytest.mark.parametrize("theta0", [-2 * math.pi, -math.pi, 0.0, math.pi, 2 * math.pi])
def test_theta0_accepts_closed_range(theta0):
    assert Params(1.0, 1.0, theta0=theta0).theta0 == theta0


@pytest.mark.parametrize("theta0", [-2 * math.pi - 1e-9, 2 * math.pi + 1e-9, 10.0, 360.0])
def test_theta0_out_of_range_is_rejected(theta0):
    with pytest.raises(ValueError, match=r"^theta0=.*\[-6\.28319, 6\.28319\]"):
        Params(1.0, 1.0, theta0=theta0)


@pytest.mark.parametrize("lam", [1e-5, 0.51])
def test_repulsion_range_is_bounded(lam):
    with pytest.raises(ValueError, match="^lam="):
        Params(1.0, 1.0, lam=lam)


def test_message_names_value_and_meaning():
    with pytest.raises(ValueError) as info:
        Params(k_r=-1.0, k_theta=1.0)
    assert str(info.value).startswith("k_r=-1.0 is invalid: radial stiffness k_r must be")


def test_values_are_stored_as_float():
    p = Params(k_r=3, k_theta=1)
    assert type(p.k_r) is float and type(p.k_theta) is float


def test_defaults_follow_the_model_constants():
    p = Params(1.0, 1.0)
    assert (p.F_N, p.theta0, p.beta) == (1.0, math.pi / 2, 1.0)
    assert {k: getattr(p, k) for k in DEFAULTS} == DEFAULTS


def test_load_per_support():
    assert Params(1.0, 1.0, F_N=4.0, beta=0.25).f_N == 1.0


def test_frozen():
    p = Params(1.0, 1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.k_r = 2.0


def test_hashable_and_equal_by_value():
    a, b = Params(3.0, 0.01), Params(k_r=3, k_theta=0.01)
    assert a == b and hash(a) == hash(b)
    assert len({a, b, Params(3.0, 0.02)}) == 2
    assert {a: "cached"}[b] == "cached"


def test_replace_changes_only_what_is_asked():
    base = REGIMES["soft"]
    p = base.replace(F_N=3.0)
    assert p.F_N == 3.0 and base.F_N == 1.0
    assert dataclasses.replace(p, F_N=1.0) == base


@pytest.mark.parametrize("change", [{"k_r": -1.0}, {"F_N": 0.0}, {"beta": 1.5},
                                    {"theta0": math.nan}, {"k_theta": "stiff"}])
def test_replace_validates(change):
    with pytest.raises(ValueError, match=f"^{next(iter(change))}="):
        REGIMES["soft"].replace(**change)


def test_as_dict_round_trips():
    p = Params(0.5, 0.2, F_N=2.0, theta0=1.0, beta=0.7)
    assert Params(**p.as_dict()) == p


def test_regimes_match_the_paper():
    stiffness = {name: (p.k_r, p.k_theta) for name, p in REGIMES.items()}
    assert stiffness == {"pendulum": (3.0, 0.01), "slider": (0.01, 3.0),
                         "stiff": (3.0, 3.0), "soft": (0.03, 0.03)}


def test_regime_fixture_defaults(regime_params):
    assert isinstance(regime_params, Params)
    assert (regime_params.F_N, regime_params.theta0, regime_params.beta) == (1.0, math.pi / 2, 1.0)


@pytest.mark.parametrize("name", sorted(REGIMES))
def test_regime_constructor(name):
    assert Params.regime(name) == REGIMES[name]
    p = Params.regime(name, F_N=10.0)
    assert p.F_N == 10.0 and p.k_r == REGIMES[name].k_r


def test_regime_constructor_validates():
    with pytest.raises(ValueError, match="^regime='rigid' is unknown"):
        Params.regime("rigid")
    with pytest.raises(ValueError, match="^F_N="):
        Params.regime("stiff", F_N=-1.0)


def test_array_functions_refuse_fields_they_would_ignore():
    """Per-call choices travel as arguments: a theta0 or beta in Params that an array
    function would not use is an error naming the field and the fix."""
    from model.contact.params import check_array_params

    base = Params(1.0, 1.0)
    check_array_params(base, "uniform_array", "self", uses_theta0=False)
    check_array_params(base.replace(theta0=2.0), "fixed_orientation", 0.5, uses_theta0=True)
    check_array_params(base.replace(beta=0.5), "fixed_orientation", 0.5, uses_theta0=True)
    with pytest.raises(ValueError, match=r"^theta0=2.0 is not used by uniform_array.*"
                                         r"params.replace\(theta0=math.pi / 2\)"):
        check_array_params(base.replace(theta0=2.0), "uniform_array", "self", uses_theta0=False)
    for beta in ("self", 0.7):
        with pytest.raises(ValueError, match=r"^beta=0.5 in params would be ignored by "
                                             r"orientation_sweep.*pass beta=0.5"):
            check_array_params(base.replace(beta=0.5), "orientation_sweep", beta,
                               uses_theta0=False)
