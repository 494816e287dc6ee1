"""Serving the replayed image (tests/test_docker_replay.py): its CMD on a free loopback port,
docker's SIGTERM stop, and its HEALTHCHECK command run as docker runs it."""
from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from browser.serving import _free_port
from dockerfile_replay import (IMAGE_PORT, Replay, _map_env, _only, dockerfile,
                               exec_form, image_env, parse_healthcheck, replace_option)


def _children(pid: int) -> set[int]:
    """Descendants of ``pid`` (from /proc)."""
    parents = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier}
        found |= frontier
    return found


def _alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


def _serve(replay: Replay, log_path: Path):
    """Start the image's CMD in its WORKDIR on a free loopback port: (process, port, argv)."""
    port = _free_port()
    argv = replace_option(replay.cmd, "--port", str(port))
    argv = replace_option(argv, "--address", "127.0.0.1")  # the test serves loopback only
    panel = shutil.which("panel", path=os.path.dirname(sys.executable))
    argv = ([panel] if panel else [sys.executable, "-m", "panel"]) + argv[1:]
    log = open(log_path, "w", encoding="utf-8")
    process = subprocess.Popen(argv, cwd=replay.workdir, env=replay.process_env(port),
                               stdout=log, stderr=subprocess.STDOUT)
    process.log = log
    return process, port, argv


def _stop(process) -> float:
    """SIGTERM (as ``docker stop`` sends) and wait; returns the seconds it took."""
    start = time.perf_counter()
    process.send_signal(signal.SIGTERM)
    try:
        process.wait(timeout=60)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait(timeout=15)
        raise
    finally:
        process.log.close()
    return time.perf_counter() - start


def _healthcheck_argv(replay: Replay, port: int) -> list[str]:
    argv = list(replay.healthcheck.argv)
    if argv[0] in ("python", "python3"):
        argv[0] = sys.executable
    old = f"127.0.0.1:{IMAGE_PORT}/"
    assert sum(a.count(old) for a in argv) == 1, argv
    return [a.replace(old, f"127.0.0.1:{port}/") for a in argv]


def _run_check(argv, env, timeout, cwd) -> int:
    """The health command's exit code, run in the image's working directory (-1: killed at
    docker's timeout)."""
    try:
        return subprocess.run(argv, env=env, capture_output=True, timeout=timeout,
                              cwd=cwd).returncode
    except subprocess.TimeoutExpired:
        return -1


def _log_tail(path: Path) -> str:
    return path.read_text(encoding="utf-8", errors="replace")[-3000:]


def _replay_without_build(root: Path) -> Replay:
    """The image's ENV, CMD and HEALTHCHECK, for serving an app folder made in ``root``."""
    instructions = dockerfile()
    env = {k: _map_env(v, root) for k, v in image_env(instructions).items()}
    return Replay(root=root, site=root, env=env, workdir=root,
                  cmd=exec_form(_only(instructions, "CMD").args, "CMD"),
                  healthcheck=parse_healthcheck(_only(instructions, "HEALTHCHECK")))
