"""The declared, tested stack: constraints.txt pins what the README's commands install, and
pyproject.toml bounds the serving stack to the tested minor releases (.ci/constraints.py)."""
from __future__ import annotations

import importlib.util
import tomllib
from importlib.metadata import version
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.version import Version

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def stack():
    spec = importlib.util.spec_from_file_location("ci_constraints", ROOT / ".ci" / "constraints.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def declared() -> dict[str, Requirement]:
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    return {Requirement(d).name: Requirement(d) for d in deps}


def test_serving_stack_is_bounded_to_the_tested_minor_release(stack):
    reqs = declared()
    for name in stack.BOUNDED:
        tested = Version(version(name))
        spec = reqs[name].specifier
        assert tested in spec, f"{name} {tested} (installed, tested) is outside {name}{spec}"
        next_minor = Version(f"{tested.major}.{tested.minor + 1}")
        assert next_minor not in spec, f"{name}{spec} admits the untested {next_minor}"


def test_the_readme_commands_read_the_constraints():
    readme = (ROOT / "README.md").read_text()
    first_block = readme.split("```")[1]
    commands = [line.split(" #")[0] for line in first_block.splitlines()[1:] if line.strip()]
    assert len(commands) == 2 and all("-c constraints.txt" in c for c in commands)


def test_the_check_fails_on_a_loosened_bound_and_the_command_restores_it(stack, tmp_path,
                                                                         monkeypatch):
    loose = tmp_path / "pyproject.toml"
    text = (ROOT / "pyproject.toml").read_text()
    pin = version("panel")
    loosened = text.replace(f'"panel{stack.bound(pin)}"', '"panel>=1.9.2"')
    assert loosened != text
    loose.write_text(loosened)
    monkeypatch.setattr(stack, "PYPROJECT", loose)
    assert stack.main(["--check"]) == 1
    assert stack.render_pyproject(stack.pins()) == text


def test_every_pin_is_in_the_declared_range(stack):
    reqs = declared()
    pinned = stack.current_pins()
    outside = [f"{name}=={pinned[name]} vs {req}" for name, req in reqs.items()
               if name in pinned and Version(pinned[name]) not in req.specifier]
    assert not outside


@pytest.mark.slow
def test_python_3_13_resolves_to_the_pinned_set(stack):
    """pip's resolver (dry run, wheels for Linux) gives Python 3.13 the pinned versions:
    this machine cannot run 3.13, so its resolution is the evidence that it gets the tested
    stack (needs the package index, as the install itself does)."""
    assert stack.resolution_differences("3.13", stack.current_pins()) == []
