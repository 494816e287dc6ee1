"""The quick tier's list of slow tests (``tests/slow_tests.txt``), written from measured
durations.

The suite's quick tier for local work is ``python -m pytest -m "not slow and not browser"``.
A test is ``slow`` when it says so (``@pytest.mark.slow``) or when it is listed in
``tests/slow_tests.txt``: the tests (browser tests aside: they have their own mark) that
took ``THRESHOLD_S`` or more in a measured run. ``tests/conftest.py`` marks them. CI runs
every tier (the README's command selects nothing).

Refresh the list on purpose, like ``constraints.txt``, from a run of the non-browser tests::

    python -m pytest -m "not browser" --junitxml=durations.xml
    python tests/tiers.py durations.xml

(``tests/test_tiers.py`` checks that every listed test still exists.)
"""
from __future__ import annotations

import argparse
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

#: A test that takes this long or longer (setup, call and teardown) is slow.
THRESHOLD_S = 2.0
LIST = Path(__file__).with_name("slow_tests.txt")
HEADER = ("# Tests marked slow for the quick tier (tests/tiers.py: measured >= {:g} s).\n"
          "# Written by `python tests/tiers.py durations.xml`; do not edit by hand.\n")


def node_id(classname: str, name: str) -> str:
    """pytest's node id of a JUnit test case (``tests.test_x`` + ``test_y[a]@group``)."""
    return f"{classname.replace('.', '/')}.py::{name.rsplit('@', 1)[0]}"


def read(path: Path) -> set[str]:
    """The node ids listed in ``path`` (comments and blank lines skipped)."""
    if not path.exists():
        return set()
    lines = (line.split("#", 1)[0].strip() for line in path.read_text().splitlines())
    return {line for line in lines if line}


def durations(junit: Path) -> dict[str, float]:
    """node id -> seconds, from a JUnit XML report (``pytest --junitxml``)."""
    out = {}
    for case in ET.parse(junit).getroot().iter("testcase"):
        out[node_id(case.get("classname", ""), case.get("name", ""))] = float(case.get("time", 0))
    return out


def slow(times: dict[str, float], threshold: float = THRESHOLD_S) -> dict[str, float]:
    return {k: v for k, v in sorted(times.items()) if v >= threshold
            and not k.startswith("tests/browser/")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("junit", type=Path, nargs="+", help="JUnit XML report(s) of a run")
    ap.add_argument("--threshold", type=float, default=THRESHOLD_S,
                    help=f"seconds from which a test is slow ({THRESHOLD_S:g})")
    args = ap.parse_args(argv)
    times: dict[str, float] = {}
    for path in args.junit:
        for key, value in durations(path).items():
            times[key] = max(value, times.get(key, 0.0))
    listed = slow(times, args.threshold)
    LIST.write_text(HEADER.format(args.threshold)
                    + "".join(f"{k}  # {v:.1f} s\n" for k, v in listed.items()))
    print(f"{len(listed)} of {len(times)} tests listed as slow in {LIST}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
