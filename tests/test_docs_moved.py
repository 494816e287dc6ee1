"""Nothing of the old README was lost when it became a short README and a documentation site.

The README of commit 0e92e10 (934 lines: a user manual, the measurements and the layout)
was split into docs/*.md. ``tests/data/readme_before_docs.json`` holds what a user could
look up in it, per section: every shell command (the fenced ``bash`` lines and the inline
commands), every URL, every number and every table row, extracted by this file::

    git show 0e92e10:README.md | python tests/test_docs_moved.py > facts.json
    mv facts.json tests/data/readme_before_docs.json

Each must still be found, word for word (line breaks and runs of spaces aside), in
README.md or a page of docs/.
"""
import json
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FACTS = ROOT / "tests" / "data" / "readme_before_docs.json"
#: Inline code that is a command a user types.
COMMAND_START = ("python ", "pip ", "panel serve", "docker ", "micropillar ", "jupyter ")
URL = re.compile(r"https?://[^\s)`'\"|>]+")
#: A number as written: 0.9987, 1e-5, 2026-11-24, 24 x 24 is two.
NUMBER = re.compile(r"(?<![\w.])\d+(?:[.:-]\d+)*(?:e-?\d+)?(?![\w])")


def _flat(text: str) -> str:
    return " ".join(text.split())


def extract(readme: str) -> dict[str, dict[str, list[str]]]:
    """The commands, URLs, numbers and table rows of each ``##`` section of ``readme``."""
    sections: dict[str, list[str]] = {}
    name = "(top)"
    fence = None
    for line in readme.splitlines():
        if line.startswith("```"):
            fence = None if fence is not None else line[3:].strip()
        elif fence is None and line.startswith("## "):
            name = line[3:].strip()
        sections.setdefault(name, []).append(line)
    facts = {}
    for name, lines in sections.items():
        text = "\n".join(lines)
        commands, fence = [], None
        for line in text.replace("\\\n", " ").splitlines():
            if line.startswith("```"):
                fence = None if fence is not None else line[3:].strip()
            elif fence == "bash" and line.strip():
                commands.append(_flat(line.split(" #", 1)[0]))
        prose = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
        commands += [_flat(code) for code in re.findall(r"`([^`]+)`", prose)
                     if _flat(code).startswith(COMMAND_START)]
        urls = [u.rstrip(".,;:") for u in URL.findall(text)]
        rows = [_flat(line) for line in lines  # (a row of pictures is checked by the build)
                if line.startswith("|") and "---" not in line and "![" not in line]
        facts[name] = {"commands": sorted(set(commands)), "urls": sorted(set(urls)),
                       "numbers": sorted(set(NUMBER.findall(text))), "table_rows": rows}
    return facts


@pytest.fixture(scope="module")
def documentation() -> str:
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    text = "\n".join(p.read_text(encoding="utf-8") for p in pages)
    return _flat(text.replace("\\\n", " "))  # a shell line continued with \ read as one


def _cases():
    facts = json.loads(FACTS.read_text(encoding="utf-8"))
    return [pytest.param(section, kind, items, id=f"{section}: {kind}")
            for section, kinds in facts.items() for kind, items in kinds.items() if items]


def test_the_extract_holds_the_old_readme():
    facts = json.loads(FACTS.read_text(encoding="utf-8"))
    assert {"Performance", "Deploying with Docker", "Command line", "The dashboard",
            "Reproducing the paper", "Solvers"} <= set(facts)
    assert sum(len(f["commands"]) for f in facts.values()) >= 40
    assert sum(len(f["numbers"]) for f in facts.values()) >= 500


@pytest.mark.parametrize("section, kind, items", _cases())
def test_each_fact_of_the_old_readme_is_still_documented(section, kind, items, documentation):
    if kind == "numbers":
        present = set(NUMBER.findall(documentation))
        missing = [n for n in items if n not in present]
    else:
        missing = [item for item in items if item not in documentation]
    assert not missing, f"old README, {section!r}: {kind} no longer in README.md or docs/: {missing}"


if __name__ == "__main__":
    json.dump(extract(sys.stdin.read()), sys.stdout, indent=1, ensure_ascii=False)
    sys.stdout.write("\n")
