"""On-disk cache for expensive results (sweeps, uniform arrays).

Each entry is one ``.npz`` file holding named numpy arrays, the canonical JSON of its
key, free-form metadata, the package version and a sha256 checksum. The file name is
the sha256 of the canonical JSON (``sort_keys``) of the key and the package version,
so a changed parameter, solver setting or version is a different entry.

Location: ``directory`` if given, else the environment variable
``MICROPILLAR_CACHE_DIR``, else the user cache directory
(``platformdirs.user_cache_dir("micropillar-friction")``); entries live in a
subfolder per package version (``v0.1.0``).

Guarantees:

* an entry is written to a temporary file in the same folder and moved into place
  with ``os.replace`` (atomic), so a reader sees a complete file or none, and two
  processes writing the same key leave one valid file;
* on read the stored key, version and checksum are verified; a corrupted,
  truncated, unreadable or stale file is logged, deleted where possible and treated
  as a miss, so it is recomputed and never returned;
* a cache folder is not trusted to hold what this module wrote: only a regular file is
  read (a named pipe, a folder or a symbolic link at an entry's path is a miss, never a
  blocked read), at most ``max_entry_bytes`` of it, and its arrays are unpacked only
  when their declared sizes add up to at most ``max_entry_bytes`` (a few hundred kB of
  compressed zeros cannot become hundreds of MB in memory);
* an ``OSError`` on write (read-only folder, full disk) turns writing to that folder
  off for the rest of the process, with one logged warning instead of raising (a sweep
  makes a ``DiskCache`` per point: still one warning); a folder that cannot exist (its
  parent is a file) is a miss on read; something other than a file in the way of one
  entry (a folder at its path) skips that entry only;
* the folder is bounded (``max_entries``, ``max_bytes``): the least recently used
  entries (oldest mtime; a hit refreshes it) are evicted. Each process counts its own
  writes on top of what its last scan of the folder found, and scans (one ``stat`` per
  entry) only when that count passes a bound; the scan then evicts down to
  ``LOW_WATER`` of the bounds, so at most one write in ``(1 - LOW_WATER) * max_entries``
  pays for a scan. With P processes writing one folder it may pass its bounds by the
  other processes' unscanned writes, at most ``(P - 1) (1 - LOW_WATER)`` of them.

    >>> cache = DiskCache()
    >>> arrays = cache.get_or_compute(make_key("uniform_array", params=p, tol=1e-3),
    ...                               lambda: {"F": np.array([1.0])})
"""
from __future__ import annotations

import json
import logging
import math
import os
import re
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

from .cache_entry import MAX_ENTRY_BYTES, CorruptEntry, checksum, read_regular, unpack
from .cache_keys import APP_NAME, canonical_json, key_digest, make_key, package_version

__all__ = ["DiskCache", "make_key", "key_digest", "canonical_json", "default_directory"]

log = logging.getLogger(__name__)

ENV_VAR = "MICROPILLAR_CACHE_DIR"
_RESERVED = ("__key__", "__meta__", "__version__", "__checksum__")
_SUFFIX, _TMP_SUFFIX = ".npz", ".tmp"
_TMP_MAX_AGE = 3600.0  # seconds before an orphaned temporary file is removed
_ENTRY = re.compile(r"[0-9a-f]{64}\.npz")
_TMP = re.compile(r"[0-9a-f]{16}\..*\.tmp")
_VERSION_DIR = re.compile(r"v\d[\w.+-]*")
#: Folders found not writable in this process: no ``DiskCache`` writes there again.
_UNWRITABLE: set[Path] = set()
#: After a scan, eviction leaves this fraction of ``max_entries`` and ``max_bytes``.
LOW_WATER = 0.9



def default_directory() -> Path:
    """Root of the cache: ``$MICROPILLAR_CACHE_DIR`` or the user cache directory."""
    env = os.environ.get(ENV_VAR)
    if env:
        return Path(env).expanduser()
    import platformdirs

    return Path(platformdirs.user_cache_dir(APP_NAME))


class _InTheWay(OSError):
    """Something other than a regular file sits at an entry's path (a folder)."""


