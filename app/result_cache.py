"""Finished results shared by every session of the server process: a bounded LRU."""
from __future__ import annotations

import pickle
import threading
from collections import OrderedDict

#: Finished results shared by all sessions of the server process: at most this many ...
CACHE_SIZE = 2048
#: ... and this many bytes (as pickled: a single support with its 400-sample trajectory
#: is ~35 kB, a polar sweep ~20 kB), so what a class leaves behind stays small.
CACHE_BYTES = 32 * 2**20
#: ... cut down to this many bytes, the most recently used, once no session is open any
#: more (``app.pages.release_memory``): what the next class may reuse, while the server
#: goes back near its size at the start.
IDLE_CACHE_BYTES = 4 * 2**20


def _nbytes(value) -> int:
    """The size of a result as the workers send it (pickled)."""
    try:
        return len(pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL))
    except Exception:  # not picklable here: count it as one small entry
        return 1024


class ResultCache:
    """A bounded LRU of finished results (``maxsize`` entries, ``max_bytes`` pickled
    bytes), shared by all sessions of the server process."""

    def __init__(self, maxsize: int = CACHE_SIZE, max_bytes: int = CACHE_BYTES):
        self._data: OrderedDict = OrderedDict()
        self._sizes: dict = {}
        self._lock = threading.Lock()
        self.maxsize, self.max_bytes = maxsize, max_bytes
        self.nbytes = 0

    def get(self, key):
        with self._lock:
            if key in self._data:
                self._data.move_to_end(key)
                return self._data[key]
        return None

    def put(self, key, value) -> None:
        size = _nbytes(value)
        if size > self.max_bytes:
            return
        with self._lock:
            self.nbytes += size - self._sizes.get(key, 0)
            self._data[key], self._sizes[key] = value, size
            self._data.move_to_end(key)
            while len(self._data) > self.maxsize or self.nbytes > self.max_bytes:
                old, _ = self._data.popitem(last=False)
                self.nbytes -= self._sizes.pop(old)

    def shrink(self, max_bytes: int = IDLE_CACHE_BYTES) -> None:
        """Drop the least recently used results until at most ``max_bytes`` remain."""
        with self._lock:
            while self._data and self.nbytes > max_bytes:
                old, _ = self._data.popitem(last=False)
                self.nbytes -= self._sizes.pop(old)

    def clear(self) -> None:
        with self._lock:
            self._data.clear()
            self._sizes.clear()
            self.nbytes = 0

    def __len__(self) -> int:
        return len(self._data)
