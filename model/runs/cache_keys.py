"""Keys of the on-disk cache (``model.runs.cache``): canonical JSON of what a result depends
on -- the function, its parameters and settings, the package version and a digest of the
model's code -- and its sha256."""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
from pathlib import Path

import numpy as np

from .._version import __version__

APP_NAME = "micropillar-friction"


def package_version() -> str:
    """The version of the ``model`` package."""
    return __version__


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
    root = Path(__file__).parents[1]  # the model package
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
