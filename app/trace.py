"""Timestamps along one update, for ``benchmarks/bench_dashboard.py``: with the environment
variable ``MICROPILLAR_TRACE`` naming a file, ``mark(stage, **info)`` appends one JSON line
``{"t": wall-clock seconds, "stage": ..., **info}`` to it; without it, nothing (one check).

Stages: ``server receives`` (Panel starts on a browser event) and ``answer sent`` (what
answers it has left), ``job submitted`` (a result asked of the work pool), ``worker
starts`` / ``worker ends`` (handed to a worker process / its result back), ``result
applied`` / ``result sent`` (the views updated / their message left); and for a page being
opened (``app.opening``): ``page build starts`` (the browser said it is ready), ``page
objects built``, ``page models start`` (the next turn of the loop), ``page sent``.
"""
from __future__ import annotations

import json
import os
import threading
import time

_PATH = os.environ.get("MICROPILLAR_TRACE") or None
_LOCK = threading.Lock()


def mark(stage: str, **info) -> None:
    if _PATH is None:
        return
    line = json.dumps({"t": time.time(), "stage": stage, **info}, default=str)
    with _LOCK, open(_PATH, "a", encoding="utf-8") as out:
        out.write(line + "\n")
