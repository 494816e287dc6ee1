"""Reading the Dockerfile and .dockerignore, and replaying the image's build outside
Docker (see tests/test_docker.py): COPY through .dockerignore into a temporary root, the
project's install, the ``python -m model`` steps, with the image's paths mapped into it."""
from __future__ import annotations

import dataclasses
import fnmatch
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]  # the repository (importable as tests.* too)

DOCKERFILE = ROOT / "Dockerfile"
DOCKERIGNORE = ROOT / ".dockerignore"
IMAGE_PORT = 5006


# --------------------------------------------------------------------------- reading


@dataclasses.dataclass(frozen=True)
class Instruction:
    keyword: str  # upper case: FROM, ENV, RUN, ...
    args: str     # the rest of the instruction, continuation lines joined
    line: int     # where it starts in the Dockerfile


def parse_dockerfile(text: str) -> list[Instruction]:
    """Instructions in order; comments dropped, ``\\`` continuations joined."""
    instructions, parts, start = [], [], 0
    for number, raw in enumerate(text.splitlines(), 1):
        stripped = raw.strip()
        if stripped.startswith("#") or (not stripped and not parts):
            continue  # comments may also sit between continuation lines
        if not parts:
            start = number
        if stripped.endswith("\\"):
            parts.append(stripped[:-1].strip())
            continue
        parts.append(stripped)
        keyword, _, args = " ".join(p for p in parts if p).partition(" ")
        instructions.append(Instruction(keyword.upper(), args.strip(), start))
        parts = []
    assert not parts, "the Dockerfile ends inside a continued line"
    return instructions


def _only(instructions, keyword) -> Instruction:
    found = [i for i in instructions if i.keyword == keyword]
    assert len(found) == 1, f"expected one {keyword}, found {len(found)}"
    return found[0]


def env_of(instruction: Instruction) -> dict[str, str]:
    """``ENV KEY=value ...`` (the ``KEY value`` legacy form is refused)."""
    pairs = {}
    for word in shlex.split(instruction.args):
        key, sep, value = word.partition("=")
        assert sep, f"line {instruction.line}: write ENV as KEY=value, got {word!r}"
        pairs[key] = value
    return pairs


def exec_form(args: str, where: str) -> list[str]:
    """The JSON array of an exec-form CMD / HEALTHCHECK CMD."""
    try:
        argv = json.loads(args)
    except json.JSONDecodeError as error:
        raise AssertionError(f"{where} is not in exec form (a JSON array): {args!r}") from error
    assert isinstance(argv, list) and argv and all(isinstance(a, str) for a in argv), args
    return argv


@dataclasses.dataclass
class Healthcheck:
    options: dict[str, float]  # --interval, --timeout, --start-period, --retries in s / count
    argv: list[str]


def parse_healthcheck(instruction: Instruction) -> Healthcheck:
    match = re.fullmatch(r"(?P<opts>(?:--[\w-]+=\S+\s+)*)CMD\s+(?P<cmd>\[.*\])", instruction.args)
    assert match, f"HEALTHCHECK is not `[--option=value ...] CMD [exec form]`: {instruction.args!r}"
    options = {}
    for option in match["opts"].split():
        name, _, value = option[2:].partition("=")
        number = re.fullmatch(r"(\d+(?:\.\d+)?)(ms|s|m|h)?", value)
        assert number, f"HEALTHCHECK --{name}={value} is not a number or duration"
        scale = {None: 1, "ms": 1e-3, "s": 1, "m": 60, "h": 3600}[number[2]]
        options[name] = float(number[1]) * scale
    return Healthcheck(options, exec_form(match["cmd"], "HEALTHCHECK CMD"))


def run_segments(instruction: Instruction) -> list[list[str]]:
    """A shell-form RUN split on ``&&`` into argv lists (no other shell syntax is used)."""
    assert not re.search(r"[|;`$<>]|\|\|", instruction.args), (
        f"line {instruction.line}: RUN uses shell syntax the replay does not model")
    return [shlex.split(part) for part in instruction.args.split("&&")]


def option_value(argv: list[str], name: str) -> str | None:
    for i, arg in enumerate(argv):
        if arg == name and i + 1 < len(argv):
            return argv[i + 1]
        if arg.startswith(name + "="):
            return arg.split("=", 1)[1]
    return None


def replace_option(argv: list[str], name: str, value: str) -> list[str]:
    out, hits = list(argv), 0
    for i, arg in enumerate(out):
        if arg == name:
            out[i + 1], hits = value, hits + 1
        elif arg.startswith(name + "="):
            out[i], hits = f"{name}={value}", hits + 1
    assert hits == 1, f"{name} appears {hits} times in {argv}"
    return out


