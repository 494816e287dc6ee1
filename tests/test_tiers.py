"""The quick tier's list of slow tests (``tests/tiers.py``) names tests that exist, and
marks them: the quick tier leaves them out, CI (no ``-m``) runs them."""
import ast
import subprocess
import sys
from pathlib import Path

from tiers import LIST, node_id, read, slow

ROOT = Path(__file__).resolve().parents[1]


def _functions(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    return {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}


def test_every_listed_test_exists():
    listed = read(LIST)
    assert len(listed) >= 50
    for entry in listed:
        file, name = entry.split("::", 1)
        path = ROOT / file
        assert path.is_file(), f"{entry}: no {file} (refresh the list: tests/tiers.py)"
        assert name.split("[", 1)[0] in _functions(path), (
            f"{entry}: no such test in {file} (refresh the list: tests/tiers.py)")


def test_junit_names_map_to_node_ids_and_the_threshold_picks_slow_ones():
    assert node_id("tests.test_support", "test_x[a.b-1]@test_support") == \
        "tests/test_support.py::test_x[a.b-1]"
    times = {"tests/test_a.py::t1": 2.5, "tests/test_a.py::t2": 0.1,
             "tests/browser/test_b.py::t3": 30.0}
    assert list(slow(times)) == ["tests/test_a.py::t1"]


def test_the_quick_tier_leaves_the_listed_tests_out():
    entry = sorted(read(LIST))[0]
    file = entry.split("::", 1)[0]
    quick = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-n0", "--collect-only", "-q",
         "-m", "not slow and not browser", file], cwd=ROOT, capture_output=True, text=True,
        timeout=300)
    every = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-n0", "--collect-only", "-q",
         file], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert entry in every.stdout, every.stdout[-2000:]
    assert entry not in quick.stdout, quick.stdout[-2000:]