class _Usage:
    """One folder's entries as this process knows them: the count and bytes found by the
    last scan plus this process's writes since (``None`` before the first scan)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.count: int | None = None
        self.bytes = 0


_USAGE: dict[Path, _Usage] = {}
_USAGE_LOCK = threading.Lock()


def _usage(folder: Path) -> _Usage:
    with _USAGE_LOCK:
        return _USAGE.setdefault(folder, _Usage())


class DiskCache:
    """Cache of dicts of numpy arrays keyed by JSON-serialisable dicts (see module doc)."""

    def __init__(self, directory=None, max_entries: int = 10_000,
                 max_bytes: int | None = 2 * 1024**3, version: str | None = None,
                 max_entry_bytes: int = MAX_ENTRY_BYTES):
        self.version = version or package_version()
        self.root = Path(directory).expanduser() if directory is not None else default_directory()
        self.path = self.root / f"v{self.version}"
        self.max_entries = int(max_entries)
        self.max_bytes = None if max_bytes is None else int(max_bytes)
        self.max_entry_bytes = int(max_entry_bytes)
        self.writable = self.path not in _UNWRITABLE  # off after an OSError on write

    def __repr__(self):
        return f"DiskCache({str(self.path)!r}, writable={self.writable})"

    def file_for(self, key: dict) -> Path:
        """The file that holds (or would hold) the entry of ``key``."""
        return self.path / (key_digest(key, self.version) + _SUFFIX)

    # ------------------------------------------------------------------ reading
    def get(self, key: dict) -> dict | None:
        """The arrays stored under ``key``, or None on a miss or an invalid file."""
        entry = self.load(key)
        return None if entry is None else entry[0]

    def load(self, key: dict) -> tuple[dict, dict] | None:
        """``(arrays, meta)`` stored under ``key``, or None (see ``get``)."""
        path = self.file_for(key)
        try:
            entry = self._read(path, canonical_json(key))
        except (FileNotFoundError, NotADirectoryError):  # no entry, or no folder for it
            return None
        except Exception as exc:  # anything unreadable is discarded, never returned
            log.warning("cache file %s is invalid (%s); discarding it and recomputing", path, exc)
            self._remove(path)
            return None
        self._touch(path)
        return entry

    def _read(self, path: Path, key_json: str) -> tuple[dict, dict]:
        contents = unpack(read_regular(path, self.max_entry_bytes), self.max_entry_bytes)
        missing = [name for name in _RESERVED if name not in contents]
        if missing:
            raise CorruptEntry(f"missing {', '.join(missing)}")
        stored = {name: str(contents[name][()]) for name in _RESERVED}
        arrays = {name: a for name, a in contents.items() if name not in _RESERVED}
        if stored["__version__"] != self.version:
            raise CorruptEntry(f"stale: written by version {stored['__version__']}, "
                               f"this is {self.version}")
        if stored["__key__"] != key_json:
            raise CorruptEntry("stale: the stored key differs from the requested key")
        check = checksum(arrays, stored["__key__"], stored["__meta__"], stored["__version__"])
        if check != stored["__checksum__"]:
            raise CorruptEntry("checksum mismatch")
        return arrays, json.loads(stored["__meta__"])

    # ------------------------------------------------------------------ writing
    def put(self, key: dict, arrays: dict, meta: dict | None = None) -> bool:
        """Store ``arrays`` (name -> array) under ``key``; True if written to disk.

        Bad input (a reserved or non-string name, an object array, a key or meta that
        is not JSON-serialisable) raises; a failing disk only logs one warning.
        """
        payload = self._payload(key, arrays, meta or {})
        if not self.writable:
            return False
        if sum(a.nbytes for a in payload.values()) > self.max_entry_bytes:
            log.warning("result of %d bytes not cached: more than max_entry_bytes = %d",
                        sum(a.nbytes for a in payload.values()), self.max_entry_bytes)
            return False
        try:
            self.path.mkdir(parents=True, exist_ok=True)
            size = self._write_atomic(self.file_for(key), payload)
        except _InTheWay as exc:  # this entry only: the folder itself is fine
            log.warning("cache entry %s not written: %s", self.file_for(key), exc)
            return False
        except OSError as exc:
            self.writable = False
            if self.path not in _UNWRITABLE:
                _UNWRITABLE.add(self.path)
                log.warning("disk cache %s is not writable (%s); continuing without a disk "
                            "cache", self.path, exc)
            return False
        usage = _usage(self.path)
        with usage.lock:
            if usage.count is not None:
                usage.count += 1  # or a replaced entry: counted anyway, a scan comes sooner
                usage.bytes += size
            if usage.count is None or self._over(usage.count, usage.bytes, 1.0):
                usage.count, usage.bytes = self._evict()
        return True

    def _over(self, count: int, size: int, fraction: float) -> bool:
        """True when ``count`` entries of ``size`` bytes pass ``fraction`` of the bounds
        (of ``max_entries`` at least one entry, when it allows one)."""
        entries = max(math.floor(fraction * self.max_entries), min(1, self.max_entries))
        return (count > entries or
                (self.max_bytes is not None and size > fraction * self.max_bytes))

    def _payload(self, key, arrays, meta) -> dict:
        arrays = {name: np.asarray(a) for name, a in arrays.items()}
        for name, a in arrays.items():
            if not isinstance(name, str) or not name or name in _RESERVED:
                raise ValueError(f"array name {name!r} is empty, not a string or reserved")
            if a.dtype.hasobject:
                raise TypeError(f"array {name!r} has dtype object; only plain numpy dtypes are cached")
        key_json, meta_json = canonical_json(key), canonical_json(meta)
        check = checksum(arrays, key_json, meta_json, self.version)
        return {**arrays, "__key__": np.array(key_json), "__meta__": np.array(meta_json),
                "__version__": np.array(self.version), "__checksum__": np.array(check)}

    def _write_atomic(self, path: Path, payload: dict) -> int:
        """Write ``payload`` to ``path`` through a temporary file; the bytes written."""
        fd, tmp = tempfile.mkstemp(prefix=path.stem[:16] + ".", suffix=_TMP_SUFFIX, dir=self.path)
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, allow_pickle=False, **payload)
                f.flush()
                os.fsync(f.fileno())
                size = f.tell()
            try:
                os.replace(tmp, path)
            except OSError as exc:
                if os.path.lexists(path) and not path.is_file():
                    raise _InTheWay(exc.errno, f"{exc.strerror}: something other than a file "
                                    "is at its path") from exc
                raise
        except BaseException:
            self._remove(Path(tmp))
            raise
        return size

    def get_or_compute(self, key: dict, compute):
        """The cached arrays of ``key``, else ``compute()`` stored and returned.

        ``compute()`` returns a dict of arrays, or ``(arrays, meta)``.
        """
        arrays = self.get(key)
        if arrays is not None:
            return arrays
        result = compute()
        arrays, meta = result if isinstance(result, tuple) else (result, {})
        self.put(key, arrays, meta)
        return {name: np.asarray(a) for name, a in arrays.items()}

    # ------------------------------------------------------------- housekeeping
    def entries(self) -> list[Path]:
        """The entry files of this version, oldest (least recently used) first."""
        try:
            found = [(e.stat().st_mtime, Path(e.path)) for e in os.scandir(self.path)
                     if _ENTRY.fullmatch(e.name) and e.is_file()]
        except FileNotFoundError:
            return []
        return [p for _, p in sorted(found)]

    def clear(self, all_versions: bool = False) -> int:
        """Delete every entry (of every version with ``all_versions``); the number deleted."""
        folders = [self.path]
        if all_versions and self.root.is_dir():
            folders = [p for p in self.root.iterdir() if p.is_dir() and _VERSION_DIR.fullmatch(p.name)]
        count = 0
        for folder in folders:
            for p in folder.glob("*"):
                if _ENTRY.fullmatch(p.name) or _TMP.fullmatch(p.name):
                    count += self._remove(p) and p.suffix == _SUFFIX
        return count

    def _evict(self) -> tuple[int, int]:
        """Scan the folder: delete stale temporary files and, when the entries pass a bound,
        the least recently used ones down to ``LOW_WATER`` of the bounds. Returns the
        entries and bytes left."""
        try:
            scan = list(os.scandir(self.path))
        except OSError:
            return 0, 0
        now, items = time.time(), []
        for e in scan:
            try:
                st = e.stat()
            except OSError:
                continue
            if _TMP.fullmatch(e.name) and now - st.st_mtime > _TMP_MAX_AGE:
                self._remove(Path(e.path))
            elif _ENTRY.fullmatch(e.name):
                items.append((st.st_mtime, st.st_size, Path(e.path)))
        items.sort()
        total = sum(size for _, size, _ in items)
        if self._over(len(items), total, 1.0):
            while items and self._over(len(items), total, LOW_WATER):
                _, size, path = items.pop(0)
                self._remove(path)
                total -= size
        return len(items), total

    @staticmethod
    def _remove(path: Path) -> bool:
        try:
            path.unlink()
            return True
        except OSError:
            return False

    @staticmethod
    def _touch(path: Path) -> None:
        try:
            os.utime(path)
        except OSError:
            pass
