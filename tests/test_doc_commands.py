"""Every command of the README and docs/*.md that runs the project (``python -m model``,
``python -m app...``, ``micropillar``) is run here as written, from a scratch directory,
and must exit 0. Only servers are left out (``SKIP``): they do not end."""
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
#: Commands of the project, at the start of a shell line.
PROJECT = re.compile(r"^(python -m (model|app)\b|micropillar(\s|$))")
#: Never run: servers that do not end, and containers (no Docker engine in tests).
SKIP = ("panel serve", "docker")
#: Commands that take more than ~30 s (full sweeps, every figure, a stiff real pillar):
#: run in CI, marked slow.
SLOW = ("python -m model sweep", "python -m model reproduce", "python -m app.reproduce",
        "python -m model pillar", "python -m model design")


def _shell_blocks(text: str):
    """The bodies of the fenced blocks tagged bash, sh, shell or console (read in order,
    so a closing fence is never taken for an opening one)."""
    body, language = None, None
    for line in text.splitlines():
        if line.startswith("```"):
            if body is None:
                body, language = [], line[3:].strip()
            else:
                if language in ("bash", "sh", "shell", "console"):
                    yield "\n".join(body)
                body = None
        elif body is not None:
            body.append(line)


def commands() -> list[tuple[str, str]]:
    """(file, command) of every project command in a fenced shell block."""
    found = []
    for path in DOCS:
        for block in _shell_blocks(path.read_text(encoding="utf-8")):
            for line in block.replace("\\\n", " ").splitlines():
                command = line.split(" #", 1)[0].strip().removeprefix("$ ")
                if PROJECT.match(command) and not any(s in command for s in SKIP):
                    found.append((path.relative_to(ROOT).as_posix(), command))
    return found


def _params():
    """One case per distinct command (the README repeats a few of the docs' commands)."""
    first = {}
    for name, command in commands():
        first.setdefault(command, name)
    return [pytest.param(command, id=f"{name}: {command[:60]}",
                         marks=[pytest.mark.slow] if command.startswith(SLOW) else [])
            for command, name in first.items()]


def test_the_docs_hold_the_commands_this_test_runs():
    found = [c for _, c in commands()]
    assert any(c.startswith("python -m model pillar") and "--evaluate" in c for c in found)
    assert len(found) >= 15


@pytest.mark.parametrize("command", _params())
def test_each_documented_command_runs(command, tmp_path):
    argv = shlex.split(command)
    if argv[0] == "python":
        argv[0] = sys.executable
    else:  # an installed script
        found = shutil.which(argv[0])
        assert found, f"{argv[0]} is not installed (the README's install puts it on PATH)"
        argv[0] = found
    out = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, timeout=1800)
    assert out.returncode == 0, f"{command}\nexit {out.returncode}\n{out.stderr[-2000:]}"
