"""The image's constraints file: ``python .ci/constraints.py`` (``--check`` to verify).

``constraints.txt`` pins every package the image installs (the project's dependencies in
pyproject.toml and theirs, for Linux) to the exact version installed in this environment,
the one the test suite runs against; the Dockerfile installs with
``pip install --constraint constraints.txt .``. After changing the environment (an
upgrade, a new dependency), rerun this command in it and commit the file: the tests
(tests/test_docker.py) fail while the file and the environment disagree.
"""
from __future__ import annotations

import sys
import tomllib
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]
CONSTRAINTS = ROOT / "constraints.txt"
COMMAND = "python .ci/constraints.py"


def project_requirements() -> list[str]:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]


def pins() -> dict[str, str]:
    """Canonical name -> installed version, for the dependency closure of the project."""
    found, todo = {}, [Requirement(r) for r in project_requirements()]
    while todo:
        req = todo.pop()
        if req.marker is not None and not req.marker.evaluate({"extra": ""}):
            continue  # another platform's or an extra's dependency
        name = canonicalize_name(req.name)
        if name in found:
            continue
        try:
            dist = distribution(req.name)
        except PackageNotFoundError:
            raise SystemExit(f"{req.name} (needed by the project) is not installed here; "
                             "install the project first: pip install -e \".[test]\"") from None
        found[name] = dist.version
        todo += [Requirement(r) for r in dist.requires or []]
    return dict(sorted(found.items()))


def render() -> str:
    lines = [f"# Exact versions of every package the image installs: the ones the tests ran",
             f"# against. Regenerate with `{COMMAND}` after changing the environment.",
             *(f"{name}=={version}" for name, version in pins().items())]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    text = render()
    if args == ["--check"]:
        current = CONSTRAINTS.read_text() if CONSTRAINTS.exists() else ""
        if current != text:
            print(f"{CONSTRAINTS.name} differs from this environment; run `{COMMAND}`",
                  file=sys.stderr)
            return 1
        return 0
    if args:
        print(__doc__.split("\n")[0], file=sys.stderr)
        return 2
    CONSTRAINTS.write_text(text)
    print(f"{CONSTRAINTS.name}: {text.count('==')} pins")
    return 0


if __name__ == "__main__":
    sys.exit(main())
