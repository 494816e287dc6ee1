"""The Dockerfile's build and start, replayed outside Docker (its static checks:
tests/test_docker.py).

These machines have no Docker engine, so the image is never built here. The tests read the
Dockerfile instead and replay it with the same files, commands and environment: the COPY
steps (through .dockerignore) into a temporary root, the project's install (without its
dependencies, which this environment already has), the build-time warm-up, then the CMD,
probed with the HEALTHCHECK command itself. Paths of the image are mapped into the
temporary root and the port 5006 to a free one; nothing else is changed.
"""
from __future__ import annotations

import asyncio
import re
import shlex
import shutil
import subprocess
import sys
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

from browser.serving import ROOT, _status

from docker_serving import (
    _alive, _children, _healthcheck_argv, _log_tail, _replay_without_build, _run_check,
    _serve, _stop)
from dockerfile_replay import Replay, replay_build, cache_snapshot


@pytest.fixture(scope="module")
def image(tmp_path_factory) -> Replay:
    return replay_build(tmp_path_factory.mktemp("image"))


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
    code = ("import sys; from model import REGIMES; from model.runs.sweeps import regime_map\n"
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
