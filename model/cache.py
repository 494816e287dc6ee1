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
* an ``OSError`` on write (read-only folder, full disk) turns writing to that folder
  off for the rest of the process, with one logged warning instead of raising (a sweep
  makes a ``DiskCache`` per point: still one warning); a folder that cannot exist (its
  parent is a file) is a miss on read;
* the folder is bounded (``max_entries``, ``max_bytes``): the least recently used
  entries (oldest mtime; a hit refreshes it) are evicted.

    >>> cache = DiskCache()
    >>> arrays = cache.get_or_compute(make_key("uniform_array", params=p, tol=1e-3),
    ...                               lambda: {"F": np.array([1.0])})
"""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import logging
import os
import re
import tempfile
import time
from pathlib import Path

import numpy as np

__all__ = ["DiskCache", "make_key", "key_digest", "canonical_json", "default_directory"]

log = logging.getLogger(__name__)

ENV_VAR = "MICROPILLAR_CACHE_DIR"
APP_NAME = "micropillar-friction"
_RESERVED = ("__key__", "__meta__", "__version__", "__checksum__")
_SUFFIX, _TMP_SUFFIX = ".npz", ".tmp"
_TMP_MAX_AGE = 3600.0  # seconds before an orphaned temporary file is removed
_ENTRY = re.compile(r"[0-9a-f]{64}\.npz")
_TMP = re.compile(r"[0-9a-f]{16}\..*\.tmp")
_VERSION_DIR = re.compile(r"v\d[\w.+-]*")
#: Folders found not writable in this process: no ``DiskCache`` writes there again.
_UNWRITABLE: set[Path] = set()


def package_version() -> str:
    """The version of the ``model`` package (read lazily to avoid an import cycle)."""
    try:
        from . import __version__
    except ImportError:  # called while ``model`` itself is still being imported
        from importlib.metadata import version

        return version(APP_NAME)
    return __version__


def default_directory() -> Path:
    """Root of the cache: ``$MICROPILLAR_CACHE_DIR`` or the user cache directory."""
    env = os.environ.get(ENV_VAR)
    if env:
        return Path(env).expanduser()
    import platformdirs

    return Path(platformdirs.user_cache_dir(APP_NAME))


def _jsonable(obj):
    """JSON fallback for numpy scalars/arrays, dataclasses (Params, SolverOptions), tuples."""
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {"__type__": type(obj).__name__, **dataclasses.asdict(obj)}
    raise TypeError(f"cache key part {obj!r} of type {type(obj).__name__} is not JSON-serialisable")


def canonical_json(obj) -> str:
    """Canonical JSON text: sorted keys, no spaces, NaN/inf refused."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False,
                      default=_jsonable)


def key_digest(key: dict, version: str) -> str:
    """sha256 (hex) of the canonical JSON of the key together with the package version."""
    text = canonical_json({"key": key, "version": version})
    return hashlib.sha256(text.encode()).hexdigest()


#: Subpackages that only gather, tabulate or parse what the model computed.
PRESENTATION = ("reproduce", "cli")


@functools.lru_cache(maxsize=1)
def code_digest() -> str:
    """sha256 of the model package's Python sources: results change when the code does,
    even between released versions (an edited checkout), so the code is part of every key.

    The reproduction and command-line layers (``PRESENTATION``) compute nothing that is
    cached, so editing a report does not throw away hours of sweep points."""
    root = Path(__file__).parent
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        if path.relative_to(root).parts[0] in PRESENTATION:
            continue
        h.update(path.relative_to(root).as_posix().encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def make_key(function: str, **parts) -> dict:
    """A cache key: the function name, its parameters and settings, the package version
    and the digest of the model's code."""
    return {"function": function, "version": package_version(), "code": code_digest(), **parts}


def _checksum(arrays: dict, key_json: str, meta_json: str, version: str) -> str:
    """sha256 over the key, metadata, version and every array's name, dtype, shape and bytes."""
    h = hashlib.sha256()
    for text in (key_json, meta_json, version):
        h.update(text.encode())
        h.update(b"\0")
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()


class CorruptEntry(Exception):
    """A cache file that must not be returned (corrupted, truncated or stale)."""


class DiskCache:
    """Cache of dicts of numpy arrays keyed by JSON-serialisable dicts (see module doc)."""

    def __init__(self, directory=None, max_entries: int = 10_000,
                 max_bytes: int | None = 2 * 1024**3, version: str | None = None):
        self.version = version or package_version()
        self.root = Path(directory).expanduser() if directory is not None else default_directory()
        self.path = self.root / f"v{self.version}"
        self.max_entries = int(max_entries)
        self.max_bytes = None if max_bytes is None else int(max_bytes)
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
        except (FileNotFoundError, NotADirectoryError):
            return None
        except Exception as exc:  # anything unreadable is discarded, never returned
            log.warning("cache file %s is invalid (%s); discarding it and recomputing", path, exc)
            self._remove(path)
            return None
        self._touch(path)
        return entry

    def _read(self, path: Path, key_json: str) -> tuple[dict, dict]:
        with np.load(path, allow_pickle=False) as npz:
            missing = [name for name in _RESERVED if name not in npz.files]
            if missing:
                raise CorruptEntry(f"missing {', '.join(missing)}")
            stored = {name: str(npz[name][()]) for name in _RESERVED}
            arrays = {name: npz[name] for name in npz.files if name not in _RESERVED}
        if stored["__version__"] != self.version:
            raise CorruptEntry(f"stale: written by version {stored['__version__']}, "
                               f"this is {self.version}")
        if stored["__key__"] != key_json:
            raise CorruptEntry("stale: the stored key differs from the requested key")
        check = _checksum(arrays, stored["__key__"], stored["__meta__"], stored["__version__"])
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
        try:
            self.path.mkdir(parents=True, exist_ok=True)
            self._write_atomic(self.file_for(key), payload)
        except OSError as exc:
            self.writable = False
            if self.path not in _UNWRITABLE:
                _UNWRITABLE.add(self.path)
                log.warning("disk cache %s is not writable (%s); continuing without a disk "
                            "cache", self.path, exc)
            return False
        self._evict()
        return True

    def _payload(self, key, arrays, meta) -> dict:
        arrays = {name: np.asarray(a) for name, a in arrays.items()}
        for name, a in arrays.items():
            if not isinstance(name, str) or not name or name in _RESERVED:
                raise ValueError(f"array name {name!r} is empty, not a string or reserved")
            if a.dtype.hasobject:
                raise TypeError(f"array {name!r} has dtype object; only plain numpy dtypes are cached")
        key_json, meta_json = canonical_json(key), canonical_json(meta)
        check = _checksum(arrays, key_json, meta_json, self.version)
        return {**arrays, "__key__": np.array(key_json), "__meta__": np.array(meta_json),
                "__version__": np.array(self.version), "__checksum__": np.array(check)}

    def _write_atomic(self, path: Path, payload: dict) -> None:
        fd, tmp = tempfile.mkstemp(prefix=path.stem[:16] + ".", suffix=_TMP_SUFFIX, dir=self.path)
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, allow_pickle=False, **payload)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, path)
        except BaseException:
            self._remove(Path(tmp))
            raise

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

    def _evict(self) -> None:
        """Delete least recently used entries beyond the bounds, and stale temporary files."""
        try:
            scan = list(os.scandir(self.path))
        except OSError:
            return
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
        while items and (len(items) > self.max_entries
                         or (self.max_bytes is not None and total > self.max_bytes)):
            _, size, path = items.pop(0)
            self._remove(path)
            total -= size

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
