"""Shared fixtures."""
import pytest

from model.params import REGIMES


@pytest.fixture(params=list(REGIMES.values()), ids=list(REGIMES))
def regime_params(request):
    """The ``Params`` of each named regime (pendulum, slider, stiff, soft) in turn."""
    return request.param