def dockerignore_patterns() -> list[str]:
    lines = [line.strip() for line in DOCKERIGNORE.read_text().splitlines()]
    patterns = [line for line in lines if line and not line.startswith("#")]
    for pattern in patterns:  # the subset of the syntax that ``ignored`` evaluates
        assert not pattern.startswith("!") and "**" not in pattern.removeprefix("**/"), pattern
    return patterns


def ignored(relative: str, patterns: list[str]) -> bool:
    """True when .dockerignore leaves ``relative`` (or a folder above it) out of the context."""
    parts = relative.split("/")
    for depth in range(1, len(parts) + 1):
        path, name = "/".join(parts[:depth]), parts[depth - 1]
        for pattern in patterns:
            if pattern.startswith("**/"):  # NAME at any depth
                if fnmatch.fnmatchcase(name, pattern[3:]):
                    return True
            else:  # anchored at the context's root; a wildcard stays within one folder
                anchored = pattern.strip("/")
                if path.count("/") == anchored.count("/") and fnmatch.fnmatchcase(path, anchored):
                    return True
    return False


def context_files(source: str, patterns: list[str]) -> list[Path]:
    """The files under ``source`` (relative to the repository) that the build context holds."""
    top = ROOT / source
    assert top.exists(), f"COPY source {source} does not exist"
    if top.is_file():
        return [] if ignored(source, patterns) else [top]
    files = []
    for folder, dirs, names in os.walk(top):
        rel = Path(folder).relative_to(ROOT).as_posix()
        dirs[:] = [d for d in dirs if not ignored(f"{rel}/{d}", patterns)]
        files += [Path(folder, n) for n in names if not ignored(f"{rel}/{n}", patterns)]
    return files


def dockerfile() -> list[Instruction]:
    return parse_dockerfile(DOCKERFILE.read_text())


def image_env(instructions: list[Instruction]) -> dict[str, str]:
    """Every ENV of the Dockerfile, in order."""
    env = {}
    for inst in instructions:
        if inst.keyword == "ENV":
            env.update(env_of(inst))
    return env


# --------------------------------------------------------------------------- replaying


def _pip_install_args(argv: list[str]) -> list[str] | None:
    """The arguments after ``pip install`` (or ``python -m pip install``), else None."""
    if argv[:2] == ["pip", "install"]:
        return argv[2:]
    if argv[:4] in (["python", "-m", "pip", "install"], ["python3", "-m", "pip", "install"]):
        return argv[4:]
    return None


def _is_warmup(argv: list[str]) -> bool:
    return argv[:1] in (["python"], ["python3"]) and argv[1:] == ["-m", "model", "warmup"]


def _is_model_command(argv: list[str]) -> bool:
    """``python -m model ...``: the package's own command line (warm-up, cache filling)."""
    return argv[:1] in (["python"], ["python3"]) and argv[1:3] == ["-m", "model"]


CONSTRAINTS = "constraints.txt"
PIP_ARGS = ["--no-cache-dir", "--constraint", CONSTRAINTS, "."]


def _check_pip_install(pip_args: list[str], line: int) -> None:
    assert pip_args == PIP_ARGS, (
        f"line {line}: the image installs the project from its own pyproject.toml at the "
        f"tested versions (`pip install {shlex.join(PIP_ARGS)}`), got "
        f"`pip install {shlex.join(pip_args)}`")


