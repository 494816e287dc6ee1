"""Shared fixtures."""
import pytest

from model.params import REGIMES


@pytest.fixture(params=list(REGIMES.values()), ids=list(REGIMES))
def regime_params(request):
    """The ``Params`` of each named regime (pendulum, slider, stiff, soft) in turn."""
    return request.param


@pytest.fixture(scope="session")
def reference():
    """scipy DOP853 solution at rtol 1e-12 (cached for the session): reference(params)."""
    from functools import lru_cache

    from model import simulate_support

    @lru_cache(maxsize=None)
    def solve(params, rtol=1e-12):
        res = simulate_support(params, rtol=rtol, atol=rtol / 100, method="reference",
                               max_steps=5_000_000)
        assert res.success, res.message
        return res

    return solve
