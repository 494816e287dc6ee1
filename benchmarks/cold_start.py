"""Cold start: seconds from launching ``panel serve app`` with an empty numba cache (as
after installing) to the first ``GET /app`` answered, median [min-max] over runs; then
the time of the Docker health check's first step, ``GET /liveness?endpoint=/app`` (right
after the first page, while the solver may still compile, and five more times).

    python benchmarks/cold_start.py [--runs 3] [--port 5089]

The solver compiles in the background meanwhile (the page says so); before, the server
compiled first and answered after ~16 s.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import tempfile
import time
import urllib.request

import numpy as np


def _timed_get(url: str) -> float:
    start = time.perf_counter()
    with urllib.request.urlopen(url, timeout=60) as r:
        r.read()
        assert r.status == 200, (url, r.status)
    return time.perf_counter() - start


def first_page(port: int, timeout_s: float = 60.0) -> tuple[float, list]:
    """Seconds from launch to the first page of a server with an empty numba cache, and
    the seconds of six liveness probes after it."""
    env = dict(os.environ, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="numba-cold-"))
    start = time.perf_counter()
    server = subprocess.Popen(["panel", "serve", "app", "--port", str(port), "--address",
                               "127.0.0.1", f"--allow-websocket-origin=127.0.0.1:{port}",
                               "--liveness"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{port}"
    try:
        page = float("nan")
        while time.perf_counter() - start < timeout_s:
            try:
                with urllib.request.urlopen(f"{base}/app", timeout=30) as r:
                    if r.status == 200:
                        page = time.perf_counter() - start
                        break
            except OSError:
                time.sleep(0.05)
        probes = [_timed_get(f"{base}/liveness?endpoint=/app") for _ in range(6)]
        return page, probes
    finally:
        server.terminate()
        server.wait(15)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--port", type=int, default=5089)
    args = ap.parse_args()
    runs = [first_page(args.port) for _ in range(args.runs)]
    times = [page for page, _ in runs]
    first = [probes[0] for _, probes in runs]
    later = [p for _, probes in runs for p in probes[1:]]
    print(f"first page after launch, empty numba cache: {np.median(times):.2f} "
          f"[{min(times):.2f}-{max(times):.2f}] s over {args.runs} runs "
          f"(load average {os.getloadavg()[0]:.2f})")
    print(f"/liveness?endpoint=/app right after it: {np.median(first) * 1e3:.0f} "
          f"[{min(first) * 1e3:.0f}-{max(first) * 1e3:.0f}] ms; five more each run: "
          f"{np.median(later) * 1e3:.0f} [{min(later) * 1e3:.0f}-{max(later) * 1e3:.0f}] ms")


if __name__ == "__main__":
    main()
