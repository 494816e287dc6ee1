"""Shared fixtures, and how the suite is spread over the machine's cores.

The README's test command runs the suite on every core (pytest-xdist, ``-n auto`` in
pyproject.toml). Tests travel to a core by module, so a module's fixtures are built once;
the browser tests travel together (``tests/browser``): they share one served dashboard and
one Chromium, which would otherwise start again on each core and each time a core came back
to them.
"""
from pathlib import Path

import pytest
# --cpu-report: each test's CPU, its processes' included (tests/cpu_report.py).
from cpu_report import (pytest_addoption, pytest_configure,  # noqa: F401
                        pytest_runtest_protocol, pytest_sessionfinish,
                        pytest_terminal_summary)

from model.contact.params import REGIMES


@pytest.fixture(params=list(REGIMES.values()), ids=list(REGIMES))
def regime_params(request):
    """The ``Params`` of each named regime (pendulum, slider, stiff, soft) in turn."""
    return request.param


@pytest.fixture(scope="session")
def reference():
    """scipy's solution at rtol 1e-12 (cached for the session): reference(params), DOP853;
    reference(params, method="reference-radau") for stiff contacts (large loads)."""
    from functools import lru_cache

    from model import simulate_support

    @lru_cache(maxsize=None)
    def solve(params, rtol=1e-12, method="reference"):
        res = simulate_support(params, rtol=rtol, atol=rtol / 100, method=method,
                               max_steps=5_000_000)
        assert res.success, res.message
        return res

    return solve


@pytest.fixture(autouse=True, scope="session")
def _private_disk_cache(tmp_path_factory):
    """Keep the suite's disk cache out of the user's cache directory."""
    import os

    old = os.environ.get("MICROPILLAR_CACHE_DIR")
    os.environ["MICROPILLAR_CACHE_DIR"] = str(tmp_path_factory.mktemp("disk-cache"))
    yield
    if old is None:
        os.environ.pop("MICROPILLAR_CACHE_DIR", None)
    else:
        os.environ["MICROPILLAR_CACHE_DIR"] = old


@pytest.fixture
def pool(monkeypatch):
    """Every dashboard computation run here and now (``fakes.InProcessPool``), recorded."""
    from app import results as results_module
    from app import slot, speed_results
    from fakes import InProcessPool

    pool = InProcessPool()
    for module in (slot, results_module, speed_results):
        monkeypatch.setattr(module, "work_pool", lambda: pool)
    return pool


BROWSER_DIR = Path(__file__).parent / "browser"
#: The browser tests' modules in this many groups, taken in turn: each group runs on one
#: xdist worker with its own served dashboard and Chromium (the package's fixtures), so the
#: two cores share the browser tests instead of one worker carrying them all.
BROWSER_GROUPS = 2


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Group each test with its module, the browser tests' modules in ``BROWSER_GROUPS``
    groups (``--dist loadgroup``);
    mark ``slow`` the tests listed in ``tests/slow_tests.txt`` (``tests/tiers.py``), before
    ``-m`` selects."""
    from tiers import LIST, read

    slow = read(LIST)
    browser_modules = sorted({Path(str(item.fspath)).stem for item in items
                              if BROWSER_DIR in Path(str(item.fspath)).parents})
    for item in items:
        path = Path(str(item.fspath))
        group = (f"browser-{browser_modules.index(path.stem) % BROWSER_GROUPS}"
                 if BROWSER_DIR in path.parents else path.stem)
        item.add_marker(pytest.mark.xdist_group(group))
        if item.nodeid.split("@", 1)[0] in slow:
            item.add_marker(pytest.mark.slow)
