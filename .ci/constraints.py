"""The tested stack: ``python .ci/constraints.py`` (``--check``, ``--resolve 3.12 3.13``).

``constraints.txt`` pins every package that the README's two commands and the image
install (the project's dependencies in pyproject.toml, its ``test`` extra, and theirs, for
Linux) to the exact version installed in this environment, the one the test suite runs
against. Every install reads it: ``pip install -c constraints.txt -e ".[test]"`` (the
README, CI), ``pip install --constraint constraints.txt .`` (the Dockerfile). The serving
stack (``BOUNDED``: panel, bokeh, param, tornado) is also bounded in pyproject.toml, from the
tested release up to the next minor one, so an install that does not read the constraints
(``pip install .`` elsewhere, on any Python) never gets an untested Panel or Bokeh.

After changing the environment on purpose (an upgrade, a new dependency), run
``python .ci/constraints.py`` in it: it rewrites constraints.txt and those bounds together;
commit both. ``--check`` says whether both agree with this environment (tests/test_docker.py
runs it). ``--resolve 3.12 3.13`` asks pip's resolver (a dry run, no install) what the
project's declared dependencies give on those Pythons with the constraints applied, and
fails where that differs from the pins: the interpreters this machine cannot run still get
the tested set.
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
import tempfile
import tomllib
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[1]
CONSTRAINTS = ROOT / "constraints.txt"
PYPROJECT = ROOT / "pyproject.toml"
COMMAND = "python .ci/constraints.py"
EXTRAS = ("test",)
BOUNDED = ("panel", "bokeh", "param", "tornado")


def project_requirements() -> list[str]:
    project = tomllib.loads(PYPROJECT.read_text())["project"]
    extras = project.get("optional-dependencies", {})
    return list(project["dependencies"]) + [r for extra in EXTRAS for r in extras[extra]]


def pins() -> dict[str, str]:
    """Canonical name -> installed version, for the dependency closure of the project."""
    found: dict[str, str] = {}
    found_extras: dict[str, frozenset[str]] = {}
    todo: list[tuple[Requirement, frozenset[str]]] = [
        (Requirement(r), frozenset({""})) for r in project_requirements()]
    while todo:
        req, extras = todo.pop()
        if req.marker is not None and not any(req.marker.evaluate({"extra": e}) for e in extras):
            continue  # another platform's or an unused extra's dependency
        name = canonicalize_name(req.name)
        try:
            dist = distribution(req.name)
        except PackageNotFoundError:
            raise SystemExit(f"{req.name} (needed by the project) is not installed here; "
                             f"install the project first: pip install -c constraints.txt "
                             f"-e \".[test]\"") from None
        wanted = frozenset({""} | set(req.extras))
        if name in found and wanted <= found_extras[name]:
            continue
        found[name] = dist.version
        found_extras[name] = found_extras.get(name, frozenset()) | wanted
        todo += [(Requirement(r), wanted) for r in dist.requires or []]
    return dict(sorted(found.items()))


def render_constraints(pinned: dict[str, str]) -> str:
    lines = ["# Exact versions of every package the README's commands and the image install:",
             "# the ones the tests ran against. Regenerate with "
             f"`{COMMAND}` after changing the environment.",
             *(f"{name}=={version}" for name, version in pinned.items())]
    return "\n".join(lines) + "\n"


def bound(version: str) -> str:
    """``>=tested,<next minor``: the range a bounded package may take."""
    v = Version(version)
    return f">={v.base_version},<{v.major}.{v.minor + 1}"


def render_pyproject(pinned: dict[str, str]) -> str:
    """pyproject.toml with each ``BOUNDED`` dependency's range set from its pin."""
    text = PYPROJECT.read_text()
    for name in BOUNDED:
        pattern = re.compile(rf'^(\s*)"{name}[<>=!~][^"]*"', re.M)
        if not pattern.search(text):
            raise SystemExit(f"pyproject.toml declares no \"{name}...\" dependency to bound")
        text = pattern.sub(lambda m, n=name: f'{m[1]}"{n}{bound(pinned[n])}"', text, count=1)
    return text


def resolve(python_version: str) -> dict[str, str]:
    """What pip's resolver installs for the project on ``python_version`` (Linux, wheels
    only, constraints applied), as canonical name -> version; a dry run, nothing installed."""
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "report.json"
        cmd = [sys.executable, "-m", "pip", "install", "--dry-run", "--ignore-installed",
               "--quiet", "--python-version", python_version, "--only-binary=:all:",
               "--target", str(Path(tmp) / "target"), "--report", str(report),
               "--constraint", str(CONSTRAINTS), *project_requirements()]
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        if run.returncode != 0:
            raise SystemExit(f"Python {python_version}: pip could not resolve the project "
                             f"with {CONSTRAINTS.name}:\n{run.stderr[-2000:]}")
        installed = json.loads(report.read_text())["install"]
    return {canonicalize_name(i["metadata"]["name"]): i["metadata"]["version"] for i in installed}


def resolution_differences(python_version: str, pinned: dict[str, str]) -> list[str]:
    """Packages that ``python_version`` would get at a version other than the pinned one."""
    return [f"{name} {version} (pinned {pinned[name]})"
            for name, version in sorted(resolve(python_version).items())
            if name in pinned and version != pinned[name]]


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if args[:1] == ["--resolve"] and len(args) > 1:
        pinned, failed = current_pins(), False
        for python_version in args[1:]:
            diff = resolution_differences(python_version, pinned)
            print(f"Python {python_version}: " + ("the pinned set" if not diff else
                  "differs from the pins: " + ", ".join(diff)))
            failed |= bool(diff)
        return 1 if failed else 0
    pinned = pins()
    texts = {CONSTRAINTS: render_constraints(pinned), PYPROJECT: render_pyproject(pinned)}
    if args == ["--check"]:
        stale = [p.name for p, text in texts.items() if p.read_text() != text]
        if stale:
            print(f"{' and '.join(stale)} differ from this environment; run `{COMMAND}`",
                  file=sys.stderr)
            return 1
        return 0
    if args:
        print(__doc__.split("\n")[0], file=sys.stderr)
        return 2
    for path, text in texts.items():
        path.write_text(text)
    print(f"{CONSTRAINTS.name}: {len(pinned)} pins; pyproject.toml: "
          + ", ".join(f"{n}{bound(pinned[n])}" for n in BOUNDED))
    return 0


def current_pins() -> dict[str, str]:
    """The pins of constraints.txt as written."""
    return {canonicalize_name(m[1]): m[2] for m in
            re.finditer(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==(\S+)$", CONSTRAINTS.read_text(), re.M)}


if __name__ == "__main__":
    sys.exit(main())
