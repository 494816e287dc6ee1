"""Writing result files safely: a reader sees the old file or the complete new one."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["write_atomic", "write_text_atomic"]


def write_atomic(path, write) -> None:
    """``write(temporary_path)`` into a new file beside ``path``, then moved onto ``path``
    in one step (``os.replace``): readers see the old file or the complete new one, never
    a partial file, and a failed or interrupted write leaves ``path`` as it was."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # the mode open() would give a new file
        write(Path(tmp))
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text_atomic(path, text: str) -> None:
    """``Path.write_text`` (UTF-8), atomically as ``write_atomic``."""
    write_atomic(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
