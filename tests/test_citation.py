"""Citable and installable: CITATION.cff, the version everywhere, the console script.

CITATION.cff is validated against the Citation File Format 1.2.0 JSON schema
(``tests/data/cff-1.2.0.schema.json``, the schema shipped in the ``cffconvert`` 2.0.0
wheel on PyPI; cffconvert itself pins jsonschema < 4, which would downgrade the
environment) with ``jsonschema``, plus checks the schema cannot make: one version
everywhere, the paper's title as in its text, a well-formed DOI.
"""
import json
import os
import re
import shutil
import subprocess
import tomllib
from importlib import metadata
from pathlib import Path

import jsonschema
import pytest
import yaml

import model
from app.about import PAPER_DOI, citation_text, version_text
from model.cli import main

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = Path(__file__).parent / "data" / "cff-1.2.0.schema.json"
PAPER_TEXT = ROOT.parent / "shared" / "paper"


class _CffLoader(yaml.SafeLoader):
    """YAML without implicit timestamps: the schema wants dates as strings (its note to
    tool implementers says to cast them)."""


_CffLoader.yaml_implicit_resolvers = {
    key: [(tag, rx) for tag, rx in resolvers if tag != "tag:yaml.org,2002:timestamp"]
    for key, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}


def load_cff(path=ROOT / "CITATION.cff") -> dict:
    return yaml.load(path.read_text(encoding="utf-8"), Loader=_CffLoader)


def validator():
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema, format_checker=cls.FORMAT_CHECKER)


def test_citation_cff_validates_against_the_schema():
    errors = sorted(validator().iter_errors(load_cff()), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors)


@pytest.mark.parametrize("break_it", [
    lambda c: c.pop("authors"),
    lambda c: c.update({"cff-version": "9.9"}),
    lambda c: c["references"][0].update({"doi": "not a doi"}),
    lambda c: c["references"][0].update({"date-published": "14 April 2021"}),
    lambda c: c.update({"unknown-key": 1}),
])
def test_the_schema_check_catches_a_broken_file(break_it):
    cff = load_cff()
    break_it(cff)
    assert list(validator().iter_errors(cff))


def test_one_version_everywhere():
    cff = load_cff()
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert cff["version"] == pyproject["project"]["version"] == model.__version__
    assert version_text() == f"micropillar-friction {model.__version__}"
    assert cff["title"].startswith(pyproject["project"]["name"])


def test_the_paper_it_implements():
    paper = load_cff()["references"][0]
    assert paper["type"] == "article" and paper["journal"] == "Scientific Reports"
    assert (paper["volume"], paper["start"], paper["year"]) == (11, 8093, 2021)
    assert paper["doi"] == PAPER_DOI and re.fullmatch(r"10\.1038/s41598-021-\d{5}-\d", PAPER_DOI)
    assert PAPER_DOI in citation_text() and version_text() in citation_text()
    texts = sorted(PAPER_TEXT.glob("*.txt")) if PAPER_TEXT.is_dir() else []
    if texts:  # the paper's text, where it is beside the project
        first_line = texts[0].read_text(encoding="utf-8").strip().splitlines()[0].strip()
        assert paper["title"] == first_line
        assert "Published online: 14 April 2021" in texts[0].read_text(encoding="utf-8")


# --------------------------------------------------------------------------- console script

def test_the_console_script_is_declared_and_resolves(capsys):
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    target = pyproject["project"]["scripts"]["micropillar"]
    entry = metadata.EntryPoint("micropillar", target, "console_scripts")
    assert entry.load() is main
    assert entry.load()(["support", "--regime", "stiff", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["success"] is True


def test_the_installed_console_script_runs():
    """After ``pip install -e .`` (CI) the ``micropillar`` command exists and runs."""
    installed = [e for e in metadata.entry_points(group="console_scripts")
                 if e.name == "micropillar"]
    script = shutil.which("micropillar")
    # The README's test command (pip install -e ".[test]") installs it.
    assert installed and script is not None, \
        "the micropillar console script is not installed (pip install -e . installs it)"
    assert installed[0].value == "model.cli:main"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([script, "support", "--regime", "pendulum", "--json"],
                          capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["params"]["k_r"] == 3.0
    bad = subprocess.run([script, "support", "--k-r", "-1", "--k-theta", "1"],
                         capture_output=True, text=True, env=env, timeout=300)
    assert bad.returncode == 2 and "--k-r" in bad.stderr
    # Errors name the command as it was typed.
    assert bad.stderr.startswith("micropillar support: error:"), bad.stderr
