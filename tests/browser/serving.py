"""Serving the dashboard and launching Debian's headless Chromium for the browser tests."""
from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

CHROMIUM = "/usr/bin/chromium"
# Debian's Chromium on a machine with a closed network, run as root, without a GPU.
CHROMIUM_FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-sync",
    "--disable-dev-shm-usage",
]
VIEWPORT = {"width": 1280, "height": 720}
ROOT = Path(__file__).resolve().parents[2]


class ServerError(RuntimeError):
    """``panel serve`` did not come up healthy."""


def _stop_with_parent() -> None:
    """Run in the server's process before it starts (Linux): it gets SIGTERM when the
    process that started it dies, so an interrupted test run (an xdist worker stopped
    mid-test) leaves no server behind. Elsewhere a no-op."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes
    import signal

    pr_set_pdeathsig = 1
    try:
        ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, int(signal.SIGTERM))
    except (OSError, AttributeError):
        pass


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def _status(url: str) -> int | None:
    try:
        with urllib.request.urlopen(url, timeout=10) as response:
            return response.status
    except urllib.error.HTTPError as error:
        return error.code
    except (urllib.error.URLError, OSError):
        return None


@contextlib.contextmanager
def serve_app(log_path: Path, app_dir: str = "app", timeout_s: float = 60.0, warmup: bool = True,
              extra_args: tuple[str, ...] = (), env: dict | None = None):
    """Run ``panel serve <app_dir>`` from the repository root on a free loopback port.

    Compiles the model's kernel first (``python -m model warmup``), waits until
    ``/liveness?endpoint=/<app>`` answers 200 (the server ran the app's page script), yields
    the base URL (``http://127.0.0.1:<port>``) and stops the server on exit. The server's
    output goes to ``log_path``. Raises ``ServerError`` (with the log's tail) otherwise.
    ``extra_args`` are appended to the ``panel serve`` command line; ``env`` is added to
    the server's environment.
    """
    if warmup:
        subprocess.run([sys.executable, "-m", "model", "warmup"], cwd=ROOT, check=True,
                       timeout=600, stdout=subprocess.DEVNULL)
    port = _free_port()
    base = f"http://127.0.0.1:{port}"
    panel = shutil.which("panel", path=os.path.dirname(sys.executable))
    command = ([panel] if panel else [sys.executable, "-m", "panel"]) + [
        "serve", app_dir, "--port", str(port), "--address", "127.0.0.1",
        f"--allow-websocket-origin=127.0.0.1:{port}", "--liveness", *extra_args]
    log = open(log_path, "w", encoding="utf-8")
    env = dict(os.environ, PYTHONUNBUFFERED="1", **(env or {}))
    process = subprocess.Popen(command, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT, env=env,
                               preexec_fn=_stop_with_parent)
    try:
        deadline = time.monotonic() + timeout_s
        status = None
        while time.monotonic() < deadline and process.poll() is None:
            status = _status(f"{base}/liveness?endpoint=/{Path(app_dir).name}")
            if status in (200, 500):  # 500: the app raised while building its page
                break
            time.sleep(0.5)
        if status != 200:
            log.flush()
            tail = Path(log_path).read_text(encoding="utf-8", errors="replace")[-3000:]
            raise ServerError(f"`{' '.join(command)}` was not healthy within {timeout_s:.0f} s "
                              f"(exit code {process.poll()}, last /liveness status {status}); "
                              f"its log:\n{tail}")
        yield base
    finally:
        process.terminate()
        try:
            process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout=15)
        log.close()


def launch_chromium(playwright):
    """Debian's Chromium, headless, launched by Playwright (``sync_playwright()``)."""
    return playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS,
                                      headless=True)
