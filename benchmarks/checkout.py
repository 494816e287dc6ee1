"""The checkout's test helpers that the browser and load benchmarks reuse.

The benchmarks import the installed package (``model``, ``app``: ``pip install -e .``).
Serving the dashboard on a free port, driving headless Chromium and reading the
Dockerfile's environment are done by helpers kept beside the tests
(``tests/browser/serving.py``, ``tests/browser/page_tools.py``,
``tests/dockerfile_replay.py``), which are not part of the package: ``helper`` loads one
of them from this checkout by its file, without putting the repository on ``sys.path``.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[1]


def helper(name: str) -> ModuleType:
    """The test helper ``tests/<name>.py`` of this checkout (e.g. ``"browser/serving"``)."""
    path = ROOT / "tests" / f"{name}.py"
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing: the browser and load benchmarks run from a "
                                "checkout of the repository, with its tests/ folder")
    module_name = "checkout_tests." + name.replace("/", ".")
    if module_name in sys.modules:
        return sys.modules[module_name]
    spec = importlib.util.spec_from_file_location(module_name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module  # dataclasses look their module up while defined
    spec.loader.exec_module(module)
    return module
