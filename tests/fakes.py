"""Stand-ins for the server's work pool (``app.jobs.WorkPool``) in tests without workers."""
from __future__ import annotations

import concurrent.futures as cf


class InProcessPool:
    """Runs every job here and now, so patches of ``app.worker`` take effect; records the
    names of the functions it ran."""

    def __init__(self):
        self.calls = []

    def session_id(self):
        return 0

    def submit(self, lane, key, fn, *args, **options):
        self.calls.append(fn.__name__)
        future = cf.Future()
        try:
            future.set_result(fn(*args))
        except Exception as exc:
            future.set_exception(exc)
        return future
