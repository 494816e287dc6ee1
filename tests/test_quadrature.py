"""Adaptive Gauss-Kronrod quadrature."""
import math

import numpy as np
import pytest

from model.arrays.quadrature import NODES, W_G, W_K, integrate


@pytest.mark.parametrize("k", range(24))
def test_rules_are_exact_to_their_degree(k):
    exact = (1 - (-1) ** (k + 1)) / (k + 1)
    assert W_K @ NODES**k == pytest.approx(exact, abs=1e-14)  # Kronrod-15: degree 22 (+ odd)
    if k <= 13:
        assert W_G @ NODES**k == pytest.approx(exact, abs=1e-14)  # Gauss-7: degree 13


def test_smooth_integrand_converges_without_refinement():
    res = integrate(lambda x: np.c_[np.sin(x), np.cos(x) ** 2], 0.0, math.pi, 1e-10)
    np.testing.assert_allclose(res.integral, [2.0, math.pi / 2], atol=1e-12)
    assert res.converged and res.edges.size == 5


@pytest.mark.parametrize("jump", [0.3, 1.3, 2.9])
def test_error_estimate_brackets_the_true_error_at_a_jump(jump):
    f = lambda x: np.c_[np.where(x < jump, 1.0, 0.0)]  # noqa: E731
    for tol in (1e-2, 1e-4, 1e-6):
        res = integrate(f, 0.0, math.pi, tol)
        true = abs(res.integral[0] - jump)
        assert res.converged and res.error[0] <= tol
        assert true <= res.error[0]


def test_only_controlled_components_drive_refinement():
    f = lambda x: np.c_[np.sin(x), np.where(x < 1.0, 1.0, 0.0)]  # noqa: E731
    free = integrate(f, 0.0, math.pi, 1e-8, control=[0])
    both = integrate(f, 0.0, math.pi, 1e-8)
    assert free.edges.size < both.edges.size


def test_interval_budget_stops_refinement():
    res = integrate(lambda x: np.c_[np.where(x < 1.0, 1.0, 0.0)], 0.0, math.pi, 1e-14,
                    max_intervals=16)
    assert not res.converged and res.edges.size - 1 <= 16
