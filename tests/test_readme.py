"""The README's first commands are the ones CI runs."""
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SERVE_COMMAND = "pip install -c constraints.txt . && panel serve app"
TEST_COMMAND = 'pip install -c constraints.txt -e ".[test]" && python -m pytest'


def _first_code_block(text: str) -> list[str]:
    match = re.search(r"^```[^\n]*\n(.*?)^```", text, flags=re.S | re.M)
    assert match, "README.md has no fenced code block"
    return [line for line in match.group(1).splitlines() if line.strip()]


def _command(line: str) -> str:
    """A shell line without its trailing comment."""
    return line.split(" #", 1)[0].strip()


@pytest.fixture(scope="module")
def readme() -> str:
    return (ROOT / "README.md").read_text(encoding="utf-8")


def test_first_block_opens_the_readme(readme):
    lines = readme.splitlines()
    assert lines[0].startswith("# ")
    first_content = next(line for line in lines[1:] if line.strip())
    assert first_content.startswith("```"), "the commands must come right after the title"


def test_first_block_holds_the_two_commands(readme):
    commands = [_command(line) for line in _first_code_block(readme)]
    assert commands == [SERVE_COMMAND, TEST_COMMAND]


def test_ci_runs_the_readme_test_command(readme):
    test_line = _first_code_block(readme)[1]
    command = _command(test_line)
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    ci_commands = [line.strip() for line in ci.splitlines()
                   if line.strip() and not line.lstrip().startswith("#")]
    assert command in ci_commands
    assert "set -euo pipefail" in ci_commands


def test_ci_script_is_executable():
    assert os.access(ROOT / ".ci" / "run", os.X_OK)
