"""One entry of the on-disk cache (``model.runs.cache``), read as untrusted input: only a
regular file, at most ``limit`` bytes, its ``.npz`` members unpacked only when their
declared sizes fit, no Python objects; and the checksum that binds its arrays to its key.
"""
from __future__ import annotations

import hashlib
import io
import math
import os
import stat
import zipfile
from pathlib import Path

import numpy as np

#: Largest entry read or written, in bytes, on disk and unpacked. The model's entries are
#: rows of scalars (a few kB); the bound only stops a planted file from filling memory.
MAX_ENTRY_BYTES = 16 * 1024**2
#: ``numpy.lib.format`` readers of the ``.npy`` header versions ``numpy.savez`` writes.
_NPY_HEADERS = {(1, 0): np.lib.format.read_array_header_1_0,
                (2, 0): np.lib.format.read_array_header_2_0}
_OPEN_FLAGS = (os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOFOLLOW", 0)
               | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))


class CorruptEntry(Exception):
    """A cache file that must not be returned (corrupted, truncated or stale)."""


def checksum(arrays: dict, key_json: str, meta_json: str, version: str) -> str:
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


def read_regular(path: Path, limit: int) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes.

    Opened without following a symbolic link and without blocking (a named pipe with no
    writer would otherwise hang the reader), then checked on the open descriptor."""
    fd = os.open(path, _OPEN_FLAGS)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise CorruptEntry(f"not a regular file (mode {stat.filemode(info.st_mode)})")
        if info.st_size > limit:
            raise CorruptEntry(f"{info.st_size} bytes, more than the {limit} allowed")
        with os.fdopen(os.dup(fd), "rb") as f:
            data = f.read(info.st_size + 1)  # read(n) allocates n bytes up front
    finally:
        os.close(fd)
    if len(data) > info.st_size:
        raise CorruptEntry("grew while read")
    return data


def unpack(data: bytes, limit: int) -> dict:
    """The arrays of an ``.npz`` archive held in ``data``, unpacking at most ``limit`` bytes.

    The declared sizes are checked before anything is decompressed, each member is read
    only up to its declared size, and each array only from an ``.npy`` header whose shape
    and dtype match the bytes that follow (no object arrays, nothing allocated from a
    header alone)."""
    arrays = {}
    with zipfile.ZipFile(io.BytesIO(data)) as archive:
        members = archive.infolist()
        declared = sum(m.file_size for m in members)
        if declared > limit:
            raise CorruptEntry(f"its arrays declare {declared} bytes, more than the {limit} "
                               "allowed")
        for member in members:
            if not member.filename.endswith(".npy") or member.is_dir():
                raise CorruptEntry(f"unexpected member {member.filename!r}")
            with archive.open(member) as f:
                raw = bytearray(f.read(member.file_size + 1))
            if len(raw) != member.file_size:
                raise CorruptEntry(f"member {member.filename!r} is not its declared size")
            arrays[member.filename[:-4]] = npy_array(raw, member.filename)
    return arrays


def npy_array(raw: bytearray, name: str) -> np.ndarray:
    """One array from the bytes of an ``.npy`` file (a writable view of ``raw``)."""
    buf = io.BytesIO(raw)
    version = np.lib.format.read_magic(buf)
    if version not in _NPY_HEADERS:
        raise CorruptEntry(f"member {name!r} has .npy version {version}")
    shape, fortran, dtype = _NPY_HEADERS[version](buf)
    if dtype.hasobject:
        raise CorruptEntry(f"member {name!r} holds Python objects")
    count = math.prod(shape)
    offset = buf.tell()
    if count * dtype.itemsize != len(raw) - offset:
        raise CorruptEntry(f"member {name!r}: shape {shape} of {dtype} does not match its "
                           f"{len(raw) - offset} bytes")
    array = np.frombuffer(raw, dtype=dtype, count=count, offset=offset)
    return array.reshape(shape, order="F" if fortran else "C")
