"""The documentation builds, its API reference's examples run, and the README's links and
Python hold.

* ``python -m sphinx -W --keep-going -b html docs OUT``: the site builds with warnings as
  errors (a broken link between pages, an image that is missing, a docstring that is not
  valid reStructuredText all fail it);
* the API reference documents the whole public API (``model.__all__``), and every public
  function carries examples, which run as doctests (``-b doctest``, on the pages as built,
  so what a reader sees is what runs);
* the README's links into the repository resolve (file and heading) and its Python runs.
"""
import inspect
import re
import subprocess
import sys
from pathlib import Path

import pytest

import model

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
TIMEOUT = 300


def _sphinx(builder: str, out: Path, doctrees: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q",
                           "-b", builder, "-d", str(doctrees), "docs", str(out)],
                          cwd=ROOT, capture_output=True, text=True, timeout=TIMEOUT)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The site built as HTML once; the doctest build reuses its doctrees."""
    base = tmp_path_factory.mktemp("docs")
    out = _sphinx("html", base / "html", base / "doctrees")
    assert out.returncode == 0, f"the docs do not build cleanly:\n{out.stderr[-4000:]}"
    return base


@pytest.mark.slow  # the module's site build (~15 s, built once)
def test_the_site_builds_with_warnings_as_errors(built):
    html = built / "html"
    pages = {p.stem for p in html.glob("*.html")}
    assert {"index", "dashboard", "classroom", "teaching", "design", "cli", "python",
            "deploying", "model", "solvers", "architecture", "performance", "api"} <= pages
    index = (html / "index.html").read_text(encoding="utf-8")
    for page in ("dashboard", "model", "performance", "api"):  # in the navigation
        assert f'href="{page}.html"' in index


@pytest.mark.slow  # the module's site build (~15 s, built once)
def test_the_api_reference_documents_the_public_api(built):
    generated = built / "html" / "generated"
    missing = [name for name in model.__all__ if not (generated / f"model.{name}.html").exists()]
    assert not missing, f"public names without an API page (add them to docs/api.rst): {missing}"


def test_every_public_function_has_examples():
    functions = [name for name in model.__all__ if inspect.isfunction(getattr(model, name))]
    assert len(functions) >= 10
    without = [name for name in functions if ">>>" not in (getattr(model, name).__doc__ or "")]
    assert not without, f"public functions whose docstring has no example: {without}"


@pytest.mark.slow  # the module's site build (~15 s, built once)
def test_the_api_reference_examples_run(built):
    out = _sphinx("doctest", built / "doctest", built / "doctrees")
    report = (built / "doctest" / "output.txt").read_text(encoding="utf-8")
    assert out.returncode == 0, f"an example of the API reference fails:\n{report[-4000:]}"
    ran = sum(int(n) for n in re.findall(r"^\s*(\d+) tests$", report, flags=re.M))
    assert ran >= 30, report[-2000:]
    assert re.search(r"^\s*0 failures in tests$", report, flags=re.M), report[-2000:]


def _slug(heading: str) -> str:
    """The anchor GitHub and MyST give a heading: lower case, punctuation dropped."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def _links(text: str):
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if not re.match(r"[a-z]+:", target):  # not http:, mailto: ...
            yield target


@pytest.mark.parametrize("target", sorted(set(_links(README))))
def test_each_readme_link_resolves(target):
    path, _, anchor = target.partition("#")
    file = ROOT / path
    assert file.exists(), f"README links to {path}, which does not exist"
    if anchor:
        headings = re.findall(r"^#+ (.+)$", file.read_text(encoding="utf-8"), flags=re.M)
        assert anchor in {_slug(h) for h in headings}, f"{path} has no heading #{anchor}"


def test_the_readme_python_runs(tmp_path):
    blocks = re.findall(r"^```python\n(.*?)^```", README, flags=re.S | re.M)
    assert blocks, "the README's quick start has no Python"
    for code in blocks:
        out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                             text=True, timeout=TIMEOUT)
        assert out.returncode == 0, f"{code}\n{out.stderr[-2000:]}"
