"""The friction law of Eq. (4) and its smooth form mu(s)/s used in the force."""
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from model.contact.friction import SERIES_BELOW, mu, mu0, mu_over_s, series_coefficients
from model.contact.params import DEFAULTS, Params

ZETA = DEFAULTS["zeta"]
S_SERIES = SERIES_BELOW / ZETA  # below this speed mu_over_s uses the Taylor series


def mu_scalar(v, mu_s=1.3, A=1.44, B=-20.0, zeta=10.0):
    """Eq. (4) written out with the math module."""
    z = zeta * v
    return mu_s * math.sin(A * math.atan(z - B * (z - math.atan(z))))


def test_mu_vanishes_at_rest():
    assert mu(0.0) == 0.0
    assert mu_over_s(0.0) == pytest.approx(1.3 * 1.44 * 10.0, rel=1e-15)


def test_mu0_is_mu_at_slab_speed():
    assert mu0() == pytest.approx(mu_scalar(1.0), rel=1e-15)
    assert abs(mu0() - 1.0082) < 1e-4


@settings(max_examples=50, deadline=None)
@given(st.floats(0.0, 10.0))
def test_mu_matches_eq4(v):
    assert float(mu(v)) == pytest.approx(mu_scalar(v), rel=1e-13, abs=1e-300)


def test_mu_uses_params():
    p = Params(1.0, 1.0, mu_s=0.5, A=2.0, B=3.0, zeta=4.0)
    v = np.array([0.01, 0.3, 2.0])
    expected = [mu_scalar(x, 0.5, 2.0, 3.0, 4.0) for x in v]
    np.testing.assert_allclose(mu(v, p), expected, rtol=1e-13)
    assert mu0(p) == pytest.approx(mu_scalar(1.0, 0.5, 2.0, 3.0, 4.0), rel=1e-15)


def test_mu_over_s_is_closed_form_away_from_zero():
    s = np.geomspace(1e-3, 1e-1, 201)
    np.testing.assert_allclose(mu_over_s(s), mu(s) / s, rtol=1e-12, atol=0)


def test_series_matches_closed_form_below_threshold():
    s = np.geomspace(1e-2 * S_SERIES, S_SERIES, 101)[:-1]
    np.testing.assert_allclose(mu_over_s(s), mu(s) / s, rtol=1e-12, atol=0)


def test_continuous_across_series_threshold():
    below, above = mu_over_s(np.array([S_SERIES * (1 - 1e-9), S_SERIES * (1 + 1e-9)]))
    assert below == pytest.approx(above, rel=1e-12)


def test_finite_and_smooth_through_zero():
    s = np.linspace(0.0, 5 * S_SERIES, 2001)
    f = mu_over_s(s)
    assert np.all(np.isfinite(f))
    # f = f0 (1 + c z^2 + ...): second differences are uniform, no kink at the threshold.
    second = np.diff(f, 2)
    assert np.ptp(second) < 1e-3 * np.max(np.abs(second)) + 1e-14 * f[0]


def test_shapes_are_kept():
    assert np.shape(mu_over_s(0.5)) == ()
    assert mu_over_s(np.zeros((3, 4))).shape == (3, 4)
    assert mu(np.ones(5)).shape == (5,)


# --- the Taylor coefficients, against exact rational power-series arithmetic -----------

ORDER = 8


def _mul(a, b):
    out = [Fraction(0)] * (ORDER + 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b[: ORDER + 1 - i]):
                out[i + j] += x * y
    return out


def _compose(coeffs, u):
    """sum_k coeffs[k] u^k for a series u without constant term, to ORDER."""
    out, power = [Fraction(0)] * (ORDER + 1), [Fraction(1)] + [Fraction(0)] * ORDER
    for c in coeffs:
        out = [o + c * p for o, p in zip(out, power)]
        power = _mul(power, u)
    return out


def _exact_coefficients(A: Fraction, B: Fraction):
    """Coefficients of sin(A atan(z - B (z - atan z))) / z, orders 0, 2, 4, 6."""
    atan = [Fraction((-1) ** (k // 2), k) if k % 2 else Fraction(0) for k in range(ORDER + 1)]
    z = [Fraction(0), Fraction(1)] + [Fraction(0)] * (ORDER - 1)
    w = [zk - B * (zk - tk) for zk, tk in zip(z, atan)]
    sin_a = [A**k * Fraction((-1) ** (k // 2), math.factorial(k)) if k % 2 else Fraction(0)
             for k in range(ORDER + 1)]
    series = _compose(sin_a, _compose(atan, w))
    return [series[k + 1] for k in (0, 2, 4, 6)]


@pytest.mark.parametrize("A, B", [("1.44", "-20"), ("1", "0"), ("2", "5"), ("0.5", "-3"),
                                  ("3.7", "-250"), ("0.01", "1000")])
def test_series_coefficients_are_exact(A, B):
    exact = _exact_coefficients(Fraction(A), Fraction(B))
    got = series_coefficients(float(A), float(B))
    for k, (g, e) in enumerate(zip(got, exact)):
        assert g == pytest.approx(float(e), rel=1e-13, abs=1e-300), f"c{2 * k}"


def test_series_coefficients_predict_the_function():
    """The truncated series is the function to O(z^8) at a few small z (float check)."""
    A, B = 1.44, -20.0
    c = series_coefficients(A, B)
    for z in (1e-3, 3e-3, 1e-2):
        series = sum(ck * z ** (2 * k) for k, ck in enumerate(c))
        closed = math.sin(A * math.atan(z - B * (z - math.atan(z)))) / z
        assert series == pytest.approx(closed, rel=1e-13 + 1e3 * z**8)
