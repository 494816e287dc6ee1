"""The declared, tested stack: constraints.txt pins what the README's commands install, and
pyproject.toml bounds the serving stack to the tested minor releases (``.ci/constraints.py``,
run here as the command it is)."""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tomllib
from importlib.metadata import version
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.version import Version

ROOT = Path(__file__).resolve().parent.parent
SERVING_STACK = ("panel", "bokeh", "param", "tornado")


def declared(pyproject: Path = ROOT / "pyproject.toml") -> dict[str, Requirement]:
    deps = tomllib.loads(pyproject.read_text())["project"]["dependencies"]
    return {Requirement(d).name: Requirement(d) for d in deps}


def pinned() -> dict[str, str]:
    return dict(re.findall(r"^([A-Za-z0-9._-]+)==(\S+)$",
                           (ROOT / "constraints.txt").read_text(), re.M))


def constraints_command(*args, root: Path = ROOT, timeout=120):
    return subprocess.run([sys.executable, str(root / ".ci" / "constraints.py"), *args],
                          cwd=root, capture_output=True, text=True, timeout=timeout)


def test_serving_stack_is_bounded_to_the_tested_minor_release():
    reqs = declared()
    for name in SERVING_STACK:
        tested = Version(version(name))
        spec = reqs[name].specifier
        assert tested in spec, f"{name} {tested} (installed, tested) is outside {name}{spec}"
        next_minor = Version(f"{tested.major}.{tested.minor + 1}")
        assert next_minor not in spec, f"{name}{spec} admits the untested {next_minor}"


def test_the_readme_commands_read_the_constraints():
    first_block = (ROOT / "README.md").read_text().split("```")[1]
    commands = [line.split(" #")[0] for line in first_block.splitlines()[1:] if line.strip()]
    assert len(commands) == 2 and all("-c constraints.txt" in c for c in commands)


def test_every_pin_is_in_the_declared_range():
    pins = pinned()
    outside = [f"{name}=={pins[name]} vs {req}" for name, req in declared().items()
               if name in pins and Version(pins[name]) not in req.specifier]
    assert not outside


def test_the_check_fails_on_a_loosened_bound_and_the_command_restores_it(tmp_path):
    """A copy of the project's stack files with ``panel>=1.9.2`` (no upper bound): the
    check fails naming pyproject.toml, and the command writes the tested bound back."""
    (tmp_path / ".ci").mkdir()
    shutil.copy(ROOT / ".ci" / "constraints.py", tmp_path / ".ci")
    shutil.copy(ROOT / "constraints.txt", tmp_path)
    text = (ROOT / "pyproject.toml").read_text()
    loosened = re.sub(r'"panel>=[^"]*"', '"panel>=1.9.2"', text)
    assert loosened != text
    (tmp_path / "pyproject.toml").write_text(loosened)
    check = constraints_command("--check", root=tmp_path)
    assert check.returncode == 1 and "pyproject.toml" in check.stderr
    assert constraints_command(root=tmp_path).returncode == 0
    assert (tmp_path / "pyproject.toml").read_text() == text


@pytest.mark.slow
def test_python_3_13_resolves_to_the_pinned_set():
    """pip's resolver (dry run, Linux wheels) gives Python 3.13 the pinned versions: this
    machine cannot run 3.13, so its resolution is the evidence that such a user gets the
    tested stack (needs the package index, as the install itself does)."""
    done = constraints_command("--resolve", "3.13", timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Python 3.13: the pinned set" in done.stdout