def constraint_pins(path: Path) -> dict[str, str]:
    """``name==version`` lines of a constraints file (every other form refused)."""
    pins = {}
    for number, raw in enumerate(path.read_text().splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        match = re.fullmatch(r"([A-Za-z0-9][A-Za-z0-9._-]*)==([A-Za-z0-9.+!_-]+)", line)
        assert match, f"{path.name}:{number}: {line!r} is not an exact `name==version` pin"
        pins[match[1].lower()] = match[2]
    return pins


def check_constraints(path: Path) -> dict[str, str]:
    """The pins of ``path``, asserting each is the version installed here: the image then
    gets the versions the tests ran against (the replay uses this environment's)."""
    from importlib.metadata import PackageNotFoundError, version

    pins, wrong = constraint_pins(path), []
    for name, pinned in pins.items():
        try:
            here = version(name)
        except PackageNotFoundError:
            here = "not installed"
        if here != pinned:
            wrong.append(f"{name}=={pinned} (here {here})")
    assert not wrong, (f"{path.name} pins versions the tests do not run against: "
                       f"{', '.join(wrong)}; run `python .ci/constraints.py`")
    return pins


@dataclasses.dataclass
class Replay:
    """The image, replayed into ``root``: its environment, working directory and commands."""
    root: Path
    site: Path              # stands for site-packages: where ``pip install .`` put the package
    env: dict[str, str]     # the image's ENV with its paths mapped into ``root``
    workdir: Path
    cmd: list[str]
    healthcheck: Healthcheck
    warmup_seconds: float = 0.0

    def process_env(self, port: int | None = None) -> dict[str, str]:
        env = {k: v for k, v in os.environ.items() if not k.startswith(("BOKEH_", "PANEL_"))}
        env.update(self.env, PYTHONPATH=str(self.site))
        if port is not None:
            env = {k: v.replace(f":{IMAGE_PORT}", f":{port}") for k, v in env.items()}
        return env


def _map_env(value: str, root: Path) -> str:
    return str(root / value.lstrip("/")) if value.startswith("/") else value


def replay_build(root: Path) -> Replay:
    """Replay the Dockerfile's build steps into ``root`` (see the module's docstring)."""
    instructions = dockerfile()
    patterns = dockerignore_patterns()
    site = root / "site-packages"
    env: dict[str, str] = {}  # the image's ENV so far, its paths mapped into ``root``
    workdir = "/"
    warmup_seconds = 0.0
    for inst in instructions:
        if inst.keyword == "ENV":
            env.update({k: _map_env(v, root) for k, v in env_of(inst).items()})
        elif inst.keyword == "WORKDIR":
            assert inst.args.startswith("/"), f"line {inst.line}: WORKDIR should be absolute"
            workdir = inst.args
            (root / workdir.lstrip("/")).mkdir(parents=True, exist_ok=True)
        elif inst.keyword == "COPY":
            *sources, dest = shlex.split(inst.args)
            assert not any(s.startswith("--") for s in sources), "COPY options are not replayed"
            target = Path(dest) if dest.startswith("/") else Path(workdir) / dest
            target = root / str(target).lstrip("/")
            for source in sources:
                base = ROOT / source
                for file in context_files(source, patterns):
                    if base.is_dir():  # a folder's contents go into the destination
                        out = target / file.relative_to(base)
                    elif len(sources) == 1 and not dest.endswith("/"):
                        out = target
                    else:
                        out = target / file.name
                    out.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(file, out)
        elif inst.keyword == "RUN":
            cwd = root / workdir.lstrip("/")
            for argv in run_segments(inst):
                pip_args = _pip_install_args(argv)
                if pip_args is not None:
                    _check_pip_install(pip_args, inst.line)
                    # The dependencies are this environment's own, at the versions the
                    # copied constraints pin (checked); the project itself is built from
                    # the copied files exactly as in the image, with those constraints.
                    check_constraints(cwd / CONSTRAINTS)
                    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet",
                                    "--no-cache-dir", "--no-deps", "--constraint",
                                    CONSTRAINTS, "--target", str(site), "."],
                                   cwd=cwd, check=True, timeout=600,
                                   env=dict(os.environ, PIP_ROOT_USER_ACTION="ignore"))
                elif _is_model_command(argv):
                    run_env = dict(os.environ, **env, PYTHONPATH=str(site))
                    start = time.perf_counter()
                    args = [_map_env(a, root) for a in argv[1:]]  # image paths into root
                    subprocess.run([sys.executable, *args], cwd=cwd, env=run_env, check=True,
                                   timeout=600, stdout=subprocess.DEVNULL)
                    warmup_seconds += time.perf_counter() - start
                elif argv[0] in ("mkdir", "rm"):
                    flags = [a for a in argv[1:] if a.startswith("-")]
                    paths = [root / a.lstrip("/") for a in argv[1:] if not a.startswith("-")]
                    for p in paths:
                        if argv[0] == "mkdir":
                            assert "-p" in flags, argv
                            p.mkdir(parents=True, exist_ok=True)
                        else:
                            shutil.rmtree(p, ignore_errors="-f" in flags or "-rf" in flags)
                elif argv[0] in ("groupadd", "useradd", "chown"):
                    pass  # users and ownership: checked by test_dockerfile_runs_as_its_own_user
                else:
                    raise AssertionError(f"line {inst.line}: the replay does not know `{argv[0]}`; "
                                         "teach replay_build what it does")
    return Replay(root=root, site=site, env=env, workdir=root / workdir.lstrip("/"),
                  cmd=exec_form(_only(instructions, "CMD").args, "CMD"),
                  healthcheck=parse_healthcheck(_only(instructions, "HEALTHCHECK")),
                  warmup_seconds=warmup_seconds)


def cache_snapshot(folder: Path) -> dict[str, int]:
    """Files under ``folder`` with their modification times (ns)."""
    return {p.relative_to(folder).as_posix(): p.stat().st_mtime_ns
            for p in folder.rglob("*") if p.is_file()}
