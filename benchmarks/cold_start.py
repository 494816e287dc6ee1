"""Cold start: seconds from launching ``panel serve app`` with an empty numba cache (as
after installing) to the first ``GET /app`` answered, median [min-max] over runs.

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


def first_page(port: int, timeout_s: float = 60.0) -> float:
    """Seconds from launch to the first page of a server with an empty numba cache."""
    env = dict(os.environ, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="numba-cold-"))
    start = time.perf_counter()
    server = subprocess.Popen(["panel", "serve", "app", "--port", str(port), "--address",
                               "127.0.0.1", f"--allow-websocket-origin=127.0.0.1:{port}"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        while time.perf_counter() - start < timeout_s:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/app", timeout=30) as r:
                    if r.status == 200:
                        return time.perf_counter() - start
            except OSError:
                time.sleep(0.05)
        return float("nan")
    finally:
        server.terminate()
        server.wait(15)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--port", type=int, default=5089)
    args = ap.parse_args()
    times = [first_page(args.port) for _ in range(args.runs)]
    print(f"first page after launch, empty numba cache: {np.median(times):.2f} "
          f"[{min(times):.2f}-{max(times):.2f}] s over {args.runs} runs "
          f"(load average {os.getloadavg()[0]:.2f})")


if __name__ == "__main__":
    main()
